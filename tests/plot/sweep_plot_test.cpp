// plot/sweep_plot.cpp: `beltsim plot` of a sweep's summary.csv: the hints of its errors built
// from the file's own columns.
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
  EXPECT_TRUE(plot_csv(csv, {"pretension", "slip_max [1]"}, -INFINITY, (d / "p.png").string()).empty());
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

}  // namespace
}  // namespace beltsim::plot
