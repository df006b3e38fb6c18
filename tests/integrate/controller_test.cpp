// The step-size control's error norm (integrate/controller.hpp): a component the problem holds
// each on its own (OdeProblem::held_each) counts at the full tolerance, not in the state norm's
// mean 10 times looser; the belt holds so its LuGre bristles' deflections and nothing else.
#include "integrate/controller.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>

#include "integrate/belt_problem.hpp"
#include "support/presets.hpp"

namespace beltsim {
namespace {

// y' = 0 on n components, with one answer quantity (component 0) and component `held` held each
// on its own when `hold` is set
class HeldProblem final : public OdeProblem {
 public:
  HeldProblem(int n, int held, bool hold) : n_(n), held_(held), hold_(hold) {}
  int size() const override { return n_; }
  void rhs(double, const double*, double* dy) override {
    for (int k = 0; k < n_; ++k) dy[k] = 0;
  }
  int answer_size() const override { return 1; }
  void answer(double, const double* y, double* a, int) override { a[0] = y[0]; }
  void answer_error(double, const double*, const double* e, double* da, int) override { da[0] = e[0]; }
  bool held_each(int k) const override { return hold_ && k == held_; }

 private:
  int n_, held_;
  bool hold_;
};

// One component of 1 000 with an error twice its weight w = atol + rtol·|y| (y = 0: w = atol):
// held on its own the norm is 2 (a rejected step); in the state norm, the root mean square over
// the 1 000 divided by the looseness, 2/√1000/10 = 6.3e-3 (accepted).
TEST(Controller, HoldsAHeldComponentAtTheFullTolerance) {
  const int n = 1000, k = 700;
  const double tol = 1e-3;
  Eigen::VectorXd y0 = Eigen::VectorXd::Zero(n), y1 = y0, err = Eigen::VectorXd::Zero(n);
  err[k] = 2 * tol;
  for (const bool hold : {true, false}) {
    HeldProblem sys(n, k, hold);
    StepController ctl(sys, Tolerances{tol, tol}, 2);
    const double e = ctl.error_norm(0.1, y0, y1, err);
    if (hold)
      EXPECT_DOUBLE_EQ(e, 2.0);
    else
      EXPECT_NEAR(e, 2.0 / std::sqrt(double(n)) / StepController::kStateLooseness, 1e-12);
  }
}

// The belt holds each LuGre bristle's deflection on its own, and no other component: under LuGre's
// law on the whole belt (the paper's dry drive with friction.law = lugre) one per element; under
// the paper's law none.
TEST(Controller, BeltHoldsTheLuGreBristlesOnly) {
  for (const bool lugre : {true, false}) {
    SceneDef d = presets::paper_dry();
    if (lugre) d.friction.law = FrictionKind::lugre;
    const Scene sc = build_scene(d);
    const Model& m = sc.model;
    BeltProblem p(m, sc.drive);
    int held = 0, held_before = 0;
    for (int k = 0; k < p.size(); ++k)
      if (p.held_each(k)) ++held, held_before += k < m.bristle_offset();
    EXPECT_EQ(held, lugre ? m.n_el() : 0) << (lugre ? "LuGre" : "Threlfall");
    EXPECT_EQ(held_before, 0);
  }
}

}  // namespace
}  // namespace beltsim
