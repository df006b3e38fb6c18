// Steppers: one step of a method and its error estimate, nothing else (odeint's split of
// stepper / controller / driver). Butcher and Rosenbrock tables are data in tableau.cpp.
#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "integrate/system.hpp"

namespace beltsim {

class StepController;

class Stepper {
 public:
  virtual ~Stepper() = default;
  virtual std::string name() const = 0;
  virtual int order() const = 0;            // of the propagated solution
  virtual int embedded_order() const = 0;   // of the error estimate's companion
  // implicit methods measure their iterations in the controller's weighted norm
  virtual void attach(const StepController&) {}
  // linearly implicit methods solve with the system's LinearSolver (an integrator refuses a
  // system without one); explicit methods read only the problem
  virtual bool needs_linear_solver() const { return false; }
  // L-stable: a component far faster than the step is damped, not carried (its error dies out
  // within the step). Only such a method may leave a problem's fast components out of the state
  // norm (OdeProblem::in_state_norm): an explicit method's error in them would grow unseen.
  virtual bool l_stable() const { return false; }
  // One step of size h from (t, y) with f0 = F(t, y). Writes y1 and the error estimate err.
  // Returns false when the step cannot be taken at all (e.g. a singular matrix): the driver
  // then shrinks h as for a rejected step.
  virtual bool step(const OdeSystem& sys, double t, const Eigen::VectorXd& y, const Eigen::VectorXd& f0, double h,
                    Eigen::VectorXd& y1, Eigen::VectorXd& err) = 0;
  // after step(): the longest step the method can take from here and stay faithful to what
  // grows (NewtonAids::unstable_rate); infinity when nothing bounds it. A step refused (false)
  // with h above it was refused for that alone: the driver retries at this size
  virtual double h_limit() const { return std::numeric_limits<double>::infinity(); }
  // after a step that returned true: the states the method solved for inside it, Z[i] at
  // t + c[i]·h with 0 < c[i] < 1 (an implicit method's stage values), for a dense output through
  // states alone (OneStep); none by default
  virtual void interior(std::vector<double>& c, std::vector<Eigen::VectorXd>& Z) const {
    c.clear();
    Z.clear();
  }
  // after a step that returned true, with its t, y and h: the estimated error e of the dense
  // output at t + c·h, where it reads the state Z (the driver holds the answer there to the
  // tolerance as at the step's end: StepController::interior_norm); false when the method
  // estimates none
  virtual bool interior_error(const OdeSystem& sys, double t, const Eigen::VectorXd& y, double h, double& c,
                              const Eigen::VectorXd*& Z, const Eigen::VectorXd*& e) {
    (void)sys, (void)t, (void)y, (void)h, (void)c, (void)Z, (void)e;
    return false;
  }
};

// "esdirk32" (L-stable ESDIRK 3(2) with semi-smooth Newton, Kennedy & Carpenter 2003),
// "trbdf2" (TR-BDF2 as an ESDIRK, Hosea & Shampine 1996), "rkf45" (the paper's
// Runge–Kutta–Fehlberg 4(5)) or "ros34pw2" (L-stable Rosenbrock–W 3(2), Rang & Angermann 2005);
// throws std::invalid_argument listing the valid names otherwise
std::unique_ptr<Stepper> make_stepper(const std::string& name);
std::vector<std::string> stepper_names();
// every integrator a run accepts: the steppers and the CVODE peers ("cvode", "cvode-fd",
// integrate/cvode.hpp); integrator_problem says why a name is none of them ("unknown integrator
// 'x' (valid: ...)", "" when it is one), check_integrator throws it (std::invalid_argument)
std::vector<std::string> integrator_names();
std::string integrator_problem(const std::string& name);
void check_integrator(const std::string& name);
// why a run by this integrator at rtol may miss the accuracy contract (the pulley speeds within
// 3·rtol and the span tensions within 10·rtol of the converged answer; docs/accuracy.md), as
// measured; "" where it keeps it (trbdf2; the CVODE peers from rtol 1e-3 up)
std::string contract_miss(const std::string& name, double rtol);
// why the energy.* columns of a run by this integrator do not balance (the torques' work against
// the mechanical energy's change and the dissipation integrals), as measured; "" where they do
// (within about the tolerance: trbdf2, esdirk32 and the CVODE peers)
std::string energy_miss(const std::string& name);

}  // namespace beltsim
