// Step-size controller: the error norm of a step and the next step size. A rejected step is a
// status returned to the driver, not an exception.
//
// The error norm measures the answer users read, each quantity on its own, and the state as a
// whole more loosely:
//   w_k = atol·scale_k + rtol·max(|y0_k|, |y1_k|)          (state component k)
//   e_state  = sqrt(mean over the components in the state norm of (err_k/w_k)²)
//   W_a = atol·ascale_a + rtol·max(|A_a(y0)|, |A_a(y1)|)   (answer quantity a: OdeProblem::answer)
//   e_answer = max_a |δA_a| / W_a,   δA = A(y1) - A(y1 - err)
//   e_held   = max over the components held each on their own (OdeProblem::held_each) of |err_k|/w_k
//   ‖err‖ = max(e_answer, e_held, e_state / kStateLooseness)
//   h_new = h·min(grow, max(shrink, 0.7·‖err‖^(-1/(q+1))))   with q the lower of the two orders
// The mean over all the states lets one quantity's error be √n times the tolerance (a pulley's
// speed among 6n element states), and holds the element states, whose local vibration no output
// depends on, as tightly as the answer: e_answer holds each answer quantity to the tolerance, and
// the state norm keeps only what the iteration and the answer's future need (docs/integration.md,
// "Error control"). With an answer, the problem may leave components out of the state norm
// when its method is L-stable (OdeProblem::in_state_norm: the belt elements' velocities, as Adams' index-3 form leaves
// velocities out of its error test): an element vibrating at ω (rocking undamped at its bending
// frequency, bouncing on its contact spring) carries a velocity error ω times its position's, and a
// norm that holds that velocity holds the step to the vibration's period, which no answer depends
// on; the positions, held, bound what the velocity error carries, and the answer holds the pulley
// speeds and the span tensions, whose dampers read the elements' velocities.
// A problem without an answer is controlled by e_state alone, unscaled, over every component.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "integrate/system.hpp"

namespace beltsim {

struct Tolerances {
  static constexpr double kAtolUnset = -1;  // atol left out: the same as rtol
  double rtol = 1e-6;
  double atol = kAtolUnset;  // per unit of each component's natural size; kAtolUnset: same as rtol
  double absolute() const { return atol < 0 ? rtol : atol; }  // the atol in force
};

class StepController {
 public:
  // the factor by which the state's norm is looser than the answer's (when there is an answer)
  static constexpr double kStateLooseness = 10.0;

  // q: the lower order of the method's pair. p: the order of the solution a method propagates when
  // it is the lower of the pair (trbdf2, rkf45), else 0. Such a method's error per step, held to
  // the tolerance, adds up to a global error ∝ tol^(p/(p+1)), not ∝ tol: below kProportionalFrom
  // it runs at the tighter tolerance rtol·(rtol/kProportionalFrom)^(1/p) (atol likewise), so that
  // its global error falls in proportion to rtol (Hairer, Nørsett & Wanner I, II.4: tolerance
  // proportionality). At and above it, the rtol given.
  static constexpr double kProportionalFrom = 1e-4;
  // reduced: leave out of the state norm what the problem leaves out (OdeProblem::in_state_norm;
  // an L-stable method's controller)
  StepController(OdeProblem& sys, const Tolerances& tol, int q, int p = 0, bool reduced = false);
  // the error norm of a step from y0 to y1 at t1 with the error estimate err; worst: the state
  // component with the largest weighted error
  double error_norm(double t1, const Eigen::VectorXd& y0, const Eigen::VectorXd& y1, const Eigen::VectorXd& err,
                    int* worst = nullptr);
  // the error norm inside a step: at t + c·h, where the dense output reads the state Z with the
  // estimated error e, the largest of the answer's quantities checked inside a step
  // (OdeProblem::checked_inside), each against its tolerance as in error_norm; 0 without an answer
  double interior_norm(double t, const Eigen::VectorXd& y0, const Eigen::VectorXd& Z, const Eigen::VectorXd& e);
  double rtol() const { return rtol_; }  // the tolerance in force
  // next step size after a step with error norm e (accepted when e <= 1): at most kGrowMax·h
  double propose(double h, double e) const;
  static constexpr double kGrowMax = 5.0;
  // the state norm at the full tolerance (Newton's convergence test, the first step)
  double weighted_norm(const Eigen::VectorXd& y, const Eigen::VectorXd& v) const;

 private:
  OdeProblem& sys_;
  Eigen::VectorXd atol_;
  Eigen::VectorXd in_norm_;  // 1 for a component in the state norm, else 0
  double n_in_norm_ = 0;     // their number
  std::vector<int> held_;    // the components held each on their own (OdeProblem::held_each)
  std::vector<int> inside_;  // the answer's quantities checked inside a step (OdeProblem::checked_inside)
  Eigen::VectorXd aatol_, a0_, a1_, da_;  // the answer's atol, its values at y0 and y1, its error
  double rtol_;
  double exponent_;
};

}  // namespace beltsim
