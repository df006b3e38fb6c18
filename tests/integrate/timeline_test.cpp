// Samples at step ends (integrate/timeline.hpp): a stream added as landed is one the integrator's
// steps end on, while the steps are at most half its interval; longer steps cover several of its
// times, which the dense output gives, and the stream does not change them. rkf45 on
// y' = cos(ω t), whose steps the tolerance sets (no kinks, no stiffness).
#include "integrate/timeline.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <memory>
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

// a pause (the live page's control) stops right after the next output, where run_to of that
// output's time stands too: a change made there and the run after it are those of run_to(t) and
// the change, bit for bit (a session's replay). Stopped at a step's end instead, the replay's
// run_to(t) read t from a step of its own where an attempt was rejected near it.
TEST(Timeline, APauseStopsAtTheNextOutputWhereRunToOfItStands) {
  struct Run {
    CosineWave sys;
    std::unique_ptr<Integrator> integ = make_integrator("rkf45", sys, Tolerances{1e-6, 1e-6});
    Timeline tl{*integ};
    std::vector<double> samples;
    Run() {
      tl.add_stream(
          0.0, 0.01, [this](double t, const Eigen::VectorXd& y) { samples.push_back(t + y[0]); }, false);
      Eigen::VectorXd y0(1);
      y0[0] = 0;
      tl.start(0.0, y0);
    }
    // the change made at the pause: the state moved by 1
    void change() {
      Eigen::VectorXd y = tl.state();
      y[0] += 1;
      tl.changed(&y);
    }
  };
  Run paused;
  std::atomic<bool> pause{false};
  double asked_in = 0;  // the start of the step after which the pause was asked
  const Timeline::Progress ask = [&](double t, const WorkCounters&) {
    if (t > 0.123 && !pause) pause = true, asked_in = paused.integ->t_prev();
  };
  const Timeline::Result r = paused.tl.run_to(1.0, nullptr, ask, {}, &pause);
  ASSERT_TRUE(r.interrupted);
  const double t_p = r.t;
  EXPECT_GT(t_p, asked_in) << "the first output the step that asked for it holds, or a later one";
  EXPECT_LT(t_p, 1.0);
  EXPECT_DOUBLE_EQ(std::round(t_p / 0.01) * 0.01, t_p) << "the pause stands on a sample's time";
  paused.change();
  paused.tl.run_to(1.0);

  Run replay;
  replay.tl.run_to(t_p);
  ASSERT_EQ(replay.tl.now(), t_p);
  replay.change();
  replay.tl.run_to(1.0);
  ASSERT_EQ(replay.samples.size(), paused.samples.size());
  for (size_t k = 0; k < paused.samples.size(); ++k) ASSERT_EQ(replay.samples[k], paused.samples[k]) << "sample " << k;
  EXPECT_EQ(replay.tl.state()[0], paused.tl.state()[0]);
}

// The fires of `when(y > level)` on the wave y = sin(ω t)/ω up to 0.2 s, whose condition reads
// false at the instant of every restart, as the belt's slip figures may there (read from the held
// step's ends before the restart, from the state itself after it); with `reset` each action sets
// y to 0, a jump of the state. Counting stops at 5: the condition is removed.
int when_fires(double level, bool reset) {
  CosineWave sys;
  auto integ = make_integrator("rkf45", sys, Tolerances{1e-6, 1e-6});
  Timeline tl(*integ);
  double restarted_at = -1;
  tl.on_restart([&](double t) { restarted_at = t; });
  int fires = 0, id = 0;
  Eigen::VectorXd zero = Eigen::VectorXd::Zero(1);
  id = tl.add_when([&](double t, const Eigen::VectorXd& y) { return t != restarted_at && y[0] > level; },
                   [&](double) {
                     if (++fires == 5) tl.remove(id);
                     if (reset) tl.changed(&zero);
                   });
  tl.start(0.0, zero);
  tl.run_to(0.2);
  return fires;
}

// A condition true where its action ran stays true through the restart there, unless the action
// made the state jump: y = sin(10 t)/10 crosses 0.05 once before 0.2 s (at 0.052 s), and the
// condition that reads false at each restart fired again at every one (a user's trial: 1 714
// fires within 78 ns on a slip figure). Reset to 0 at each action (s0 = sin(10 t) there), y =
// (sin(10 t) - s0)/10 passes 0.03 three times: where sin(10 t) reaches 0.3, 0.6 and 0.9.
TEST(Timeline, AConditionTrueAtItsActionStaysTrueThroughTheRestart) {
  EXPECT_EQ(when_fires(0.05, false), 1);
  EXPECT_EQ(when_fires(0.03, true), 3);
}

}  // namespace
}  // namespace beltsim
