// Frames at exact times (issue 5, point 4): the driver's second dense-output stream delivers
// states at frame_t0 + k·frame_dt whatever the steps, with the accuracy of the dense output.
#include <gtest/gtest.h>

#include <cmath>

#include "integrate/driver.hpp"
#include "integrate/stepper.hpp"

namespace beltsim {
namespace {

// y1' = y2, y2' = -y1: (cos t, -sin t)
class Oscillator final : public OdeProblem {
 public:
  int size() const override { return 2; }
  void rhs(double, const double* y, double* dy) override {
    dy[0] = y[1];
    dy[1] = -y[0];
  }
};

struct Frames {
  std::vector<double> t, y0;
};

Frames run(double h_max, double t0, double dt) {
  Oscillator sys;
  auto st = make_stepper("rkf45");
  DriveOptions o;
  o.t_end = 2.0;
  o.sample_dt = 0.5;
  o.h_max = h_max;
  o.frame_dt = dt;
  o.frame_t0 = t0;
  Frames f;
  o.frame = [&](double t, const Eigen::VectorXd& y) { f.t.push_back(t), f.y0.push_back(y[0]); };
  Eigen::VectorXd y(2);
  y << 1, 0;
  drive(sys, *st, Tolerances{1e-10, 1e-10}, o, y, [](double, const Eigen::VectorXd&) {});
  return f;
}

TEST(Frames, AtTheirOwnTimesWhateverTheSteps) {
  const double t0 = 0.05, dt = 1.0 / 30;  // not a multiple of any step or sample time
  const Frames a = run(0.0, t0, dt), b = run(0.007, t0, dt);
  const size_t n = static_cast<size_t>(std::floor((2.0 - t0) / dt)) + 1;
  ASSERT_EQ(a.t.size(), n);
  ASSERT_EQ(b.t.size(), n);
  for (size_t k = 0; k < n; ++k) {
    EXPECT_EQ(a.t[k], t0 + static_cast<double>(k) * dt);  // exactly: no accumulated drift
    EXPECT_EQ(b.t[k], a.t[k]);
    // cubic Hermite on steps of rtol 1e-10: error well below 1e-6 on either step pattern
    EXPECT_NEAR(a.y0[k], std::cos(a.t[k]), 1e-6);
    EXPECT_NEAR(b.y0[k], std::cos(b.t[k]), 1e-6);
  }
}

TEST(Frames, NoneWithoutAFrameFunctionAndFromTheStart) {
  const Frames f = run(0.0, 0.0, 0.25);
  ASSERT_EQ(f.t.size(), 9u);  // 0, 0.25, ..., 2.0 (the end included)
  EXPECT_EQ(f.t.front(), 0.0);
  EXPECT_EQ(f.t.back(), 2.0);
  EXPECT_NEAR(f.y0.back(), std::cos(2.0), 1e-6);
}

}  // namespace
}  // namespace beltsim
