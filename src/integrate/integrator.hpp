// An integrator in its live form: it advances by steps of its own choosing and keeps the last
// step for dense output, so a caller can read the solution at any time inside that step (a
// sample, a frame, a pause) without shortening a step. The schedule of what happens when
// (integrate/timeline.hpp) is the same for every integrator; only this interface differs.
//
//   start(t, y)   (re)start at (t, y): a change of the right-hand side at t (a wetted stretch,
//                 a new torque law) or the first start; any step beyond t is discarded
//   step(t_land)  one accepted step from t() onwards; a step that would reach t_land lands on it
//                 exactly (a kink or jump of the model's laws at a known time)
//   kink()        the solution passed a known kink at t() with no change of the system: a
//                 multistep method restarts its history, a one-step method needs nothing
//   dense(t, out) the solution at t_prev() <= t <= t()
//   y_prev(), y() the solution at the ends of the last step, where the stage equations hold
#pragma once

#include <limits>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "integrate/controller.hpp"
#include "integrate/system.hpp"

namespace beltsim {

// A run that could not continue: NaN/Inf, runaway, or a step size that collapsed. `t` is the time
// of the run's state when it stopped: its last accepted step's (end.t in parameters.csv), which
// every such message names as the time it stopped at.
struct DivergenceError : std::runtime_error {
  DivergenceError(double time, const std::string& what) : std::runtime_error(what), t(time) {}
  double t;
};

// The message of a step from t (the last accepted state, where the run stops) to t1 whose result
// fails the state's check (`bad`: "pulley 'driven' runs away at -100451 rad/s"): "the run diverged
// at t = <t> s: <bad> in the step to t = <t1> s" (no comma: the note is a cell of parameters.csv). The two times used
// to be told apart by nothing: the message named t1 alone, where the state that ran away was, while end.t was t (trial
// 16).
std::string diverged_text(double t, double t1, const std::string& bad);

// the advice every message of a run that diverged or made no progress ends with: an explicit method
// (rkf45) is told of the implicit ones; an implicit one (all others) has already tried that
inline std::string divergence_hint(bool implicit) {
  return implicit ? "check the scene's largest values (a torque, a stiffness or a speed far beyond the drive's), or "
                    "give that component more damping; a looser rtol or atol may carry the run past it"
                  : "try an implicit integrator (trbdf2, the default), a looser rtol or atol, or more damping of "
                    "that component";
}

// A part of a run's state that does not fit what it is set into (another method's, a state of
// another size, a time outside the held step): `key` names the field as a checkpoint writes it
// ("integrator.t"), the message says why. Nothing was changed.
struct StateError : std::invalid_argument {
  StateError(std::string field, const std::string& what) : std::invalid_argument(what), key(std::move(field)) {}
  std::string key;
};

// A one-step integrator's state between steps, as plain data (Integrator::get_state): what a
// continuation needs to take the same steps, bit for bit, as the run it was taken from
// (sim/state_io.hpp writes it into checkpoints).
struct IntegratorState {
  std::string method;                                      // the stepper's name: a state fits only its own method
  double t = 0, t_prev = 0;                                // [s] the held step
  Eigen::VectorXd y, f, y_prev, f_prev;                    // the solution and its derivative at the step's two ends
  std::vector<double> interior_c;           // the nodes inside the held step, in (0, 1) (Stepper::interior)
  std::vector<Eigen::VectorXd> interior;    // the states there
  double h = 0;                                            // [s] the next step's size
  double h_used = 0;                                       // [s] the last step's
  double h_cap = std::numeric_limits<double>::infinity();  // [s] the cap after a step that failed
  bool started = false;
  int worst = -1;            // the component with the largest error in the last estimate (-1: none)
  long at_floor = 0;         // accepted steps in a row at the rounding floor of t
  long failed_in_a_row = 0;  // implicit iterations in a row that did not converge
  WorkCounters counters;     // the system's counts and warnings so far
};

class Integrator {
 public:
  virtual ~Integrator() = default;
  virtual std::string name() const = 0;
  virtual bool implicit() const { return true; }  // false: an explicit method (rkf45)
  virtual void start(double t, const Eigen::VectorXd& y) = 0;
  virtual void step(double t_land) = 0;  // throws DivergenceError
  virtual void kink() {}
  virtual void dense(double t, Eigen::VectorXd& out) const = 0;
  virtual WorkCounters work() const = 0;
  // the component with the largest error in the last error estimate (OdeProblem::describe), for
  // the messages of a run that makes no progress; "" when the method does not say
  virtual std::string stiffest() const { return ""; }
  // checkpoints (bit-identical continuation); false when the method cannot export its state
  virtual bool can_save() const { return false; }
  // its state (can_save only: std::logic_error otherwise), and a state set back: set_state
  // refuses one that does not fit the method or the system (StateError, nothing changed)
  virtual IntegratorState get_state() const { throw std::logic_error(name() + " cannot export its state"); }
  virtual void set_state(const IntegratorState&) { throw std::logic_error(name() + " cannot take a state"); }

  double t() const { return t_; }
  double t_prev() const { return t_prev_; }
  const Eigen::VectorXd& y() const { return y_; }
  const Eigen::VectorXd& y_prev() const { return y_prev_; }  // the state at t_prev()

 protected:
  double t_ = 0, t_prev_ = 0;
  Eigen::VectorXd y_, y_prev_;
};

class Stepper;
// a one-step method the caller owns (tests with their own tableaux)
std::unique_ptr<Integrator> make_one_step(Stepper& stepper, const OdeSystem& sys, const Tolerances& tol,
                                          double h_max = 0);
// a one-step method the integrator owns
std::unique_ptr<Integrator> make_one_step(std::unique_ptr<Stepper> stepper, const OdeSystem& sys,
                                          const Tolerances& tol, double h_max = 0);

// The smallest rtol a run accepts. Below it the arithmetic cannot honour the tolerance: the implicit
// stages stop their Newton iteration at 1 % of it, and the state's own rounding (double precision,
// 2.2e-16 of each value) is then a sizeable part of that, so the error estimate does not fall as the
// step shrinks and the run takes ever shorter steps without end.
constexpr double kRtolMin = 1e-12;
// what is wrong with rtol as a relative tolerance ("" when nothing): the one rule for every reader
std::string rtol_problem(double rtol);
// what is wrong with atol as a given absolute tolerance ("" when nothing): the one rule for every reader
std::string atol_problem(double atol);
// checks rtol (rtol_problem) and atol (Tolerances::kAtolUnset: same as rtol; else atol_problem);
// throws std::invalid_argument
void check_tolerances(const Tolerances& tol);

// cubic Hermite interpolation on [t0, t0 + h]
void hermite(double theta, double h, const Eigen::VectorXd& y0, const Eigen::VectorXd& f0,
             const Eigen::VectorXd& y1, const Eigen::VectorXd& f1, Eigen::VectorXd& out);

}  // namespace beltsim
