// Each integrator reaches its order on a smooth problem with a known solution.
// Problem: a harmonic oscillator y1' = y2, y2' = -y1 and a Prothero–Robinson component
// y3' = λ·(y3 - sin t) + cos t (non-autonomous, so the ∂F/∂t terms of the Rosenbrock method are
// exercised); exact solution (cos t, -sin t, sin t). Fixed steps h = 1/10 ... 1/160 to t = 1;
// the observed order log2(e(h)/e(h/2)) over the last halvings must be within 0.25 of the
// method's order (the asymptotic regime is reached by h = 1/40 for all three, measured).
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
