// No silent hang (issue 12, item 3): a run that makes no progress stops with the time, the
// stiffest component and a suggestion; the wall-time limit stops a batch run with its outputs
// finalised; the stop flag is honoured between the outputs of one step and in the scene build.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "integrate/make_integrator.hpp"
#include "integrate/timeline.hpp"
#include "scene/build.hpp"
#include "scene/scene.hpp"
#include "sim/simulation.hpp"
#include "support/dry_scene.hpp"
#include "support/presets.hpp"
#include "support/scratch.hpp"
#include "support/warning_guard.hpp"

namespace beltsim {
namespace {

using test::dry_scene;

namespace fs = std::filesystem;

// y' = -λ (y - cos t): with λ = 1e14 an explicit method is held by stability to steps of about
// 3e-14 s, below 1024 units of rounding of t (2.3e-13 s) and above the collapse guard (3.6e-15 s)
struct Stiff : OdeProblem {
  double lambda = 1e14;
  int size() const override { return 1; }
  void rhs(double t, const double* y, double* dy) override { dy[0] = -lambda * (y[0] - std::cos(t)); }
  std::string describe(int) const override { return "the stiff test component"; }
};

TEST(NoHang, StepSizeAtTheRoundingFloorStops) {
  Stiff sys;
  auto integ = make_integrator("rkf45", sys, Tolerances{1e-6, 1e-6});
  Timeline tl(*integ);
  Eigen::VectorXd y0(1);
  y0[0] = 1;
  tl.start(0.0, y0);
  try {
    tl.run_to(1.0);
    FAIL() << "no error";
  } catch (const DivergenceError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("no progress at t = "), std::string::npos) << m;
    EXPECT_NE(m.find("rounding floor"), std::string::npos) << m;
    EXPECT_NE(m.find("the stiff test component"), std::string::npos) << m;
    EXPECT_NE(m.find("try an implicit integrator"), std::string::npos) << m;
    EXPECT_LT(e.t, 1e-6);
  }
  // it stops after kFloorSteps (10000) steps in a row at the floor, not after the 1e12 or more
  // the held step size would need to reach t = 1 s (measured: 10005 steps, 634 rejected)
  EXPECT_LT(integ->work().steps, 20000);
}

// an implicit method whose iteration can never converge (the linear solver finds every matrix
// singular): each failure cuts the step to a fifth, and the tenth in a row stops the run with the
// time, the component and a suggestion, before the step size collapses
TEST(NoHang, ImplicitFailuresInARowStop) {
  test::expect_warnings({WarningKind::failed_step});
  struct Problem : OdeProblem {
    int size() const override { return 1; }
    void rhs(double t, const double*, double* dy) override { dy[0] = std::cos(t); }
    std::string describe(int) const override { return "the test component"; }
  } problem;
  struct Singular : LinearSolver {
    bool prepare_jacobian(double, const double*) override { return true; }
    bool factor(double) override { return false; }
    void solve(const double*, double*) override {}
  } singular;
  auto integ = make_integrator("esdirk32", OdeSystem(problem, &singular), Tolerances{1e-6, 1e-6});
  Timeline tl(*integ);
  Eigen::VectorXd y0(1);
  y0[0] = 1;
  tl.start(0.0, y0);
  try {
    tl.run_to(1.0);
    FAIL() << "no error";
  } catch (const DivergenceError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("no progress at t = 0 s: the implicit iteration failed 10 times in a row"), std::string::npos)
        << m;
    // no step was ever taken, so no error estimate names a component (not a made-up one)
    EXPECT_NE(m.find("no step was taken, so no component has an error estimate"), std::string::npos) << m;
    EXPECT_EQ(m.find("the test component"), std::string::npos) << m;
    EXPECT_NE(m.find("check the scene's largest values"), std::string::npos) << m;  // (it is implicit already)
    EXPECT_EQ(m.find("try an implicit integrator"), std::string::npos) << m;
    EXPECT_EQ(e.t, 0.0);
  }
  const WarningStat failed = integ->work().warnings[WarningKind::failed_step];
  EXPECT_EQ(failed.count, 10);
  EXPECT_EQ(failed.first_t, 0.0);
}

fs::path hang_temp(const std::string& name) {
  const fs::path p = beltsim::test::scratch_dir("beltsim_hang_test") / name;
  fs::remove_all(p);
  return p;
}

// a 1 s run with a wall-time limit of 0.05 s stops at the last finished step, outputs closed. The
// clock is the test's: 1 ms per look, so the limit is passed at the 51st look after the start
// whatever the machine's speed, and the run must stop at that look, not a later one
TEST(NoHang, WallLimitStopsABatchRun) {
  // the paper's dry drive has failed implicit steps from 0.036 s, if the run gets that far
  test::expect_warnings({WarningKind::failed_step});
  RunSettings rs;
  rs.t_end = 1.0;
  rs.sample_dt = 1e-4;
  rs.wall_limit = 0.05;
  rs.out_dir = hang_temp("wall").string();
  long looks = 0, past = 0;  // the clock's looks, and those after the one past the limit
  rs.wall_clock = [&] {
    if (looks > 51) past++;
    return 1e-3 * static_cast<double>(looks++);
  };
  const RunResult r = run(dry_scene(), rs);
  // the look that passes the limit stops the run; the run then reads the clock once more for its
  // total wall time
  EXPECT_LE(past, 1) << looks << " looks";
  EXPECT_TRUE(r.over_wall_limit);
  EXPECT_FALSE(r.interrupted);
  EXPECT_GT(r.t_reached, 0.0);
  EXPECT_LT(r.t_reached, 1.0);
  // the CSV ends with whole rows up to the time reached; parameters.csv has its closing lines
  std::ifstream f(r.csv_path);
  std::string line, last;
  long rows = 0;
  while (std::getline(f, line)) last = line, rows++;
  EXPECT_GT(rows, 1);
  EXPECT_LE(std::stod(last), r.t_reached);
  std::ifstream p(r.parameters_path);
  const std::string params((std::istreambuf_iterator<char>(p)), std::istreambuf_iterator<char>());
  EXPECT_NE(params.find("warning.failed_step.count"), std::string::npos);
  EXPECT_NE(params.find("\nend.status,wall_limit,,derived,stopped by run.max_wall"), std::string::npos) << params;
}

// the rate watchdog on a fake clock: 0.01 s of wall time per poll while the run goes well, then
// 1e12 s per poll (a run that has all but stopped): the first 10 s window after the change sees
// a rate far below 1e-9 of the best, and the run stops with the time, the component and a
// suggestion, its outputs closed
TEST(NoHang, RateCollapseStops) {
  test::expect_warnings({WarningKind::failed_step});  // the paper's drive has some (docs/outputs.md)
  RunSettings rs;
  rs.sample_dt = 1e-4;
  rs.out_dir = hang_temp("rate").string();
  long polls = 0;
  double now = 0;
  rs.wall_clock = [&] {
    now += ++polls < 2000 ? 0.01 : 1e12;
    return now;
  };
  Simulation s(dry_scene(), rs);
  try {
    s.run_to(1.0);
    FAIL() << "no error after " << polls << " polls, at t = " << s.now() << " s";
  } catch (const DivergenceError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("no progress at t = "), std::string::npos) << m;
    EXPECT_NE(m.find("against"), std::string::npos) << m;
    EXPECT_TRUE(m.find("the largest error is in element ") != std::string::npos ||
                m.find("the largest error is in pulley '") != std::string::npos)
        << m;
    EXPECT_NE(m.find("check the scene's largest values"), std::string::npos) << m;  // (it is implicit already)
    EXPECT_EQ(m.find("try an implicit integrator"), std::string::npos) << m;
    EXPECT_GT(e.t, 0.0);
    EXPECT_LT(e.t, 1.0);
    EXPECT_GE(polls, 2000);
  }
  EXPECT_TRUE(s.closed());
}

// the stop flag between the outputs of one step: a stream at 1e-12 s holds thousands of outputs
// in each step; the stop set by the 100th ends the call there, and going on delivers exactly
// what one call would have (pausing changes nothing)
TEST(NoHang, StopBetweenOutputsOfOneStep) {
  struct Cosine : OdeProblem {
    int size() const override { return 1; }
    void rhs(double t, const double*, double* dy) override { dy[0] = std::cos(t); }
  };
  auto outputs = [](bool stop_at_100, std::vector<double>& got) {
    Cosine sys;
    auto integ = make_integrator("rkf45", sys, Tolerances{1e-6, 1e-6});
    Timeline tl(*integ);
    std::atomic<bool> stop{false};
    tl.add_stream(0.0, 1e-9, [&](double t, const Eigen::VectorXd& y) {
      got.push_back(t), got.push_back(y[0]);
      if (stop_at_100 && got.size() == 200) stop.store(true);
    });
    Eigen::VectorXd y0(1);
    y0[0] = 0;
    tl.start(0.0, y0);
    const Timeline::Result r = tl.run_to(2e-6, &stop);
    if (stop_at_100) {
      EXPECT_TRUE(r.interrupted);
      EXPECT_EQ(got.size(), 200u);               // no output after the stop
      EXPECT_LT(tl.now(), tl.integrator().t());  // inside the held step
      EXPECT_EQ(tl.now(), got[198]);
      stop.store(false);
      EXPECT_FALSE(tl.run_to(2e-6, &stop).interrupted);
    }
  };
  std::vector<double> a, b;
  outputs(true, a);
  outputs(false, b);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a, b);
}

// Ctrl-C during a long build: the build of a 5000-element belt (seconds of placement and static
// solve) polls the stop flag from its first bisection step on and ends with BuildInterrupted, no
// scene made, and so does the static solve on its own (its Newton iterations, from a state moved
// off the static one). The flag is set before the call, so that where the stop lands does not
// depend on the machine's speed; how often the build polls is in scene.hpp (every bisection
// step, Newton iteration and line-search trial).
TEST(NoHang, StopFlagEndsALongSceneBuild) {
  SceneDef d = presets::paper_dry();
  d.belt.elements = 5000;
  d.allow_large = true;
  std::atomic<bool> stop{true};
  try {
    build_scene(d, &stop);
    FAIL() << "the build finished with its stop flag set";
  } catch (const BuildInterrupted& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("interrupted"), std::string::npos) << msg;
    EXPECT_NE(msg.find("5000 elements"), std::string::npos) << msg;
  }
  const Scene& sc = dry_scene();
  Eigen::VectorXd y = sc.y0;
  y[1] += 1e-4;  // the first element 0.1 mm off its place: accelerations of 1e3 m/s² and more
  BuildWatch watch;
  watch.stop = &stop;
  EXPECT_THROW(build::static_solve(sc.model, sc.drive, y, 0, watch), BuildInterrupted);
}

}  // namespace
}  // namespace beltsim
