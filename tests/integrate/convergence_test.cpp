// Each integrator reaches its order on a smooth problem with a known solution.
// Problem: a harmonic oscillator y1' = y2, y2' = -y1 and a Prothero–Robinson component
// y3' = λ·(y3 - sin t) + cos t (non-autonomous, so the ∂F/∂t terms of the Rosenbrock method are
// exercised); exact solution (cos t, -sin t, sin t). Fixed steps h = 1/10 ... 1/160 to t = 1;
// the observed order log2(e(h)/e(h/2)) over the last halvings must be within 0.25 of the
// method's order (the asymptotic regime is reached by h = 1/40 for all three, measured).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <limits>

#include "integrate/controller.hpp"
#include "integrate/integrator.hpp"
#include "integrate/make_integrator.hpp"
#include "integrate/smooth_problem.hpp"
#include "integrate/stepper.hpp"

namespace beltsim {
namespace {

// the problem and its own linear solver (dense 3x3)
using test::SmoothProblem;

double error_at_one(const std::string& method, int steps, double lambda) {
  SmoothProblem sys(lambda);
  auto st = make_stepper(method);
  const StepController ctl(sys, Tolerances{1e-13, 1e-13}, 3);
  st->attach(ctl);
  Eigen::VectorXd y(3), y1(3), err(3), f(3);
  y << 1, 0, 0;
  const double h = 1.0 / steps;
  for (int k = 0; k < steps; ++k) {
    const double t = k * h;
    sys.rhs(t, y.data(), f.data());
    EXPECT_TRUE(st->step(sys, t, y, f, h, y1, err));
    y = y1;
  }
  return (y - SmoothProblem::exact(1.0)).cwiseAbs().maxCoeff();
}

void expect_order(const std::string& method, int order) {
  double prev = error_at_one(method, 40, -1.0);
  for (int steps : {80, 160}) {
    const double e = error_at_one(method, steps, -1.0);
    const double observed = std::log2(prev / e);
    EXPECT_NEAR(observed, order, 0.25) << method << " at h = 1/" << steps;
    prev = e;
  }
}

TEST(Convergence, Rkf45IsFourthOrder) { expect_order("rkf45", 4); }
TEST(Convergence, Ros34pw2IsThirdOrder) { expect_order("ros34pw2", 3); }
TEST(Convergence, Esdirk32IsThirdOrder) { expect_order("esdirk32", 3); }
TEST(Convergence, Trbdf2IsSecondOrder) { expect_order("trbdf2", 2); }

// an integrator takes the problem alone for an explicit method and refuses it, naming the
// method, for one that solves linear systems; given the linear solver as well, it runs
TEST(Convergence, ImplicitMethodsNeedALinearSolver) {
  SmoothProblem sys(-1.0);
  const OdeSystem alone(static_cast<OdeProblem&>(sys), nullptr);
  const Tolerances tol{1e-6, 1e-6};
  EXPECT_NO_THROW(make_integrator("rkf45", alone, tol));
  for (const std::string name : {"esdirk32", "trbdf2", "ros34pw2", "cvode", "cvode-fd"}) {
    try {
      make_integrator(name, alone, tol);
      ADD_FAILURE() << name << ": no exception";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(name + " "), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("linear solver"), std::string::npos) << e.what();
    }
  }
  auto integ = make_integrator("esdirk32", sys, tol);
  Eigen::VectorXd y(3);
  y << 1, 0, 0;
  integ->start(0, y);
  integ->step(0.1);
  EXPECT_GT(integ->t(), 0.0);
}

// A run stopped at a step's end (a pause from the live page, Ctrl-C) is replayed as run_to(that
// time): the replay's last step must be the run's own, bit for bit. Landing on t it took
// h = t - t_prev, which differs from the step's own h where t_prev + h rounded: the stages then
// differ by an ulp, and on the belt the Newton iteration's path with them (a replay's
// timeseries.csv 1e-6 off, once under load, when the page paused between samples)
TEST(Convergence, LandingOnAStepsOwnEndTakesThatStep) {
  SmoothProblem sys(-1e3);
  const Tolerances tol{1e-5, 1e-5};
  for (const std::string name : {"trbdf2", "esdirk32", "rkf45"}) {
    auto free_run = make_integrator(name, sys, tol);
    Eigen::VectorXd y0(3);
    y0 << 1, 0, 0;
    free_run->start(0, y0);
    int differ = 0, compared = 0;
    double h_before = 0;           // the step before this one
    long rejected[3] = {0, 0, 0};  // the free run's rejections before the last two steps and now
    for (int k = 1; k <= 40; ++k) {
      free_run->step(std::numeric_limits<double>::infinity());
      const double h = free_run->t() - free_run->t_prev();
      rejected[0] = rejected[1], rejected[1] = rejected[2], rejected[2] = free_run->work().rejected;
      // Not compared: a step under a tenth of the one before (landing, that one is stretched onto
      // its end, one_step.cpp kLandStretch), and a step after a rejected attempt in the last two
      // (landing shortens the attempt that was rejected, which may then pass): paths of their own
      if (h > 0.1 * h_before && rejected[2] == rejected[0]) {
        // a fresh run of the same steps landing on this step's end
        auto landed = make_integrator(name, sys, tol);
        landed->start(0, y0);
        while (landed->t() < free_run->t()) landed->step(free_run->t());
        ASSERT_EQ(landed->t(), free_run->t()) << name << " step " << k;
        differ += landed->y() != free_run->y();
        ++compared;
      }
      h_before = h;
    }
    EXPECT_GE(compared, 10) << name;
    EXPECT_EQ(differ, 0) << name << ": of " << compared << " step ends landed on, " << differ
                         << " ended elsewhere in their bits";
  }
}

TEST(Convergence, UnknownIntegratorListsTheValidNames) {
  try {
    make_stepper("rk4");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("esdirk32"), std::string::npos);
  }
}

}  // namespace
}  // namespace beltsim
