// The span tensions' ripple watch (sim/ripple_watch.hpp) on made-up samples: it warns once, when
// at least kRippleSamples samples, and more than kRippleFraction of them, had a span whose
// tension was more than kRippleShare of the largest tension away from its interval's mean; it
// names the worst span and its swing. The drives it was measured on are in the physics test
// accuracy_contract.
#include "sim/ripple_watch.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace beltsim {
namespace {

const std::vector<std::string> kNames{"span_a_b", "span_b_a"};

// n samples of two spans about 500 N and 300 N; span b_a swings by `swing` [N] about its mean in
// the samples k with rippled(k); the first row has no means (NaN), as a run's first row
struct Feed {
  RippleWatch w;
  std::vector<std::string> said;
  void run(int n, double swing, bool (*rippled)(int)) {
    for (int k = 0; k < n; ++k) {
      const double dev = rippled(k) ? swing * (k % 2 ? 1 : -1) : 0;
      const std::vector<double> T{500, 300 + dev}, mean{k == 0 ? NAN : 500, k == 0 ? NAN : 300};
      if (std::string s = w.add(T, mean, kNames); !s.empty()) said.push_back(s);
    }
  }
};

bool always(int) { return true; }
bool one_in_five(int k) { return k % 5 == 0; }

TEST(RippleWatch, WarnsOnceOfASteadyRippleNamingTheSpan) {
  Feed f;
  f.run(200, 20, always);  // 20 N of the largest 500 N: 4 %
  ASSERT_EQ(f.said.size(), 1u);
  EXPECT_NE(f.said[0].find("span_b_a swings by up to 20 N"), std::string::npos) << f.said[0];
  EXPECT_NE(f.said[0].find("(4 % of the largest tension, 500 N) in 20 of 20 samples"), std::string::npos) << f.said[0];
}

TEST(RippleWatch, QuietBelowTheShareOrInFewSamples) {
  Feed small, rare, few;
  small.run(400, 0.014 * 500, always);  // under 1.5 % of the largest tension
  rare.run(400, 20, one_in_five);       // 20 % of the samples, under the quarter
  few.run(kRippleSamples, 20, always);  // the first row has no interval: 19 counted
  EXPECT_TRUE(small.said.empty()) << small.said[0];
  EXPECT_TRUE(rare.said.empty()) << rare.said[0];
  EXPECT_TRUE(few.said.empty()) << few.said[0];
}

}  // namespace
}  // namespace beltsim
