// Durations as text (io/duration_text.hpp): rounded before they are split, so no field reads 60.
#include "io/duration_text.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace beltsim {
namespace {

TEST(DurationText, RoundsBeforeSplitting) {
  EXPECT_EQ(duration_text(179.6), "3 min 00 s");
  EXPECT_EQ(duration_text(179.4), "2 min 59 s");
  EXPECT_EQ(duration_text(3599.6), "60 min 00 s");
  EXPECT_EQ(duration_text(5399.6), "1 h 30 min");
  EXPECT_EQ(duration_text(7199.9), "2 h 00 min");
  EXPECT_EQ(duration_text(7169.0), "1 h 59 min");
}

TEST(DurationText, EachRangeHasItsUnits) {
  EXPECT_EQ(duration_text(0), "0 s");
  EXPECT_EQ(duration_text(59.6), "60 s");
  EXPECT_EQ(duration_text(89.4), "89 s");
  EXPECT_EQ(duration_text(89.6), "1 min 30 s");
  EXPECT_EQ(duration_text(125), "2 min 05 s");
  EXPECT_EQ(duration_text(3 * 3600 + 7 * 60 + 10), "3 h 07 min");
}

TEST(DurationText, NotFiniteIsUnknown) {
  EXPECT_EQ(duration_text(INFINITY), "?");
  EXPECT_EQ(duration_text(NAN), "?");
  EXPECT_EQ(duration_text(-INFINITY), "?");
  EXPECT_EQ(duration_text(1e9 * 3600), "1000000000 h 00 min");
}

}  // namespace
}  // namespace beltsim
