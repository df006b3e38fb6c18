// plot/sweep_plot.cpp: `beltsim plot` of a sweep's summary.csv: a series per value of a column
// (--by), the points it leaves out named with their status, the hints of its errors built from
// the file's own columns.
#include <gtest/gtest.h>

#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
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
  // an x column the file has not is not repeated in it
  EXPECT_NE(plot_example(csv, {"load"}).find("summary.csv' pretension 'slip_max [1]'"), std::string::npos);
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

// the rows of load x pretension, not in x order (a sweep's first list varies slowest; here shuffled)
std::string load_summary(const fs::path& d, const std::string& load_column = "load") {
  return write_file(d / "summary.csv", "point," + load_column +
                                           ",pretension,status,slip,tight [N]\n"
                                           "0,60,700,ok,0.1,1200\n1,60,300,ok,0.6,1000\n2,60,500,ok,0.25,1100\n"
                                           "3,40,500,ok,0.05,850\n4,40,300,ok,0.2,750\n5,40,700,ok,0.01,950\n");
}

// --by: a series per value of the column (trial 27 S1: the loads shared one colour, so the figure
// could not tell them apart), in increasing order, each in x order, titled with the value, a
// colour per value, a shape per column, joined
TEST(SweepPlot, ASeriesPerValueOfAColumn) {
  const fs::path d = dir("sweep_by");
  const std::string csv = load_summary(d);
  const PlotSpec spec = summary_spec(csv, {"pretension", "slip", "tight [N]"}, (d / "p.png").string(), "load");
  ASSERT_EQ(spec.series.size(), 4u);
  EXPECT_TRUE(spec.joined);
  const std::vector<std::pair<std::string, std::string>> names{
      {"slip", "load = 40"}, {"slip", "load = 60"}, {"tight", "load = 40"}, {"tight", "load = 60"}};
  for (size_t k = 0; k < 4; ++k) {
    EXPECT_EQ(spec.series[k].name, names[k].first);
    EXPECT_EQ(spec.series[k].variant, names[k].second);
    EXPECT_EQ(spec.series[k].colour, static_cast<int>(k % 2) + 1);
    EXPECT_EQ(spec.series[k].shape, static_cast<int>(k / 2));
    EXPECT_EQ(spec.series[k].t, (std::vector<double>{300, 500, 700}));  // x order
  }
  EXPECT_EQ(spec.series[0].y, (std::vector<double>{0.2, 0.05, 0.01}));  // load 40's, in x order
  EXPECT_EQ(spec.series[3].y, (std::vector<double>{1000, 1100, 1200}));
  EXPECT_EQ(spec.series[2].unit, "N");
  const std::string script = plot_script(spec, "p.png");
  EXPECT_NE(script.find("with linespoints"), std::string::npos) << script;
  EXPECT_NE(script.find("title 'slip, load = 40'"), std::string::npos) << script;
  EXPECT_NE(script.find("title 'tight [N], load = 60 (right axis)'"), std::string::npos) << script;
  // one column: the value alone titles its series; slip (of no known unit) keeps one axis
  const PlotSpec one = summary_spec(csv, {"pretension", "slip"}, (d / "p.png").string(), "load");
  const std::string one_script = plot_script(one, "p.png");
  EXPECT_NE(one_script.find("title 'load = 60'"), std::string::npos) << one_script;
  EXPECT_EQ(one_script.find("multiplot"), std::string::npos) << one_script;
  EXPECT_NE(one_script.find("set ylabel 'slip'"), std::string::npos) << one_script;
  // without --by, as before: a mark per point, unjoined, one series per column
  const PlotSpec plain = summary_spec(csv, {"pretension", "slip"}, (d / "p.png").string());
  EXPECT_EQ(plain.series.size(), 1u);
  EXPECT_FALSE(plain.joined);
  EXPECT_EQ(plot_script(plain, "p.png").find("linespoints"), std::string::npos);
  // drawn: a PNG
  EXPECT_TRUE(
      plot_csv(csv, {"pretension", "slip"}, -INFINITY, (d / "by.png").string(), INFINITY, "load").notes.empty());
  EXPECT_TRUE(fs::exists(d / "by.png"));
}

// the value's unit in the title: the column's, from its brackets or summary_units.csv; the values
// in increasing order as numbers however written, text in the order it comes
TEST(SweepPlot, ASeriesTitleHasTheValuesUnit) {
  const fs::path d = dir("sweep_by_unit");
  const std::string csv = load_summary(d, "load [N·m]");
  const PlotSpec spec = summary_spec(csv, {"pretension", "slip"}, (d / "p.png").string(), "load [N·m]");
  ASSERT_EQ(spec.series.size(), 2u);
  EXPECT_EQ(spec.series[0].variant, "load = 40 N·m");
  write_file(d / "summary_units.csv",
             "column,unit\npoint,\nload [N·m],N.m\npretension,N\nstatus,\nslip,1\ntight [N],N\n");
  EXPECT_EQ(summary_spec(csv, {"pretension", "slip"}, (d / "p.png").string(), "load [N·m]").series[1].variant,
            "load = 60 N·m");
  const fs::path e = dir("sweep_by_order");
  const std::string mixed = write_file(e / "summary.csv",
                                       "point,load,method,pretension,status,slip\n0,1e+05,radau,300,ok,1\n"
                                       "1,60,bdf,300,ok,2\n2,40.0,radau,500,ok,3\n3,40,bdf,500,ok,4\n");
  const PlotSpec numbers = summary_spec(mixed, {"pretension", "slip"}, (e / "p.png").string(), "load");
  ASSERT_EQ(numbers.series.size(), 3u);
  EXPECT_EQ(numbers.series[0].variant, "load = 40.0");  // 40.0 and 40: one value, as first written
  EXPECT_EQ(numbers.series[0].t, (std::vector<double>{500, 500}));
  EXPECT_EQ(numbers.series[1].variant, "load = 60");
  EXPECT_EQ(numbers.series[2].variant, "load = 1e+05");
  const PlotSpec words = summary_spec(mixed, {"pretension", "slip"}, (e / "p.png").string(), "method");
  ASSERT_EQ(words.series.size(), 2u);
  EXPECT_EQ(words.series[0].variant, "method = radau");
  EXPECT_EQ(words.series[1].variant, "method = bdf");
  EXPECT_EQ(words.series[1].y, (std::vector<double>{2, 4}));
}

// a series whose points differ in a third parameter has several at one x: joined, its line would
// zigzag between them; drawn unjoined, and said why
TEST(SweepPlot, ASeriesWithPointsAtOneXIsNotJoined) {
  const fs::path d = dir("sweep_by_third");
  const std::string csv = write_file(d / "summary.csv",
                                     "point,load,mu,pretension,status,slip\n0,40,0.3,300,ok,0.4\n1,40,0.3,500,ok,0.2\n"
                                     "2,40,1,300,ok,0.1\n3,40,1,500,ok,0.05\n4,60,0.3,300,ok,0.6\n5,60,1,300,ok,0.2\n");
  const PlotReport r = plot_csv(csv, {"pretension", "slip"}, -INFINITY, (d / "p.png").string(), INFINITY, "load");
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_EQ(r.notes[0],
            "--by load: the series load = 40 has several points at pretension = 300 (they differ in mu): the points "
            "are drawn unjoined, as a line through them would zigzag");
  EXPECT_FALSE(summary_spec(csv, {"pretension", "slip"}, (d / "p.png").string(), "load").joined);
  EXPECT_EQ(left_out_warnings(r), r.notes);
  EXPECT_TRUE(summary_spec(csv, {"pretension", "slip"}, (d / "p.png").string(), "load").series.size() == 2);
  EXPECT_TRUE(plot_csv(csv, {"pretension", "slip"}, -INFINITY, (d / "q.png").string(), INFINITY, "mu").notes.size() ==
              1);
}

// --by a column the file has not (a did-you-mean), one drawn, or on a time series: errors, nothing
// drawn; a point without a value of the column is named as left out
TEST(SweepPlot, ByRefusesWhatItCannotDraw) {
  const fs::path d = dir("sweep_by_refused");
  const std::string csv = load_summary(d);
  const std::string png = (d / "p.png").string();
  expect_error(
      [&] {
        plot_csv(csv, {"pretension", "slip"}, -INFINITY, png, INFINITY, "lod");
      },
      {"--by lod: ", "summary.csv has no column 'lod' (did you mean 'load'?); its columns: point, load,"});
  expect_error(
      [&] {
        plot_csv(csv, {"pretension", "slip"}, -INFINITY, png, INFINITY, "pretension");
      },
      {"pretension is drawn (x), so it cannot tell series apart too"});
  expect_error([&] { plot_csv(csv, {"pretension", "slip"}, -INFINITY, png, INFINITY, "slip"); }, {"slip is drawn (y)"});
  const std::string ts = write_file(d / "timeseries.csv", "t,driver.omega\n0,1\n0.1,2\n");
  expect_error([&] { plot_csv(ts, {"driver.omega"}, -INFINITY, png, INFINITY, "load"); },
               {"is a time series, drawn against t: a series per value of a column (load) is for a sweep's summary"});
  EXPECT_FALSE(fs::exists(png));
  const std::string gap = write_file(d / "gap.csv",
                                     "point,load,pretension,status,slip,mass\n0,40,300,ok,0.2,\n"
                                     "1,40,500,ok,0.1,2\n2,60,300,ok,0.3,3\n");
  const PlotReport r = plot_csv(gap, {"pretension", "slip"}, -INFINITY, png, INFINITY, "mass");
  ASSERT_EQ(r.points.size(), 1u);
  EXPECT_EQ(r.points[0], "point 0 (load=40, pretension=300): ok, but without a value of mass");
}

// the numbers after `what` in script, each time it comes with some ("set offsets graph 0.05, graph
// 0.05, ...": 0.05, 0.05, ...; "set y2range [600:1400]": 600, 1400; "set y2range [*:*]": none)
std::vector<std::vector<double>> numbers_after(const std::string& script, const std::string& what) {
  std::vector<std::vector<double>> all;
  for (size_t at = script.find(what); at != std::string::npos; at = script.find(what, at + 1)) {
    std::string line = script.substr(at + what.size(), script.find('\n', at) - at - what.size());
    for (char& ch : line)
      if (!(std::isdigit(static_cast<unsigned char>(ch)) || ch == '.' || ch == '-' || ch == 'e' || ch == '+')) ch = ' ';
    std::istringstream in(line);
    std::vector<double> v;
    for (std::string word; in >> word;) v.push_back(std::stod(word));
    if (!v.empty()) all.push_back(v);  // (not "[*:*]")
  }
  return all;
}

// a sweep's marks at the ends of the range were cut in half by the frame (trial 27 D3): x and y
// had a margin on one panel, but y2 (gnuplot's offsets widen x and y only) ended at its largest
// value, and stacked panels had none at the sides and bottom
TEST(SweepPlot, MarksAtTheEndsAreClearOfTheFrame) {
  const fs::path d = dir("sweep_margins");
  const std::string csv = load_summary(d);
  // two axes: y2's range set beyond the values (tight 750..1200 N)
  const std::string two = plot_script(summary_spec(csv, {"pretension", "slip", "tight [N]"}, "p.png"), "p.png");
  const auto y2 = numbers_after(two, "set y2range [");
  ASSERT_EQ(y2.size(), 1u) << two;
  ASSERT_EQ(y2[0].size(), 2u) << two;
  EXPECT_LE(y2[0][0], 750 - 0.04 * 450) << two;
  EXPECT_GE(y2[0][1], 1200 + 0.04 * 450) << two;
  EXPECT_LT(y2[0][1] - y2[0][0], 3 * 450) << two;  // a margin, not a squashed plot
  // stacked panels (three units): every side of every panel
  const std::string csv3 = write_file(d / "three.csv",
                                      "point,pretension,status,slip,tight [N],omega [rad/s]\n0,300,ok,0.2,750,-60\n"
                                      "1,500,ok,0.1,850,-65\n2,700,ok,0.05,950,-67\n");
  const PlotSpec stacked = summary_spec(csv3, {"pretension", "slip", "tight [N]", "omega [rad/s]"}, "p.png");
  const std::string panels = plot_script(stacked, "p.png");
  ASSERT_NE(panels.find("multiplot"), std::string::npos) << panels;
  const auto offsets = numbers_after(panels, "set offsets ");
  ASSERT_EQ(offsets.size(), 4u) << panels;  // the picture's, then each panel's
  for (size_t p = 0; p < offsets.size(); ++p) {
    const std::vector<double>& o = offsets[p];
    ASSERT_EQ(o.size(), 4u) << panels;
    EXPECT_GE(o[0], 0.04) << panels;  // left
    EXPECT_GE(o[1], 0.04) << panels;  // right
    EXPECT_GE(o[3], 0.04) << panels;  // bottom
    if (p > 0) {
      EXPECT_GT(o[2], o[3]) << panels;  // top: a panel's legend's room and the margin
    }
  }
  // a time series' curves still reach the frame: no margin at its sides
  PlotSpec lines = stacked;
  lines.points = false;
  for (const auto& o : numbers_after(plot_script(lines, "p.png"), "set offsets ")) {
    EXPECT_EQ(o[0], 0);
    EXPECT_EQ(o[1], 0);
  }
  EXPECT_TRUE(numbers_after(plot_script(lines, "p.png"), "set y2range [").empty());
}

}  // namespace
}  // namespace beltsim::plot
