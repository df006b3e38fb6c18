// plot/sweep_plot.cpp: `beltsim plot` of a sweep's summary.csv: the points it leaves out named
// with their status, the hints of its errors built from the file's own columns.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

#include "plot/plot.hpp"
#include "plot_test_support.hpp"

namespace beltsim::plot {
namespace {

namespace fs = std::filesystem;

std::string write_file(const fs::path& p, const std::string& text) {
  std::ofstream(p) << text;
  return p.string();
}

// a sweep file's summary: the grid mu x pretension, figures named with their units in brackets,
// one of them repeating a parameter
std::string bracketed_summary(const fs::path& d) {
  return write_file(d / "summary.csv",
                    "point,mu,pretension,status,pretension [N],slip_max [1],tight [N]\n"
                    "0,0.3,300,ok,300,0.5,700\n1,0.3,500,ok,500,0.25,800\n2,0.3,700,ok,700,0.1,900\n"
                    "3,1,300,ok,300,0.2,650\n4,1,500,ok,500,0.1,750\n5,1,700,ok,700,0.05,850\n");
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

// a figure's name without its unit bracket (the part most easily left out, trial 27) is suggested,
// not taken: `pretension` and `pretension [N]` may both be columns, a parameter and a figure that
// repeats it, which differ where a point failed
TEST(SweepPlot, AColumnNamedButForItsUnitIsSuggested) {
  const fs::path d = dir("sweep_unit_suggested");
  const std::string csv = bracketed_summary(d);
  expect_error(
      [&] {
        plot_csv(csv, {"pretension", "slip_max"}, -INFINITY, (d / "p.png").string());
      },
      {"has no column 'slip_max' (did you mean 'slip_max [1]'?); its columns: point, mu,"});
  EXPECT_FALSE(fs::exists(d / "p.png"));
  // either name may have the bracket; both columns that match are offered
  expect_error(
      [&] {
        plot_csv(csv, {"pretension [kN]", "tight [N]"}, -INFINITY, (d / "p.png").string());
      },
      {"no column 'pretension [kN]' (did you mean 'pretension' or 'pretension [N]'?)"});
  // a slip of the finger as well as the unit left out
  EXPECT_EQ(column_suggestion("slip_mx", {"mu", "slip_max [1]"}), " (did you mean 'slip_max [1]'?)");
  // names without brackets as before
  EXPECT_EQ(column_suggestion("drivr.omega", {"t", "driver.omega", "span.tension"}), " (did you mean 'driver.omega'?)");
  EXPECT_EQ(column_suggestion("hub", {"t", "driver.omega"}), "");
}

// too few columns named: the example command line names the file's own columns (it named a fixed
// `slip`, not a column of most summaries): the parameter of most values as x, the first figure of
// its own (not the one repeating a parameter) as y, and it draws
TEST(SweepPlot, TheExampleNamesTheFilesOwnColumns) {
  const fs::path d = dir("sweep_example");
  const std::string csv = bracketed_summary(d);
  const std::string none = error_of([&] { plot_csv(csv, {}, -INFINITY, (d / "p.png").string()); });
  EXPECT_NE(none.find("name the x column and at least one y column, e.g. beltsim plot "), std::string::npos) << none;
  EXPECT_NE(none.find("summary.csv' pretension 'slip_max [1]'; its columns: point, mu, pretension, status,"),
            std::string::npos)
      << none;
  EXPECT_EQ(none.find(" slip;"), std::string::npos) << none;
  // the x column named is kept
  const std::string x_only = error_of([&] { plot_csv(csv, {"mu"}, -INFINITY, (d / "p.png").string()); });
  EXPECT_NE(x_only.find("summary.csv' mu 'slip_max [1]';"), std::string::npos) << x_only;
  EXPECT_EQ(plot_example(csv, {}).substr(0, 13), "beltsim plot ");
  EXPECT_TRUE(plot_csv(csv, {"pretension", "slip_max [1]"}, -INFINITY, (d / "p.png").string()).columns.empty());
  EXPECT_TRUE(fs::exists(d / "p.png"));
  // no column of numbers but the parameter: no example, the columns still listed
  fs::create_directories(d / "text");
  const std::string text =
      write_file(d / "text" / "summary.csv", "point,mu,status,note\n0,0.3,\"error: boom\",\n1,0.5,ok,fine\n");
  const std::string bare = error_of([&] { plot_csv(text, {}, -INFINITY, (d / "p.png").string()); });
  EXPECT_NE(bare.find("name the x column and at least one y column; its columns: point, mu, status, note"),
            std::string::npos)
      << bare;
}

// a point without a mark (failed, not run, outdated, or ok without the values drawn) is named with
// its parameters and why, in the summary's order (trial 27: 2 of 6 points left out, nothing said)
TEST(SweepPlot, PointsWithoutAMarkAreNamedWithTheirStatus) {
  const fs::path d = dir("sweep_left_out");
  const std::string long_error = "error: " + std::string(300, 'x');
  const std::string csv = write_file(d / "summary.csv",
                                     "point,load,pretension,status,slip,tight [N]\n"
                                     "0,40,300,ok,0.5,700\n"
                                     "1,40,-100,\"error: belt.pretension must be > 0 (got -100 N)\",,\n"
                                     "2,60,300,ok,,\n"
                                     "3,60,500,not run,,\n"
                                     "4,60,700,\"outdated: the file has changed\",,\n"
                                     "5,60,900,\"diverged at t = 0.05 s: runs away\",,\n"
                                     "6,60,1100,ok,,900\n"
                                     "7,80,300," +
                                         long_error + ",,\n");
  const PlotReport r = plot_csv(csv, {"pretension", "slip", "tight [N]"}, -INFINITY, (d / "p.png").string());
  EXPECT_TRUE(fs::exists(d / "p.png"));
  EXPECT_TRUE(r.columns.empty());
  EXPECT_EQ(r.of_points, 8u);
  ASSERT_EQ(r.points.size(), 6u);
  EXPECT_EQ(r.points[0], "point 1 (load=40, pretension=-100): error: belt.pretension must be > 0 (got -100 N)");
  EXPECT_EQ(r.points[1], "point 2 (load=60, pretension=300): ok, but without a value of slip or tight");
  EXPECT_EQ(r.points[2], "point 3 (load=60, pretension=500): not run");
  EXPECT_EQ(r.points[3], "point 4 (load=60, pretension=700): outdated: the file has changed");
  EXPECT_EQ(r.points[4], "point 5 (load=60, pretension=900): diverged at t = 0.05 s: runs away");
  // (point 6 has a value of one column: drawn) a long status is shortened
  EXPECT_EQ(r.points[5].find("point 7 (load=80, pretension=300): error: xxx"), 0u);
  EXPECT_LT(r.points[5].size(), 220u);
  EXPECT_EQ(r.points_why, "3 failed, 1 not run, 1 outdated, 1 ok without a value");
  const std::vector<std::string> w = left_out_warnings(r);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_EQ(w[0].substr(0, w[0].find('\n')),
            "left out of the plot, with nothing to draw: 6 of the 8 points (3 failed, 1 not run, 1 outdated, 1 ok "
            "without a value):");
  EXPECT_NE(w[0].find("\n  point 3 (load=60, pretension=500): not run\n"), std::string::npos) << w[0];
  // a point without x is left out whatever its figures
  const std::string no_x = write_file(d / "no_x.csv", "point,mu,status,x,slip\n0,0.3,ok,1,2\n1,0.5,ok,,3\n");
  const PlotReport rx = plot_csv(no_x, {"x", "slip"}, -INFINITY, (d / "x.png").string());
  ASSERT_EQ(rx.points.size(), 1u);
  EXPECT_EQ(rx.points[0], "point 1 (mu=0.5): ok, but without a value of x");
  // every point drawn: nothing to say
  const PlotReport all = plot_csv(bracketed_summary(d), {"pretension", "tight [N]"}, -INFINITY, (d / "a.png").string());
  EXPECT_TRUE(all.points.empty());
  EXPECT_TRUE(left_out_warnings(all).empty());
}

// a sweep of many failed points: the first ten listed, the others counted
TEST(SweepPlot, ManyLeftOutPointsAreCounted) {
  PlotReport r;
  r.of_points = 30;
  r.points_why = "25 failed";
  for (int k = 0; k < 25; ++k) r.points.push_back("point " + std::to_string(k) + ": error: boom");
  const std::vector<std::string> w = left_out_warnings(r);
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NE(w[0].find("\n  point 9: error: boom\n  and 15 more (their status is in the summary)"), std::string::npos)
      << w[0];
  EXPECT_EQ(w[0].find("point 10:"), std::string::npos) << w[0];
}

}  // namespace
}  // namespace beltsim::plot
