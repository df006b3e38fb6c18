// Numbers as text (io/number_text.hpp): rounded_text, the messages' one formatter, is printf's %.<digits>g.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "io/number_text.hpp"

namespace beltsim {
namespace {

std::string printf_g(double v, int digits) {
  char b[64];
  std::snprintf(b, sizeof b, "%.*g", digits, v);
  return b;
}

// the messages' numbers read as they did when each printed with its own %.<digits>g: the same
// text for doubles over ±300 decades, at every precision the code uses
TEST(NumberText, RoundedIsPrintfG) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> mantissa(-1, 1);
  std::uniform_int_distribution<int> exponent(-300, 300);
  for (int k = 0; k < 10000; ++k) {
    const double v = mantissa(rng) * std::pow(10.0, exponent(rng));
    for (int digits : {3, 6, 9, 10, 17}) ASSERT_EQ(rounded_text(v, digits), printf_g(v, digits)) << v;
  }
  for (double v : {0.0, -0.0, 0.1 + 0.2, 1e-320, double(INFINITY), -double(INFINITY), double(NAN)})
    EXPECT_EQ(rounded_text(v), printf_g(v, 10)) << v;
  EXPECT_EQ(rounded_text(0.1 + 0.2), "0.3");
  EXPECT_EQ(number_text(0.1 + 0.2), "0.30000000000000004");
}

// a NaN reads "nan" in a message whatever its sign bit: Lua's 0/0 is a negative NaN on x86, which
// to_chars wrote "-nan" (a user trial: "view.centre: ... (got x = -nan)")
TEST(NumberText, ANanHasNoSign) {
  EXPECT_EQ(rounded_text(-std::nan("")), "nan");
  EXPECT_EQ(rounded_text(std::nan(""), 3), "nan");
  EXPECT_EQ(number_text(-std::nan("")), "nan");
}

// a results file writes a zero without its sign (issue 44: the CSVs held "-0"); a checkpoint's
// number keeps it, so that a resumed run starts from the same bits
TEST(NumberText, AValueOfZeroHasNoSign) {
  std::string s;
  append_value(s, -0.0);
  EXPECT_EQ(s, "0");
  s.clear();
  append_value(s, -1e-300);
  EXPECT_EQ(s, "-1e-300");
  EXPECT_EQ(number_text(-0.0), "-0");
}

}  // namespace
}  // namespace beltsim
