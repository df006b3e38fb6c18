// The points of a sweep (src/sweep/points.hpp) and the Slurm array's index list (slurm.hpp).
#include "sweep/points.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "sweep/slurm.hpp"

namespace beltsim::sweep {
namespace {

TEST(SweepPoints, TheGridCrossesTheListsTheLastFastest) {
  const Grid g{{"a", "b"}, {{Value(1LL), Value(2LL)}, {Value(0.5), Value(std::string("x")), Value(true)}}};
  const std::vector<Point> p = grid_points(g);
  ASSERT_EQ(p.size(), 6u);
  std::vector<std::string> seen;
  for (const Point& q : p)
    seen.push_back(q.id + ":" + value_text(q.params[0].second) + "," + value_text(q.params[1].second));
  EXPECT_EQ(seen, (std::vector<std::string>{"0:1,0.5", "1:1,x", "2:1,true", "3:2,0.5", "4:2,x", "5:2,true"}));
  EXPECT_THROW(grid_points(Grid{{"a"}, {{}}}), std::invalid_argument);
}

TEST(SweepPoints, IdsHaveTheWidthOfTheLast) {
  EXPECT_EQ(point_id(7, 120), "007");
  EXPECT_EQ(point_id(119, 120), "119");
  EXPECT_EQ(point_id(0, 1), "0");
  EXPECT_EQ(point_id(9, 10), "9");
  EXPECT_EQ(point_id(9, 11), "09");
}

TEST(SweepPoints, NumbersKeepFullPrecision) {
  EXPECT_EQ(value_text(Value(0.1 + 0.2)), "0.30000000000000004");
  EXPECT_EQ(value_text(Value(300LL)), "300");
}

TEST(SweepPoints, ParametersForMessagesAreNamedInTheSweepsOrder) {
  const std::vector<Point> p = grid_points(Grid{{"mu", "how"}, {{Value(0.1 + 0.2)}, {Value(std::string("run"))}}});
  EXPECT_EQ(params_text(p[0]), "mu=0.30000000000000004, how=\"run\"");  // a string quoted
  EXPECT_EQ(params_text(Point{}), "");
}

TEST(SweepPoints, SamplesAreReproducibleAndInTheirRanges) {
  const Samples s{200, {"mu", "pretension"}, {{0.2, 0.8}, {300, 600}}, 42};
  const std::vector<Point> a = sample_points(s), b = sample_points(s);
  ASSERT_EQ(a.size(), 200u);
  double lo = 1, hi = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(value_text(a[i].params[0].second), value_text(b[i].params[0].second));
    const double mu = std::get<double>(a[i].params[0].second), f = std::get<double>(a[i].params[1].second);
    EXPECT_TRUE(mu >= 0.2 && mu < 0.8) << mu;
    EXPECT_TRUE(f >= 300 && f < 600) << f;
    lo = std::min(lo, mu), hi = std::max(hi, mu);
  }
  // 200 uniform draws leave no gap wider than 0.1 at the ends but with probability (5/6)^200
  EXPECT_LT(lo, 0.3);
  EXPECT_GT(hi, 0.7);
  Samples other = s;
  other.seed = 43;
  EXPECT_NE(value_text(sample_points(other)[0].params[0].second), value_text(a[0].params[0].second));
  EXPECT_THROW(sample_points(Samples{0, {"mu"}, {{0, 1}}, 1}), std::invalid_argument);
  EXPECT_THROW(sample_points(Samples{3, {"mu"}, {{1, 0}}, 1}), std::invalid_argument);
}

TEST(SweepSlurm, ArrayIndicesAsRanges) {
  EXPECT_EQ(index_ranges({0, 1, 2, 3, 7, 9, 10, 11, 12}), "0-3,7,9-12");
  EXPECT_EQ(index_ranges({5}), "5");
  EXPECT_EQ(index_ranges({}), "");
}

}  // namespace
}  // namespace beltsim::sweep
