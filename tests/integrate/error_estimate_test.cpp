// What the step-size control rests on, for every one-step method (docs/accuracy.md, "The
// accuracy contract"):
//   - the embedded estimate measures the true local error: from the exact solution at t0, one step
//     of h; the estimate's ratio to the true error of the solution the estimate is of (the
//     propagated one when it is the lower order of the pair, the embedded one, y1 - err, when the
//     method propagates the higher) lies in [0.3, 3], and the estimate falls as h^(p̂+1), p̂ the
//     lower order of the pair (its log-slope over h = 0.04 ... 0.01 within 0.3 of p̂ + 1);
//   - on the stiff Prothero–Robinson problem y' = λ(y - sin t) + cos t at λ = -1e6 the L-stable
//     methods' filtered estimate stays within a factor 3 of the true error;
//   - run under the controller, the global error follows the tolerance: the slope of log(error)
//     against log(rtol) over rtol = 1e-3 ... 1e-6 is at least 0.8 (a method that propagates the
//     lower order of its pair reaches it through StepController's tolerance proportionality).
// Problem: integrate/smooth_problem.hpp.
#include <gtest/gtest.h>

#include <cmath>

#include <Eigen/Dense>

#include "integrate/controller.hpp"
#include "integrate/integrator.hpp"
#include "integrate/make_integrator.hpp"
#include "integrate/stepper.hpp"
#include "integrate/smooth_problem.hpp"

namespace beltsim {
namespace {

using test::SmoothProblem;

struct OneStepErrors {
  double estimate, truth;
};

OneStepErrors one_step(const std::string& method, double lambda, double h) {
  SmoothProblem sys(lambda);
  auto st = make_stepper(method);
  const StepController ctl(sys, Tolerances{1e-10, 1e-10}, 3);
  st->attach(ctl);
  const double t0 = 0.3;
  Eigen::VectorXd y = SmoothProblem::exact(t0), f(3), y1(3), err(3);
  sys.rhs(t0, y.data(), f.data());
  EXPECT_TRUE(st->step(sys, t0, y, f, h, y1, err));
  // the estimate is of the lower-order solution of the pair
  const bool propagates_higher = st->order() > st->embedded_order();
  const Eigen::VectorXd of = propagates_higher ? Eigen::VectorXd(y1 - err) : y1;
  return {err.cwiseAbs().maxCoeff(), (of - SmoothProblem::exact(t0 + h)).cwiseAbs().maxCoeff()};
}

class EstimateOf : public ::testing::TestWithParam<std::string> {};

TEST_P(EstimateOf, ItsLocalErrorOnASmoothProblem) {
  auto st = make_stepper(GetParam());
  const int p_hat = std::min(st->order(), st->embedded_order());
  std::vector<double> est;
  for (double h : {0.04, 0.02, 0.01}) {
    const OneStepErrors e = one_step(GetParam(), -1.0, h);
    EXPECT_GE(e.estimate / e.truth, 0.3) << "h = " << h << ": estimate " << e.estimate << ", true " << e.truth;
    EXPECT_LE(e.estimate / e.truth, 3.0) << "h = " << h << ": estimate " << e.estimate << ", true " << e.truth;
    est.push_back(e.estimate);
  }
  EXPECT_NEAR(std::log2(est[0] / est[2]) / 2, p_hat + 1, 0.3) << "the estimate's order";
}

TEST_P(EstimateOf, ItsLocalErrorOnAStiffProblem) {
  if (GetParam() == "rkf45") GTEST_SKIP() << "explicit: unstable at h·λ = -1e4";
  for (double h : {0.04, 0.01}) {
    const OneStepErrors e = one_step(GetParam(), -1e6, h);
    EXPECT_GE(e.estimate / e.truth, 0.3) << "h = " << h << ": estimate " << e.estimate << ", true " << e.truth;
    EXPECT_LE(e.estimate / e.truth, 3.0) << "h = " << h << ": estimate " << e.estimate << ", true " << e.truth;
  }
}

// the controlled run's global error at t = 2 against rtol (= atol)
double global_error(const std::string& method, double lambda, double rtol) {
  SmoothProblem sys(lambda);
  auto integ = make_integrator(method, sys, Tolerances{rtol, rtol});
  integ->start(0, SmoothProblem::exact(0));
  while (integ->t() < 2.0) integ->step(2.0);
  Eigen::VectorXd y(3);
  integ->dense(2.0, y);
  return (y - SmoothProblem::exact(2.0)).cwiseAbs().maxCoeff();
}

TEST_P(EstimateOf, ControlsTheGlobalError) {
  for (double lambda : {-1.0, -1e6}) {
    if (lambda < -1 && GetParam() == "rkf45") continue;
    std::vector<double> err;
    const std::vector<double> rtols{1e-3, 1e-4, 1e-5, 1e-6};
    for (double r : rtols) err.push_back(global_error(GetParam(), lambda, r));
    const double slope = std::log(err.front() / err.back()) / std::log(rtols.front() / rtols.back());
    EXPECT_GE(slope, 0.8) << "λ = " << lambda << ": errors " << err[0] << " ... " << err[3];
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, EstimateOf, ::testing::Values("esdirk32", "trbdf2", "ros34pw2", "rkf45"),
                         [](const auto& param_info) { return param_info.param; });

}  // namespace
}  // namespace beltsim
