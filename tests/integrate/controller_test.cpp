// The step-size control's error norm (integrate/controller.hpp): a component the problem holds
// each on its own (OdeProblem::held_each) counts at the full tolerance, not in the state norm's
// mean 10 times looser; the belt holds so its LuGre bristles' deflections and nothing else.
#include "integrate/controller.hpp"

#include <gtest/gtest.h>

#include <Eigen/Core>

#include "integrate/belt_problem.hpp"
#include "model/forces.hpp"
#include "model/jacobian_check.hpp"
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

// The answer's first `count` quantities are those of the whole answer, and nothing past them is
// written: the automotive drive with its tensioner arm (four pulley speeds and the arm's angle,
// then four span tensions) in a running state, with an error vector of random entries. The
// interior check asks for the speeds and the arm only (StepController::interior_norm).
TEST(Controller, BeltAnswerCountWritesTheFirstQuantitiesOnly) {
  const Scene sc = build_scene(presets::automotive_tensioner());
  BeltProblem p(sc.model, sc.drive);
  p.set_spans(sc.route.span_middles());
  const Eigen::VectorXd y = test::running_state(sc, 0.1, 30.0, 4, 0.5);
  const Eigen::VectorXd e = 1e-4 * Eigen::VectorXd::Random(y.size());
  const int na = p.answer_size(), head = sc.model.n_p() + sc.model.n_arm() + sc.model.n_coupling();
  ASSERT_EQ(na - head, static_cast<int>(sc.route.spans.size()));
  ASSERT_GT(na - head, 1);
  Eigen::VectorXd a(na), da(na);
  p.answer(0.1, y.data(), a.data(), na);
  p.answer_error(0.1, y.data(), e.data(), da.data(), na);
  for (int count : {0, head, head + 1, na}) {
    Eigen::VectorXd b = Eigen::VectorXd::Constant(na, -7.0), db = b;
    p.answer(0.1, y.data(), b.data(), count);
    p.answer_error(0.1, y.data(), e.data(), db.data(), count);
    for (int k = 0; k < na; ++k) {
      EXPECT_EQ(b[k], k < count ? a[k] : -7.0) << "answer " << k << " of count " << count;
      EXPECT_EQ(db[k], k < count ? da[k] : -7.0) << "answer_error " << k << " of count " << count;
    }
  }
  // a span tension is the axial force of the SDE nearest the span's middle
  const std::vector<Vec2> mid = sc.route.span_middles();
  for (int k = 0; k < na - head; ++k)
    EXPECT_EQ(a[head + k], sde_axial_force(sc.model, y.data(), y.data() + sc.model.n_coord(),
                                           sde_nearest(sc.model, y.data(), mid[k])));
}

// sde_nearest over several points in one pass (more than one batch of eight) gives each point's own
// answer, the first SDE in index order among equally near ones: points at the span middles, at
// random, and halfway between two neighbouring SDE middles (a tie but for rounding)
TEST(Controller, NearestSdeOfSeveralPointsIsEachPointsOwn) {
  const Scene sc = build_scene(presets::automotive_tensioner());
  const Model& m = sc.model;
  const Eigen::VectorXd y = test::running_state(sc, 0.1, 30.0, 5, 0.5);
  const double* q = y.data();
  std::vector<Vec2> pts = sc.route.span_middles();
  for (int k = 0; k < 9; ++k) pts.push_back(0.2 * Vec2::Random());
  // SDE i's middle is between elements i - 1 and i; a point equidistant from SDE 11's and 12's
  auto middle = [&](int i) {
    const int a = (i + m.n_el() - 1) % m.n_el();
    return Vec2(0.5 * (q[3 * a] + q[3 * i]), 0.5 * (q[3 * a + 1] + q[3 * i + 1]));
  };
  const Vec2 c11 = middle(11), c12 = middle(12);
  pts.push_back(0.5 * (c11 + c12));
  std::vector<int> out(pts.size(), -1);
  sde_nearest(m, q, pts.data(), static_cast<int>(pts.size()), out.data());
  for (size_t k = 0; k < pts.size(); ++k) {
    int best = 0;
    double bd = (middle(0) - pts[k]).squaredNorm();
    for (int i = 1; i < m.n_el(); ++i)
      if ((middle(i) - pts[k]).squaredNorm() < bd) bd = (middle(i) - pts[k]).squaredNorm(), best = i;
    EXPECT_EQ(out[k], best) << "point " << k;
    EXPECT_EQ(out[k], sde_nearest(m, q, pts[k])) << "point " << k;
  }
  // the halfway point: SDE 11 or 12, never another
  EXPECT_TRUE(out.back() == 11 || out.back() == 12) << out.back();
}

}  // namespace
}  // namespace beltsim
