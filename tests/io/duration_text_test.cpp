// Durations as text (io/duration_text.hpp): rounded before they are split, so no field reads 60;
// each duration in the largest unit it reaches, so that a count-down never changes form within a
// unit (a trial's estimate went from "about 1 h 36 min left" to "about 88 min 31 s left").
#include "io/duration_text.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <regex>
#include <string>

namespace beltsim {
namespace {

TEST(DurationText, RoundsBeforeSplitting) {
  EXPECT_EQ(duration_text(179.6), "3 min 00 s");
  EXPECT_EQ(duration_text(179.4), "2 min 59 s");
  EXPECT_EQ(duration_text(3599.4), "59 min 59 s");
  EXPECT_EQ(duration_text(3599.6), "1 h 00 min");
  EXPECT_EQ(duration_text(5399.6), "1 h 30 min");
  EXPECT_EQ(duration_text(7199.9), "2 h 00 min");
  EXPECT_EQ(duration_text(7169.0), "1 h 59 min");
}

TEST(DurationText, EachRangeHasItsUnits) {
  EXPECT_EQ(duration_text(0), "0 s");
  EXPECT_EQ(duration_text(59.4), "59 s");
  EXPECT_EQ(duration_text(59.6), "1 min 00 s");
  EXPECT_EQ(duration_text(89.6), "1 min 30 s");
  EXPECT_EQ(duration_text(125), "2 min 05 s");
  EXPECT_EQ(duration_text(88 * 60 + 31), "1 h 29 min");
  EXPECT_EQ(duration_text(3 * 3600 + 7 * 60 + 10), "3 h 07 min");
}

// a count-down from 3 h to 0 in steps of 7 s: no field reads 60 or more but the hours, so the form
// changes only where a unit is reached (1 h, 1 min), and each form once
TEST(DurationText, ACountDownChangesFormOnlyAtItsUnits) {
  const std::regex seconds(R"((\d+) s)"), minutes(R"((\d+) min (\d\d) s)"), hours(R"((\d+) h (\d\d) min)");
  std::string last_form;
  int forms = 0;
  for (double s = 3 * 3600; s >= 0; s -= 7) {
    const std::string text = duration_text(s);
    std::smatch m;
    std::string form;
    if (std::regex_match(text, m, hours)) {
      form = "h";
      EXPECT_GE(std::stoi(m[1]), 1) << text;
      EXPECT_LT(std::stoi(m[2]), 60) << text;
    } else if (std::regex_match(text, m, minutes)) {
      form = "min";
      EXPECT_GE(std::stoi(m[1]), 1) << text;
      EXPECT_LT(std::stoi(m[1]), 60) << text << " (" << s << " s)";
      EXPECT_LT(std::stoi(m[2]), 60) << text;
    } else if (std::regex_match(text, m, seconds)) {
      form = "s";
      EXPECT_LT(std::stoi(m[1]), 60) << text << " (" << s << " s)";
    } else {
      ADD_FAILURE() << "an unknown form: " << text;
    }
    if (form != last_form) forms++, last_form = form;
  }
  EXPECT_EQ(forms, 3);
}

TEST(DurationText, NotFiniteIsUnknown) {
  EXPECT_EQ(duration_text(INFINITY), "?");
  EXPECT_EQ(duration_text(NAN), "?");
  EXPECT_EQ(duration_text(-INFINITY), "?");
  EXPECT_EQ(duration_text(1e9 * 3600), "1000000000 h 00 min");
}

}  // namespace
}  // namespace beltsim
