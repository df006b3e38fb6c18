// Samples at step ends (integrate/timeline.hpp): a stream added as landed is one the integrator's
// steps end on, while the steps are at most half its interval; longer steps cover several of its
// times, which the dense output gives, and the stream does not change them. rkf45 on
// y' = cos(ω t), whose steps the tolerance sets (no kinks, no stiffness).
#include "integrate/timeline.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "integrate/make_integrator.hpp"

namespace beltsim {
namespace {

struct CosineWave : OdeProblem {
  double omega = 10;
  int size() const override { return 1; }
  void rhs(double t, const double* y, double* dy) override {
    (void)y;
    dy[0] = std::cos(omega * t);
  }
};

struct StreamRun {
  int samples = 0, at_step_ends = 0;
  long steps = 0;
};

// a run of the wave to t_end with a stream every dt (none when dt = 0), landed or not
StreamRun run_stream(double rtol, double dt, bool landed, double t_end) {
  CosineWave sys;
  auto integ = make_integrator("rkf45", sys, Tolerances{rtol, rtol});
  Timeline tl(*integ);
  StreamRun o;
  if (dt > 0)
    tl.add_stream(
        0.0, dt,
        [&](double t, const Eigen::VectorXd&) {
          if (t == 0) return;
          ++o.samples;
          if (integ->t() == t) ++o.at_step_ends;
        },
        landed);
  Eigen::VectorXd y0(1);
  y0[0] = 0;
  tl.start(0.0, y0);
  tl.run_to(t_end);
  o.steps = integ->work().steps;
  return o;
}

TEST(Timeline, LandedSamplesAreStepEndsWhereTheStepsAreShort) {
  // at rtol 1e-9 rkf45 takes steps of a few ms on a 0.63 s period: far below half of 0.1 s
  const StreamRun free = run_stream(1e-9, 0.1, false, 2.0), landed = run_stream(1e-9, 0.1, true, 2.0);
  ASSERT_EQ(landed.samples, 20);
  EXPECT_EQ(landed.at_step_ends, 20);
  EXPECT_LT(free.at_step_ends, 5) << "without landing, a sample at a step end is a coincidence";
  // the landings add at most about one step per sample
  EXPECT_LE(landed.steps, free.steps + 25);
}

TEST(Timeline, LandedSamplesDoNotShortenLongSteps) {
  // at rtol 1e-3 the steps grow within a few steps from the first (1e-6 s, ×5 a step) to some
  // 0.1 s, longer than twice the 2 ms interval: from there on the stream is read from the dense
  // output (landed on every time, the 2 s would take 1 000 steps or more)
  const StreamRun none = run_stream(1e-3, 0, false, 2.0), landed = run_stream(1e-3, 2e-3, true, 2.0);
  ASSERT_EQ(landed.samples, 1000);
  EXPECT_LE(landed.steps, none.steps + 2);
  EXPECT_LE(landed.at_step_ends, 3);
}

// at one time the changes come first and the outputs after them: a sample at the time of a
// landing's action (a law's step, a timed wetting) or an every-action shows the system after it,
// as a pause there reads it (the sample came first, and a row at a step's time had its `from`)
TEST(Timeline, AnOutputAtAChangesTimeComesAfterIt) {
  CosineWave sys;
  auto integ = make_integrator("rkf45", sys, Tolerances{1e-6, 1e-6});
  Timeline tl(*integ);
  std::vector<std::string> order;
  tl.add_stream(
      0.0, 0.1,
      [&](double t, const Eigen::VectorXd&) {
        if (t == 0.2) order.push_back("sample");
      },
      true);
  tl.add_every(0.2, [&](double t) {
    if (t == 0.2) order.push_back("every");
  });
  tl.set_landings({{0.2, [&](double) {
                      order.push_back("landing");
                      tl.changed();
                    }}});
  Eigen::VectorXd y0(1);
  y0[0] = 0;
  tl.start(0.0, y0);
  tl.run_to(0.3);
  EXPECT_EQ(order, (std::vector<std::string>{"every", "landing", "sample"}));
}

}  // namespace
}  // namespace beltsim
