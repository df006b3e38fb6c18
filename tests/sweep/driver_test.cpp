// The time left that a sweep's progress line gives (src/sweep/driver.hpp): from the points that
// ran to their end, the running points' elapsed times and the processes the waiting ones share.
#include "sweep/driver.hpp"

#include <gtest/gtest.h>

namespace beltsim::sweep {
namespace {

TEST(TimeLeft, NothingWithoutAPointThatRanToItsEnd) {
  // (a failed point's time is no basis: the caller leaves it out of `ran`)
  EXPECT_EQ(time_left({}, {3.0, 3.0}, 4, 2), std::nullopt);
}

TEST(TimeLeft, TheWaitingPointsStartAsProcessesComeFree) {
  // three points of 10 s on two processes: 20 s, not 3 x 10 / 2
  EXPECT_DOUBLE_EQ(*time_left({8.0, 12.0}, {}, 3, 2), 20.0);
  // running for 8 s and 2 s: they end in 2 s and 8 s, the waiting point after the first
  EXPECT_DOUBLE_EQ(*time_left({10.0}, {8.0, 2.0}, 1, 2), 12.0);
}

TEST(TimeLeft, NeverBelowWhatARunningPointStillNeeds) {
  // one point running for 1 s of its 10 on two processes: 9 s, not half of it
  EXPECT_DOUBLE_EQ(*time_left({10.0}, {1.0}, 0, 2), 9.0);
  // one past the mean needs nothing at the rate seen; the other still does
  EXPECT_DOUBLE_EQ(*time_left({10.0}, {12.0, 3.0}, 0, 2), 7.0);
  // only points past the mean: no figure rather than 0 s
  EXPECT_EQ(time_left({10.0}, {12.0}, 0, 2), std::nullopt);
}

}  // namespace
}  // namespace beltsim::sweep
