// Pulley laws (model/laws.hpp): each term against its formula written out here (docs/lua-api.md's),
// the analytic derivatives against central differences of the value, sums, kinks and jumps.
//
// Tolerances. The values are sums of a few terms of size ≤ 100 evaluated in double precision:
// they agree with the formulas to rounding, ~1e-14 absolute (asked: 1e-12). The derivatives are
// compared with central differences at h = 1e-6 s (or rad/s) at points away from every kink:
// truncation h²·|f'''|/6 ≲ 1e-12·(2π·50)³·3/6 ≈ 2e-5 for the fastest term here (a 50 Hz sine of
// amplitude 3), rounding 1e-14/1e-6 = 1e-8; asked: 1e-4 of the derivative's scale (≥ 1e2).
#include <gtest/gtest.h>

#include <cmath>

#include "model/laws.hpp"

namespace beltsim {
namespace {

// a stand-in for a Lua law: f(t, Ω) = 0.3·Ω²·cos(7t), counted
class Quadratic final : public LawFunction {
 public:
  double value(double t, double omega) const override {
    calls_++;
    return 0.3 * omega * omega * std::cos(7 * t);
  }
  std::string describe() const override { return "quadratic"; }
  long calls() const override { return calls_; }

 private:
  mutable long calls_ = 0;
};

TimeSpeedLaw every_term() {
  TimeSpeedLaw law;
  law.constant = 2;
  law.per_speed = -0.05;
  law.t = {0.0, 0.1, 0.4};
  law.value = {0.0, 5.0, 3.0};
  law.omega = {0.0, 50.0, 150.0};
  law.omega_value = {10.0, 4.0, -8.0};
  law.ramps = {{0.05, 0.25, 1.0, 6.0, false}, {0.1, 0.3, 0.0, -4.0, true}, {0.2, 0.2, 0.0, 7.0, false}};
  law.sines = {{1.5, 3.0, 50.0, 0.3}};
  law.harmonics = {{2.0, 0.8, 0.1, 80.0}, {0.5, 0.4, -1.0, 80.0}};
  law.fn = std::make_shared<Quadratic>();
  return law;
}

// docs/lua-api.md's formulas, written out independently of laws.cpp
double formula(double t, double w) {
  auto lerp = [](double x, double x0, double x1, double y0, double y1) {
    return x <= x0 ? y0 : x >= x1 ? y1 : y0 + (y1 - y0) * (x - x0) / (x1 - x0);
  };
  const double table = t < 0.1 ? lerp(t, 0, 0.1, 0, 5) : lerp(t, 0.1, 0.4, 5, 3);
  const double map = w < 50 ? lerp(w, 0, 50, 10, 4) : lerp(w, 50, 150, 4, -8);
  const double lin = lerp(t, 0.05, 0.25, 1, 6);
  const double s = std::clamp((t - 0.1) / 0.2, 0.0, 1.0);
  const double cosr = -4.0 * (1 - std::cos(M_PI * s)) / 2;
  const double step = t > 0.2 ? 7.0 : 0.0;
  const double sine = 1.5 + 3.0 * std::sin(2 * M_PI * 50 * t + 0.3);
  const double harm = 0.8 * std::sin(2 * 80 * t + 0.1) + 0.4 * std::sin(0.5 * 80 * t - 1.0);
  return 2 - 0.05 * w + table + map + lin + cosr + step + sine + harm + 0.3 * w * w * std::cos(7 * t);
}

TEST(Laws, ValueIsTheSumOfTheFormulas) {
  const TimeSpeedLaw law = every_term();
  for (double t : {-0.1, 0.0, 0.03, 0.07, 0.12, 0.19, 0.21, 0.27, 0.35, 0.5, 2.0})
    for (double w : {-10.0, 0.0, 20.0, 75.0, 149.0, 400.0}) {
      // the two sums round differently (a compiler may fuse a product and a sum into one FMA):
      // a few units of rounding of the value, 7.3e-12 at 4.5e4; a term off is far more
      const double want = formula(t, w);
      EXPECT_NEAR(law.eval(t, w), want, 4e-15 * (1 + std::abs(want))) << t << " " << w;
    }
}

TEST(Laws, StepTakesItsValueAfterTheJumpOnlyWhenAsked) {
  TimeSpeedLaw law;
  law.ramps = {{0.2, 0.2, -1.0, 7.0, false}};
  EXPECT_EQ(law.eval(0.2, 0), -1.0);        // a step that ends on the jump sees the value before
  EXPECT_EQ(law.eval(0.2, 0, true), 7.0);   // the restart there sees the value after
  EXPECT_EQ(law.eval(std::nextafter(0.2, 1.0), 0), 7.0);
  EXPECT_EQ(law.jumps(), std::vector<double>{0.2});
  EXPECT_TRUE(law.kinks().empty());
}

TEST(Laws, DerivativesMatchCentralDifferences) {
  const TimeSpeedLaw law = every_term();
  // points a margin away from every kink (0.05, 0.1, 0.2, 0.25, 0.3, 0.4 s; 50 rad/s)
  for (double t : {0.03, 0.07, 0.13, 0.17, 0.22, 0.27, 0.35})
    for (double w : {20.0, 75.0, 120.0}) {
      const double h = 1e-6;
      const double dw = (law.eval(t, w + h) - law.eval(t, w - h)) / (2 * h);
      const double dt = (law.eval(t + h, w) - law.eval(t - h, w)) / (2 * h);
      EXPECT_NEAR(law.d_omega(t, w), dw, 1e-4 * std::max(1.0, std::abs(dw))) << t << " " << w;
      EXPECT_NEAR(law.d_time(t, w), dt, 1e-4 * std::max(1e2, std::abs(dt))) << t << " " << w;
    }
}

TEST(Laws, SecondTimeDerivativeOfASpeedLaw) {
  TimeSpeedLaw law = every_term();
  law.per_speed = 0, law.omega.clear(), law.omega_value.clear();  // a speed law: time alone
  law.fn.reset();
  // second differences at h = 1e-4 s: truncation h²·|f''''|/12 ≈ 1e-8·(2π·50)⁴·3/12 ≈ 25 against
  // |f''| ≈ (2π·50)²·3 ≈ 3e5 and rounding 1e-14/h² = 1e-6: asked 1e-3 of the scale
  for (double t : {0.03, 0.13, 0.17, 0.22, 0.27}) {
    const double h = 1e-4;
    const double d2 = (law.eval(t + h, 0) - 2 * law.eval(t, 0) + law.eval(t - h, 0)) / (h * h);
    EXPECT_NEAR(law.d_time2(t), d2, 1e-3 * std::max(1e3, std::abs(d2))) << t;
  }
}

TEST(Laws, SumsMergeTablesExactly) {
  TimeSpeedLaw a, b;
  a.t = {0.0, 1.0};
  a.value = {0.0, 10.0};
  a.omega = {0.0, 100.0};
  a.omega_value = {5.0, -5.0};
  b.t = {0.5, 2.0};
  b.value = {4.0, 1.0};
  b.omega = {50.0, 60.0};
  b.omega_value = {1.0, 2.0};
  b.sines = {{1.0, 2.0, 3.0, 0.0}};
  TimeSpeedLaw s = a;
  s += b;
  for (double t : {-1.0, 0.0, 0.25, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0})
    for (double w : {-5.0, 25.0, 55.0, 80.0, 200.0}) EXPECT_NEAR(s.eval(t, w), a.eval(t, w) + b.eval(t, w), 1e-12);
  EXPECT_EQ(s.t, (std::vector<double>{0.0, 0.5, 1.0, 2.0}));
}

TEST(Laws, KinksAreTheTableBreakpointsAndRampEnds) {
  const TimeSpeedLaw law = every_term();
  EXPECT_EQ(law.kinks(), (std::vector<double>{0.0, 0.05, 0.1, 0.25, 0.3, 0.4}));
  EXPECT_EQ(law.jumps(), std::vector<double>{0.2});
}

}  // namespace
}  // namespace beltsim
