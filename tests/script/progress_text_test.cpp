// The progress line's text (script/progress.hpp): what a narrow terminal keeps of it, and its
// estimate of the time left. A user's 80-column terminal wrapped the 81-character line, and every
// redraw left a line behind; a run whose start-up ramp was cheap was told "about 35 s left" where
// about 100 s were.
#include <gtest/gtest.h>

#include <cmath>
#include <deque>
#include <string>
#include <utility>

#include "script/progress.hpp"

namespace beltsim::script {
namespace {

ProgressParts parts() {
  ProgressParts p;
  p.head = "beltsim: t = 6.6427 s of 30 s (22 %)";
  p.elapsed = "10 s elapsed";
  p.left = "about 35 s left";
  p.steps = "121659 steps";
  return p;
}

TEST(ProgressText, WholeWhereItFitsOrTheWidthIsUnknown) {
  const std::string whole = "beltsim: t = 6.6427 s of 30 s (22 %), 10 s elapsed, about 35 s left, 121659 steps";
  EXPECT_EQ(fit_progress_text(parts(), 0), whole);
  EXPECT_EQ(fit_progress_text(parts(), 200), whole);
}

TEST(ProgressText, ANarrowTerminalDropsTheStepsThenTheElapsedTimeThenTheEstimate) {
  // shorter than the terminal by a column at least (a line as wide as it wraps on some terminals)
  EXPECT_EQ(fit_progress_text(parts(), 80), "beltsim: t = 6.6427 s of 30 s (22 %), 10 s elapsed, about 35 s left");
  EXPECT_EQ(fit_progress_text(parts(), 60), "beltsim: t = 6.6427 s of 30 s (22 %), about 35 s left");
  EXPECT_EQ(fit_progress_text(parts(), 45), "beltsim: t = 6.6427 s of 30 s (22 %)");
  EXPECT_EQ(fit_progress_text(parts(), 20), "beltsim: t = 6.6427");
  for (int columns = 2; columns < 120; ++columns)
    EXPECT_LT(static_cast<int>(fit_progress_text(parts(), columns).size()), columns) << columns;
}

TEST(ProgressText, TheEstimateFollowsTheRateOfTheLastThirdOfTheRun) {
  // 0..1 s of simulated time in the first 10 s of wall time, then 0.1 s per 10 s: 3 s in all,
  // 40 s of wall time so far at t = 1.3 s; at the recent rate the 1.7 s left take 170 s, at the
  // whole run's 52 s
  std::deque<std::pair<double, double>> seen;
  for (int k = 1; k <= 40; ++k) seen.emplace_back(k, k <= 10 ? 0.1 * k : 1 + 0.01 * (k - 10));
  EXPECT_NEAR(wall_left(seen, 0, 1.3, 3, 40), 170, 1e-9);
  // a steady run: the same either way
  seen.clear();
  for (int k = 1; k <= 30; ++k) seen.emplace_back(k, 0.1 * k);
  EXPECT_NEAR(wall_left(seen, 0, 3, 4, 30), 10, 1e-9);
  // no drawing yet: the whole run's rate; nothing done yet: no estimate
  EXPECT_NEAR(wall_left({}, 0, 1, 2, 5), 5, 1e-9);
  EXPECT_TRUE(std::isnan(wall_left({}, 0, 0, 2, 5)));
}

// trial 12: a live simulation's run_to(0.15) then run_to(0.4) read "t = 0.1834 s of 0.4 s (13 %)",
// the share of the second call's 0.15..0.4; the percentage is of the span the line names, from the
// simulation's start (0, or a resumed simulation's checkpoint time)
TEST(ProgressText, ThePercentageIsOfTheSpanFromTheSimulationsStart) {
  EXPECT_EQ(progress_head(0.1834, 0.4, 0), "beltsim: t = 0.1834 s of 0.4 s (46 %)");
  EXPECT_EQ(progress_head(0.35, 0.4, 0.3), "beltsim: t = 0.3500 s of 0.4 s (50 %)");
  EXPECT_EQ(progress_head(0.4, 0.4, 0), "beltsim: t = 0.4000 s of 0.4 s (100 %)");
  EXPECT_EQ(progress_head(0.2, 0.2, 0.2), "beltsim: t = 0.2000 s of 0.2 s (100 %)");
}

}  // namespace
}  // namespace beltsim::script
