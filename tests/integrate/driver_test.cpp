// Frames at exact times (issue 5, point 4): the driver's further dense-output streams deliver
// states at their t0 + k·dt whatever the steps, with the accuracy of the dense output.
#include <gtest/gtest.h>

#include <cmath>

#include "integrate/driver.hpp"
#include "integrate/stepper.hpp"
#include "integrate/timeline.hpp"

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

Frames run(double h_max, double t0, double dt, double t_end = 2.0) {
  Oscillator sys;
  auto st = make_stepper("rkf45");
  DriveOptions o;
  o.t_end = t_end;
  o.sample_dt = 0.5;
  o.h_max = h_max;
  Frames f;
  o.streams.push_back({t0, dt, [&](double t, const Eigen::VectorXd& y) { f.t.push_back(t), f.y0.push_back(y[0]); }});
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
    EXPECT_EQ(a.t[k], t0 + static_cast<double>(k) / 30);  // exactly: no accumulated drift (stream_time)
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

// a run whose end is a whole number of frame periods ends with a frame there, whatever the
// rounding of the period: at 30 frames/s ten times slower (1/300 s) the runs to 0.3, 0.6 and 0.7 s
// lost their last frame when the times were k·(1/300) (180·(1/300) is 0.6000000000000001)
TEST(Frames, ARunEndingOnAFrameTimeEndsWithThatFrame) {
  const std::pair<double, int> ends[] = {{0.1, 30}, {0.3, 90}, {0.5, 150}, {0.6, 180}, {0.7, 210}, {1.0, 300}};
  for (const auto& [t_end, n] : ends) {
    const Frames f = run(0.0, 0.0, 1.0 / 300, t_end);
    ASSERT_EQ(f.t.size(), static_cast<size_t>(n + 1)) << "t_end " << t_end;
    EXPECT_EQ(f.t.back(), t_end);
  }
  // and a sample every 1e-3 s lands on the decimals: the 350th at 0.35, not 0.35000000000000003
  EXPECT_EQ(stream_time(0, 1e-3, 350), 0.35);
}

// several streams (a mode check's plain run watched on each mode's grid): each delivers at
// t0 + k·dt up to t_end, from the dense output, so the run's steps and values do
// not depend on them, and with no sample stream (sample_dt = 0) nothing else is delivered
TEST(Frames, FurtherStreamsAtTheirOwnTimesAndTheSameSteps) {
  auto go = [](std::vector<double> dts, std::vector<Frames>& got, long& steps) {
    Oscillator sys;
    auto st = make_stepper("rkf45");
    DriveOptions o;
    o.t0 = 0.1;
    o.t_end = 2.0;
    o.sample_dt = 0;
    got.assign(dts.size(), {});
    for (size_t i = 0; i < dts.size(); ++i)
      o.streams.push_back({o.t0, dts[i], [&got, i](double t, const Eigen::VectorXd& y) {
                             got[i].t.push_back(t), got[i].y0.push_back(y[0]);
                           }});
    Eigen::VectorXd y(2);
    y << std::cos(0.1), -std::sin(0.1);
    bool sampled = false;
    steps = drive(sys, *st, Tolerances{1e-10, 1e-10}, o, y, [&](double, const Eigen::VectorXd&) {
              sampled = true;
            }).work.steps;
    EXPECT_FALSE(sampled);
  };
  std::vector<Frames> both, first, second;
  long s_both = 0, s_first = 0, s_second = 0;
  go({1.0 / 30, 0.07}, both, s_both);
  go({1.0 / 30}, first, s_first);
  go({0.07}, second, s_second);
  EXPECT_EQ(s_both, s_first);
  EXPECT_EQ(s_both, s_second);
  ASSERT_EQ(both[0].t.size(), static_cast<size_t>(std::floor(1.9 * 30)) + 1);
  ASSERT_EQ(both[1].t.size(), static_cast<size_t>(std::floor(1.9 / 0.07)) + 1);
  EXPECT_EQ(both[0].t, first[0].t);
  EXPECT_EQ(both[0].y0, first[0].y0);  // to the bit: the same steps, the same dense output
  EXPECT_EQ(both[1].t, second[0].t);
  EXPECT_EQ(both[1].y0, second[0].y0);
  for (size_t k = 0; k < both[1].t.size(); ++k) EXPECT_NEAR(both[1].y0[k], std::cos(both[1].t[k]), 1e-6);
}

}  // namespace
}  // namespace beltsim
