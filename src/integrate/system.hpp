// The view of an ODE system that the integrators need, in the three parts SUNDIALS keeps apart
// (the problem given to CVodeInit, the SUNLinearSolver attached to the integrator, and the
// user's optional inputs):
//   OdeProblem    y' = F(t, y): its size, F, the scales of the tolerances, the kinks of a
//                 piecewise-smooth F, diagnostics, and the work counters
//   LinearSolver  for linearly implicit methods: J = ∂F/∂y at a point, the factorisation of the
//                 shifted matrix (s·I - J) and solves with it
//   NewtonAids    optional help for Newton's iteration on a piecewise-smooth F
// An integrator is given an OdeSystem: the problem, and where its method asks for them a linear
// solver (the implicit one-step methods, CVODE) and Newton aids (the ESDIRK methods).
#pragma once

#include <concepts>
#include <cstdint>
#include <limits>
#include <string>

#include <Eigen/SparseCore>

#include "integrate/warnings.hpp"

namespace beltsim {

struct WorkCounters {
  long steps = 0;        // accepted
  long rejected = 0;
  long rhs = 0;          // right-hand side evaluations
  long jacobians = 0;
  long factorizations = 0;
  long solves = 0;       // linear solves (one per implicit stage)
  long kink_restarts = 0;  // restarts of a multistep history at a located kink of F (CVODE's rootfinding)
  // the fallbacks the integrator took (integrate/warnings.hpp): steps that could not be taken,
  // CVODE's convergence failures and non-finite forces
  Warnings warnings;
};

// The problem y' = F(t, y).
class OdeProblem {
 public:
  virtual ~OdeProblem() = default;
  virtual int size() const = 0;
  virtual void rhs(double t, const double* y, double* dy) = 0;
  // absolute tolerance of component k per unit of atol (the natural size of that quantity)
  virtual double atol_scale(int) const { return 1.0; }

  // the largest error in component k that the right-hand side's piecewise laws can take without
  // changing piece at random (for the belt, a slip velocity error as large as the friction band);
  // infinite when there is no such scale
  virtual double resolution(int) const { return std::numeric_limits<double>::infinity(); }
  // switching functions, for integrators that locate the kinks of a piecewise-smooth F and
  // restart there: their number, and g at (t, y), each continuous in y and zero where F has a kink
  // (evaluated as F is: not const)
  virtual int switch_count() const { return 0; }
  virtual void switches(double, const double*, double*) {}
  // The answer: the quantities users read of a state (for the belt: the speeds of the pulleys,
  // arms and rotors and the span tensions), which the step-size control holds to the tolerance
  // each on its own (StepController). answer(t, y, a, count) writes the first count of them
  // (count <= answer_size()); answer_error(t, y, e, da, count) the change of each when the state y
  // moves by -e (the error estimate e of a step ending at y); answer_scale(k) is quantity k's
  // natural size, the unit of atol for it.
  virtual int answer_size() const { return 0; }
  virtual void answer(double, const double*, double*, int) {}
  virtual void answer_error(double, const double*, const double*, double*, int) {}
  virtual double answer_scale(int) const { return 1.0; }
  // whether component k's error counts in the state's part of the error norm beside the answer
  // (StepController; only when the problem has an answer)
  virtual bool in_state_norm(int) const { return true; }
  // whether component k's error is held on its own at the full tolerance, as an answer quantity's
  // is, rather than in the state norm (StepController; only when the problem has an answer)
  virtual bool held_each(int) const { return false; }
  // whether answer quantity k's error is also checked inside a step, where the dense output
  // gives what falls between step ends (samples among long steps, frames, pauses), besides at the
  // step's end (StepController::interior_norm)
  virtual bool checked_inside(int) const { return true; }
  virtual std::string describe_answer(int k) const { return "answer " + std::to_string(k); }

  // diagnostics: a name for component k ("element 12 y velocity") and a check of a state that
  // returns an empty string when it is sane, else what went wrong
  virtual std::string describe(int k) const { return "component " + std::to_string(k); }
  virtual std::string check(double, const double*) const { return {}; }
  // for the stop messages of a step that collapsed or an iteration that kept failing: an input of
  // the problem at (t, y) beyond what its own scales make plausible (an applied torque that no belt
  // could carry), named with its value and the scale, as the likely cause; empty when none
  virtual std::string absurd_input(double, const double*) const { return {}; }
  // absurd_input at t0 or else at t1 (a step that failed: its start, and its end for a law that
  // jumps inside it), both with the state y, as "<what>; " for a stop message, "" when neither
  std::string absurd_note(double t0, double t1, const double* y) const {
    for (const double t : {t0, t1})
      if (std::string a = absurd_input(t, y); !a.empty()) return a + "; ";
    return {};
  }

  // the work of the integrator that solves this problem, counted by the integrator (the stepper
  // counts its evaluations, Jacobians and solves, the driver its steps; CVODE's statistics are
  // copied here after every step), read after a run
  WorkCounters counters;
};

// The linear algebra of linearly implicit methods with J = ∂F/∂y of an OdeProblem.
class LinearSolver {
 public:
  virtual ~LinearSolver() = default;
  // evaluate J = ∂F/∂y and ∂F/∂t at (t, y); false when the solver cannot (a solver that only
  // gives the sparse Jacobian below)
  virtual bool prepare_jacobian(double, const double*) { return false; }
  virtual void time_derivative(double* f_t) const;  // ∂F/∂t at the prepared point (default 0)
  virtual bool factor(double) { return false; }     // factor (s·I - J); false when singular
  virtual void solve(const double* r, double* u) { (void)r, (void)u; }  // u = (s·I - J)^-1 r
  // the full J = ∂F/∂y as a sparse matrix with the same pattern every call (for the CVODE
  // peer's sparse direct solver); false when the solver has none
  virtual bool sparse_jacobian(double, const double*, Eigen::SparseMatrix<double>&) { return false; }
};

// Newton aids for a piecewise-smooth right-hand side; every one may do nothing (the defaults). They
// may evaluate the problem at the state they are given (none is const).
class NewtonAids {
 public:
  virtual ~NewtonAids() = default;
  // before the iterate z moves by the Newton correction dz, put what the correction would carry
  // across a branch onto it (see friction_reseat): by changing dz so that z + dz lands on it
  // (keep_correction), or by moving z itself onto it (the iteration then starts again from z).
  // True when it changed one.
  virtual bool reseat(double, double*, double*, bool) { return false; }
  // with G the stage residual Z - ψ - F(t, Z)/s at z, move z so that the stiffest local
  // equations hold (true when z moved)
  virtual bool local_solve(double, double, double*, const double*) { return false; }
  // Newton's starting point: carry the state z, taken at time t, forward by dt along the
  // motion it describes (the default leaves it where it is)
  virtual void predict(double, double, double*) {}
  // A hash of the smooth piece of a piecewise-smooth right-hand side that y lies on; 0 means
  // unknown. Newton may reuse a Jacobian (and its factorisation) while the hash is unchanged.
  virtual uint64_t branches(double, const double*) { return 0; }
  // how far the Newton correction dz from z carries the right-hand side past a kink, in units of
  // the kink's resolution (for the belt: slip velocities past the edge of the friction band, in
  // band widths); 0 when it leaves every law on the piece z lies on
  virtual double overshoot(double, const double*, const double*) { return 0; }
  // the fastest growth at z of a single variable with everything else held [1/s]: for the belt,
  // an element's slip velocity on a falling friction curve (see newton_aids.cpp, Falling
  // friction); 0 when nothing grows. An implicit stage with h·γ·rate > 1 has lost its solution's
  // growth and may sit on a root the motion never visits (esdirk.cpp)
  virtual double unstable_rate(double, const double*) { return 0; }
};

// What an integrator is given (none of it owned): the problem, and optionally a linear solver
// for it and Newton aids. The parts must outlive the integrator.
struct OdeSystem {
  // the problem p; p is also the linear solver, or the aids, when its class is one too (a small
  // problem that brings its own Jacobian)
  template <std::derived_from<OdeProblem> P>
  OdeSystem(P& p) : problem(&p) {
    if constexpr (std::derived_from<P, LinearSolver>) linear = &p;
    if constexpr (std::derived_from<P, NewtonAids>) aids = &p;
  }
  OdeSystem(OdeProblem& p, LinearSolver* ls, NewtonAids* a = nullptr) : problem(&p), linear(ls), aids(a) {}
  OdeProblem* problem;
  LinearSolver* linear = nullptr;
  NewtonAids* aids = nullptr;
};

}  // namespace beltsim
