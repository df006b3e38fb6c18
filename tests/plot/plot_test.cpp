// plot/: the CSV reader (its errors name file:line), the unit table, PNGs drawn by gnuplot at
// the size asked (read back with libpng), a missing column listing the valid ones, paths and
// titles with quotes and spaces, gnuplot missing or failing, the Campbell diagram (the wp picture:
// wp_plot_test.cpp).
#include "plot/plot.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "io/number_text.hpp"
#include "io/units.hpp"
#include "media/png_writer.hpp"
#include "plot/campbell_plot.hpp"
#include "plot/gnuplot.hpp"
#include "plot_test_support.hpp"
#include "support/scratch.hpp"

namespace beltsim::plot {
namespace {

namespace fs = std::filesystem;

std::string write(const fs::path& p, const std::string& text) {
  std::ofstream(p) << text;
  return p.string();
}

// two pulleys' speeds and a span tension over 0.1 s, as beltsim writes them
std::string small_csv(const fs::path& d) {
  std::string s = "t,driver.omega,driven.omega,span_driver_driven.tension,probe.slip_velocity\n";
  for (int k = 0; k <= 100; ++k) {
    const double t = 1e-3 * k;
    s += std::to_string(t) + "," + std::to_string(-700 * t * t) + "," + std::to_string(-690 * t * t + 0.1 * std::sin(300 * t)) +
         "," + std::to_string(500 + 300 * t) + "," + (k < 30 ? "nan" : std::to_string(0.01 * std::sin(200 * t))) + "\n";
  }
  return write(d / "timeseries.csv", s);
}

TEST(Units, TimeseriesColumnsAndFields) {
  EXPECT_EQ(unit_of("t"), "s");
  EXPECT_EQ(unit_of("driver.omega"), "rad/s");
  EXPECT_EQ(unit_of("driver.torque"), "N·m");
  EXPECT_EQ(unit_of("driven.belt_torque"), "N·m");
  EXPECT_EQ(unit_of("idler.hub_load"), "N");
  EXPECT_EQ(unit_of("span_driver_driven.tension"), "N");
  EXPECT_EQ(unit_of("probe.sde_force"), "N");
  EXPECT_EQ(unit_of("probe.normal_force"), "N");
  EXPECT_EQ(unit_of("probe.friction_force"), "N");
  EXPECT_EQ(unit_of("probe.slip_velocity"), "m/s");
  EXPECT_EQ(unit_of("energy.mechanical"), "J");
  EXPECT_EQ(unit_of("energy.dissipated_friction"), "J");
  EXPECT_EQ(unit_of("angle"), "rad");
  EXPECT_EQ(unit_of("element.phi"), "rad");
  EXPECT_EQ(unit_of("x"), "m");
  EXPECT_EQ(unit_of("slip"), "m/s");
  EXPECT_EQ(unit_of("normal"), "N");
  EXPECT_EQ(unit_of("mu"), "");
  EXPECT_EQ(unit_of("something.unknown"), "");
}

TEST(Csv, ReadsColumnsByName) {
  const fs::path d = dir("read");
  const Table t = read_timeseries_csv(write(d / "a.csv", "t,a.omega,b\n0,1,nan\n0.5, 2 ,\r\n\n1,3e-1,-4\n"));
  ASSERT_EQ(t.names, (std::vector<std::string>{"t", "a.omega", "b"}));
  EXPECT_EQ(t.column("t"), (std::vector<double>{0, 0.5, 1}));
  EXPECT_EQ(t.column("a.omega"), (std::vector<double>{1, 2, 0.3}));
  EXPECT_TRUE(std::isnan(t.column("b")[0]));
  EXPECT_TRUE(std::isnan(t.column("b")[1]));  // an empty field
  EXPECT_EQ(t.column("b")[2], -4);
}

TEST(Csv, ABadRowNamesFileAndLine) {
  const fs::path d = dir("bad");
  const std::string few = write(d / "few.csv", "t,x\n0,1\n1\n");
  expect_error([&] { read_timeseries_csv(few); }, {few + ":3:", "expected 2 fields", "got 1"});
  const std::string word = write(d / "word.csv", "t,x\n0,1\n1,2\n2,abc\n");
  expect_error([&] { read_timeseries_csv(word); }, {word + ":4:", "column 'x'", "'abc' is not a number"});
  const std::string hex = write(d / "hex.csv", "t,x\n0,0x10\n");
  expect_error([&] { read_timeseries_csv(hex); }, {hex + ":2:", "'0x10'"});
  expect_error([&] { read_timeseries_csv((d / "none.csv").string()); }, {"cannot read", "none.csv"});
  expect_error([&] { read_timeseries_csv(write(d / "empty.csv", "")); }, {"empty"});
}

// a quoted cell may hold line breaks, as csv_text writes a sweep's text values and figures into
// summary.csv: the row runs on to its closing quote, and a later row's line number counts them
TEST(Csv, AQuotedLineBreakStaysInsideItsRow) {
  const fs::path d = dir("quoted");
  const std::string csv =
      write(d / "summary.csv", "point,note,x,status\n0,\"one\ntwo\r\nthree\",1,ok\r\n1,\"a,b\",2,ok\n2,c,z,ok\n");
  const std::vector<std::string> only{"x"};
  expect_error([&] { read_timeseries_csv(csv, &only); }, {csv + ":6:", "column 'x'", "'z' is not a number"});
  const Table t =
      read_timeseries_csv(write(d / "ok.csv", "point,note,x,status\n0,\"one\ntwo\",1,ok\n1,\"a,b\",2,ok\n"), &only);
  EXPECT_EQ(t.column("x"), (std::vector<double>{1, 2}));
}

TEST(Plot, TwoSeriesFromACsvGiveAPngOfTheSizeAsked) {
  const fs::path d = dir("two");
  const std::string csv = small_csv(d);
  const std::string png = (d / "speeds.png").string();
  plot_csv(csv, {"driver.omega", "driven.omega"}, 0, png);
  const Image img = read_png(png);
  EXPECT_EQ(img.width, 1280);
  EXPECT_EQ(img.height, 720);
  EXPECT_GT(fs::file_size(png), 5000u);  // drawn, not blank
  // any size; two units on two axes; a gap where the speed is undefined
  const Table t = read_timeseries_csv(csv);
  PlotSpec spec{"tension and slip", {}, (d / "small.png").string(), 640, 400};
  spec.series.push_back({"span.tension", "N", t.column("t"), t.column("span_driver_driven.tension")});
  spec.series.push_back({"probe.slip_velocity", "m/s", t.column("t"), t.column("probe.slip_velocity")});
  plot_png(spec);
  const Image small = read_png(spec.file);
  EXPECT_EQ(small.width, 640);
  EXPECT_EQ(small.height, 400);
}

TEST(Plot, DefaultColumnsAreThePulleySpeedsAndFromCutsTheStart) {
  const fs::path d = dir("default");
  const std::string csv = small_csv(d);
  plot_csv(csv, {}, 0.05, (d / "plot.png").string());
  EXPECT_EQ(read_png((d / "plot.png").string()).width, 1280);
  expect_error([&] { plot_csv(csv, {}, 7, (d / "late.png").string()); }, {"no samples at t >= 7 s", "0.1 s"});
  const std::string no_speed = write(d / "tension.csv", "t,span_a_b.tension\n0,1\n1,2\n");
  expect_error([&] { plot_csv(no_speed, {}, 0, (d / "x.png").string()); }, {"no '<pulley>.omega' column", "t, span_a_b.tension"});
}

TEST(Plot, AMissingColumnSuggestsAndListsTheValidOnes) {
  const fs::path d = dir("missing");
  const std::string csv = small_csv(d);
  expect_error([&] { plot_csv(csv, {"driver.omega", "drivr.omega"}, 0, (d / "x.png").string()); },
               {"no column 'drivr.omega' (did you mean 'driver.omega'?)",
                "its columns: t, driver.omega, driven.omega, span_driver_driven.tension, probe.slip_velocity"});
  EXPECT_FALSE(fs::exists(d / "x.png"));
}

// a column with no finite value (a creep undefined at rest; a figure every point of a sweep failed
// to give) is left out and named, the rest drawn (it failed the whole picture); all of them: an error
TEST(Plot, AColumnWithoutAFiniteValueIsLeftOutAndNamed) {
  const fs::path d = dir("nan_column");
  const std::string csv = write(d / "timeseries.csv", "t,driver.omega,driver.creep\n0,1,nan\n0.1,2,nan\n");
  EXPECT_EQ(plot_csv(csv, {"driver.omega", "driver.creep"}, 0, (d / "x.png").string()).columns,
            std::vector<std::string>{"driver.creep"});
  EXPECT_EQ(read_png((d / "x.png").string()).width, 1280);
  EXPECT_EQ(left_out_warning({"driver.creep"}), "left out of the plot, with no finite value to draw: driver.creep");
  EXPECT_EQ(left_out_warning({}), "");
  EXPECT_TRUE(plot_csv(csv, {"driver.omega"}, 0, (d / "y.png").string()).columns.empty());
  expect_error([&] { plot_csv(csv, {"driver.creep"}, 0, (d / "z.png").string()); },
               {"no finite value to draw in driver.creep"});
  const std::string sweep = write(d / "summary.csv", "point,mu,status,slip,x\n0,0.3,ok,1,\n1,0.5,\"error: boom\",,\n");
  EXPECT_EQ(plot_csv(sweep, {"mu", "slip", "x"}, -INFINITY, (d / "s.png").string()).columns,
            std::vector<std::string>{"x"});
}

// a sweep's summary is drawn against a column of its own: a start time is refused, not ignored (it
// drew every point whatever the time)
TEST(Plot, ASweepSummaryTakesNoStartTime) {
  const fs::path d = dir("summary_from");
  const std::string sweep = write(d / "summary.csv", "point,mu,status,slip\n0,0.3,ok,1\n1,0.5,ok,2\n");
  EXPECT_TRUE(is_sweep_summary(sweep));
  EXPECT_FALSE(is_sweep_summary(small_csv(d)));
  expect_error(
      [&] {
        plot_csv(sweep, {"mu", "slip"}, 400, (d / "s.png").string());
      },
      {"is a sweep's summary, drawn against a column of its own, not time"});
  EXPECT_FALSE(fs::exists(d / "s.png"));
}

// t named among a time series' columns (as a sweep summary's x column comes first) drew t against t
TEST(Plot, TimeIsNotAColumnOfATimeSeries) {
  const fs::path d = dir("t_column");
  const std::string csv = small_csv(d);
  expect_error(
      [&] {
        plot_csv(csv, {"t", "driver.omega"}, 0, (d / "x.png").string());
      },
      {"is a time series: its columns are drawn against t, so name only the columns to draw (t is not one)"});
  EXPECT_FALSE(fs::exists(d / "x.png"));
}

TEST(Plot, QuotesAndSpacesInPathsAndTitles) {
  const fs::path d = dir("it's a \"quoted\" folder");
  const std::string csv = small_csv(d);
  const std::string png = (d / "pl'ot \\ x.png").string();
  plot_csv(csv, {"driver.omega"}, 0, png);  // the CSV's path, with its quotes, is the title
  EXPECT_EQ(read_png(png).height, 720);
  PlotSpec spec{"a 'title' with \"quotes\", a \\ and\na line break", {}, (d / "b.png").string()};
  spec.series.push_back({"it's", "N·m", {0, 1, 2}, {1, 2, 1}});
  plot_png(spec);
  EXPECT_TRUE(fs::exists(spec.file));
}

TEST(Plot, ThreeUnitsGiveStackedPanels) {
  const fs::path d = dir("panels");
  const std::string csv = small_csv(d);
  plot_csv(csv, {"driver.omega", "driven.omega", "span_driver_driven.tension", "probe.slip_velocity"}, 0,
           (d / "p.png").string());
  EXPECT_EQ(read_png((d / "p.png").string()).width, 1280);
}

// a series of three samples, 1 to 3 over 0.2 s
Series series(const std::string& name, const std::string& unit) {
  Series s;
  s.name = name, s.unit = unit, s.t = {0, 0.1, 0.2}, s.y = {1, 2, 3};
  return s;
}

// a stacked panel whose series' name is too long for its height is labelled by its quantity and
// unit ("tension [N]"), not by the unit alone (a user read a bare "[N]"); event labels sit on a
// box of their own, readable across a curve
TEST(Plot, APanelTooShortForItsSeriesNameIsLabelledByItsQuantity) {
  PlotSpec spec;
  spec.file = "unused.png";
  spec.series = {series("alt.omega", "rad/s"), series("alt.torque", "N·m"),
                 series("span_alternator_pump.tension", "N")};
  spec.marks = {{0.1, "wet mu = 0.25 on s in [0.1, 0.4] m"}};
  const std::string g = plot_script(spec, "p.png");
  EXPECT_NE(g.find("set ylabel 'alt.omega [rad/s]'"), std::string::npos) << g;
  EXPECT_NE(g.find("set ylabel 'tension [N]'"), std::string::npos) << g;
  EXPECT_EQ(g.find("set ylabel '[N]'"), std::string::npos) << g;
  EXPECT_NE(g.find("set style textbox opaque"), std::string::npos) << g;
  EXPECT_NE(g.find("front boxed"), std::string::npos) << g;
  // two quantities of one unit: not the first one's name for both, the unit alone
  spec.series.push_back(series("probe.sde_force", "N"));
  const std::string two = plot_script(spec, "p.png");
  EXPECT_EQ(two.find("set ylabel 'tension [N]'"), std::string::npos) << two;
  EXPECT_NE(two.find("set ylabel '[N]'"), std::string::npos) << two;
}

// stacked panels: an event's label at the window's very start was drawn under the top panel's
// legend (inside, top left), unreadable. The legends go to the right when labels on the left would
// cross them and fewer on the right; a label the legend still covers reads up to just below it.
// Marks at one time (an event and an overrun beginning at the window's start) share one label
TEST(Plot, ALabelAtTheWindowsStartIsClearOfTheLegend) {
  PlotSpec spec;
  spec.file = "unused.png";
  spec.series = {series("span_compressor_crankshaft.tension", "N"), series("tensioner.arm_angle", "rad"),
                 series("alternator.omega", "rad/s")};
  const auto label_at = [](const std::string& g, int k) {
    const std::string head = "set label " + std::to_string(k) + " ";
    const size_t at = g.find(head);
    return at == std::string::npos ? std::string() : g.substr(at, g.find('\n', at) - at);
  };
  spec.marks = {{0.1, "driven.torque -5"}};  // in the middle: as before, the legends on the left
  std::string g = plot_script(spec, "p.png");
  EXPECT_NE(g.find("set key inside left top"), std::string::npos) << g;
  EXPECT_NE(label_at(g, 1).find("at 0.1, graph 0.98 right"), std::string::npos) << label_at(g, 1);
  spec.marks = {{0, "alternator overruns"}, {0.1, "driven.torque -5"}, {0, "driven.torque -7"}};
  g = plot_script(spec, "p.png");
  EXPECT_NE(g.find("set key inside right top"), std::string::npos) << g;
  // (one label, shortened to the panel's height)
  EXPECT_EQ(label_at(g, 1).rfind("set label 1 'alternator overruns; dri\u2026' at 0, graph 0.98 right", 0), 0u)
      << label_at(g, 1);
  EXPECT_NE(label_at(g, 2).find("at 0.1, graph 0.98 right"), std::string::npos) << label_at(g, 2);
  EXPECT_EQ(label_at(g, 3), "");
  // one at each end: the legends stay on the left, the start's label below the legend
  spec.marks = {{0, "driven.torque -7"}, {0.2, "driven.torque -5"}};
  g = plot_script(spec, "p.png");
  EXPECT_NE(g.find("set key inside left top"), std::string::npos) << g;
  EXPECT_EQ(label_at(g, 1).find("graph 0.98"), std::string::npos) << label_at(g, 1);
  EXPECT_NE(label_at(g, 2).find("at 0.2, graph 0.98 right"), std::string::npos) << label_at(g, 2);
}

// a sweep's own figures have no known unit: each gets an axis of its own (a speed of -4 rad/s drew
// as a flat line at 0 beside loads of 1000 N on one shared axis), where series of one known unit
// share theirs
TEST(Plot, SeriesOfUnknownUnitsGetAxesOfTheirOwn) {
  PlotSpec spec;
  spec.file = "unused.png";
  auto series = [](const std::string& name, const std::string& unit, bool unknown) {
    Series s;
    s.name = name, s.unit = unit, s.t = {300, 500, 700}, s.y = {1, 2, 3}, s.unknown_unit = unknown;
    return s;
  };
  spec.series = {series("omega.driver", "", true), series("hub_load_mean", "", true)};
  const std::string own = plot_script(spec, "p.png");
  EXPECT_NE(own.find("set y2tics"), std::string::npos) << own;
  spec.series = {series("a.omega", "rad/s", false), series("b.omega", "rad/s", false)};
  const std::string shared = plot_script(spec, "p.png");
  EXPECT_EQ(shared.find("set y2tics"), std::string::npos) << shared;
  spec.series = {series("slip", "", true), series("omega.driver", "", true), series("s.hub_load_mean", "", true)};
  EXPECT_NE(plot_script(spec, "p.png").find("set multiplot layout 3,1"), std::string::npos);
}

// a sweep summary's columns: a unit from brackets only ("slip" is no element's slip in m/s here);
// a bracketed dimensionless figure shares no axis with one of unknown unit
TEST(Plot, ASweepSummarysUnitsComeFromBracketsOnly) {
  const fs::path d = dir("summary_units");
  const std::string csv = write(d / "summary.csv",
                                "point,pretension,status,slip,load [N],ratio [1]\n0,300,ok,-0.03,600,0.1\n"
                                "1,500,ok,-0.02,1000,0.2\n");
  const PlotSpec spec = summary_spec(csv, {"pretension", "slip", "load [N]", "ratio [1]"}, (d / "p.png").string());
  ASSERT_EQ(spec.series.size(), 3u);
  EXPECT_EQ(spec.series[0].name, "slip");
  EXPECT_EQ(spec.series[0].unit, "");
  EXPECT_TRUE(spec.series[0].unknown_unit);
  EXPECT_EQ(spec.series[1].name, "load");
  EXPECT_EQ(spec.series[1].unit, "N");
  EXPECT_FALSE(spec.series[1].unknown_unit);
  EXPECT_EQ(spec.series[2].unit, "");
  EXPECT_FALSE(spec.series[2].unknown_unit);
  EXPECT_EQ(spec.x_label, "pretension");
  // three axes: slip's own, N, and the dimensionless ratio's (not slip's)
  EXPECT_NE(plot_script(spec, "p.png").find("set multiplot layout 3,1"), std::string::npos);
}

// a summary with its summary_units.csv (a sweep's quick form: the result table's fields, whose
// units the program knows): each column's unit from that file, so the speeds share an axis in
// rad/s (they were drawn each on an axis of its own, of unknown unit: no brackets in their names)
TEST(Plot, ASweepSummarysUnitsComeFromItsUnitsFile) {
  const fs::path d = dir("summary_units_file");
  const std::string csv = write(d / "summary.csv",
                                "point,pretension,status,omega.driven,omega.driver,steps,slip\n"
                                "0,300,ok,-68,-69,4982,0.4\n1,500,ok,-68.5,-69,4990,0.3\n");
  write(d / "summary_units.csv",
        "column,unit\npoint,\npretension,\nstatus,\nomega.driven,rad/s\nomega.driver,rad/s\nsteps,1\nslip,\n");
  const PlotSpec spec =
      summary_spec(csv, {"pretension", "omega.driven", "omega.driver", "steps", "slip"}, (d / "p.png").string());
  ASSERT_EQ(spec.series.size(), 4u);
  EXPECT_EQ(spec.series[0].name, "omega.driven");
  for (int k : {0, 1}) {
    EXPECT_EQ(spec.series[k].unit, "rad/s");
    EXPECT_FALSE(spec.series[k].unknown_unit);
  }
  EXPECT_EQ(spec.series[2].unit, "");  // a count: dimensionless, known
  EXPECT_FALSE(spec.series[2].unknown_unit);
  EXPECT_TRUE(spec.series[3].unknown_unit);  // a figure the file gives no unit
  // three axes: rad/s (both speeds), the count's, slip's own
  EXPECT_NE(plot_script(spec, "p.png").find("set multiplot layout 3,1"), std::string::npos);
}

// events.csv's rows as marks: one per time, labels "what value" shortened, a cut row left out
TEST(Plot, EventsBecomeMarks) {
  const fs::path d = dir("events");
  EXPECT_TRUE(read_event_marks((d / "events.csv").string()).empty());  // no file: no marks
  const std::string events = write(d / "events.csv",
                                   "t,what,value\n"
                                   "0.02,driven.torque,-5\n"
                                   "0.02,wet,\"mu = 0.3 on s in [0, 0.3] m\"\n"
                                   "0.04,note,\"a note, with a comma, and long enough to be shortened\"\n"
                                   "0.05,cut");
  const std::vector<Mark> m = read_event_marks(events);
  ASSERT_EQ(m.size(), 2u);
  EXPECT_EQ(m[0].x, 0.02);
  EXPECT_EQ(m[0].label, "driven.torque -5; wet mu = 0.3 on s in [0, 0.3] m");
  EXPECT_EQ(m[1].x, 0.04);
  EXPECT_EQ(m[1].label, "note a note, with a comma, and long eno\u2026");
}

// the events beside a timeseries.csv are drawn as lines (every panel); outside the time range none
TEST(Plot, EventsBesideTheCsvAreDrawn) {
  const fs::path d = dir("marked");
  const std::string csv = small_csv(d);
  const std::vector<std::string> columns{"driver.omega", "span_driver_driven.tension", "probe.slip_velocity"};
  auto draw = [&](const std::string& name) {
    plot_csv(csv, {"driver.omega"}, 0, (d / (name + "_one.png")).string());
    plot_csv(csv, columns, 0, (d / (name + "_panels.png")).string());
    return std::pair{read_png((d / (name + "_one.png")).string()), read_png((d / (name + "_panels.png")).string())};
  };
  auto differing = [](const Image& a, const Image& b) {
    long n = 0;
    for (size_t k = 0; k < a.rgb.size(); k += 3) n += a.rgb[k] != b.rgb[k] || a.rgb[k + 1] != b.rgb[k + 1];
    return n;
  };
  const auto [plain_one, plain_panels] = draw("plain");
  write(d / "events.csv", "t,what,value\n0.5,late,1\n");  // after the last sample (0.1 s)
  const auto [late_one, late_panels] = draw("late");
  EXPECT_EQ(differing(plain_one, late_one), 0);
  EXPECT_EQ(differing(plain_panels, late_panels), 0);
  write(d / "events.csv", "t,what,value\n0.05,driven.torque,-5\n");
  const auto [marked_one, marked_panels] = draw("marked");
  // a dashed line across the plot (about 600 pixels high, half of them dashes) and its label
  EXPECT_GT(differing(plain_one, marked_one), 200);
  EXPECT_GT(differing(plain_panels, marked_panels), 200);
}

// an event at the window's very end: its label was drawn right of its line, which is the frame's
// right edge, outside the frame (over the right margin, or the right axis's numbers). It goes left
// of the line where it has no room on the right: the picture differs from the plain one only
// within the frame, one panel and stacked
TEST(Plot, ALabelAtTheWindowsEndIsInsideTheFrame) {
  PlotSpec spec;
  spec.file = "unused.png";
  spec.series = {series("driver.omega", "rad/s")};
  spec.marks = {{0.1, "driven.torque -5"}, {0.2, "note checkpoint end.ckpt saved"}};
  std::string g = plot_script(spec, "p.png");
  EXPECT_NE(g.find("at 0.1, graph 0.98 right rotate by 90 offset 1,0"), std::string::npos) << g;
  EXPECT_NE(g.find("at 0.2, graph 0.98 right rotate by 90 offset -0.8,0"), std::string::npos) << g;
  spec.series.push_back(series("span_driver_driven.tension", "N"));
  spec.series.push_back(series("probe.slip_velocity", "m/s"));
  g = plot_script(spec, "p.png");
  EXPECT_NE(g.find("at 0.1, graph 0.98 right rotate by 90 offset 1,0"), std::string::npos) << g;
  EXPECT_NE(g.find("at 0.2, graph 0.98 right rotate by 90 offset -0.8,0"), std::string::npos) << g;

  const fs::path d = dir("end_label");
  const std::string csv = small_csv(d);
  for (const std::vector<std::string>& columns :
       {std::vector<std::string>{"driver.omega"},
        std::vector<std::string>{"driver.omega", "span_driver_driven.tension", "probe.slip_velocity"}}) {
    fs::remove(d / "events.csv");
    plot_csv(csv, columns, 0, (d / "plain.png").string());
    write(d / "events.csv", "t,what,value\n0.1,note,checkpoint end.ckpt saved\n");  // the last sample's t
    plot_csv(csv, columns, 0, (d / "marked.png").string());
    const Image plain = read_png((d / "plain.png").string()), marked = read_png((d / "marked.png").string());
    ASSERT_EQ(plain.rgb.size(), marked.rgb.size());
    // the frame's right edge: the rightmost column dark over a third of the height
    int edge = -1;
    for (int x = 0; x < plain.width; ++x) {
      int dark = 0;
      for (int y = 0; y < plain.height; ++y) dark += plain.pixel(x, y)[0] < 100;
      if (dark > plain.height / 3) edge = x;
    }
    ASSERT_GT(edge, plain.width / 2) << columns.size();
    int differing = 0, right_of_edge = 0;
    for (int y = 0; y < plain.height; ++y)
      for (int x = 0; x < plain.width; ++x)
        if (std::memcmp(plain.pixel(x, y), marked.pixel(x, y), 3) != 0) ++differing, right_of_edge += x > edge;
    EXPECT_GT(differing, 200) << columns.size();  // the label is drawn
    EXPECT_EQ(right_of_edge, 0) << columns.size() << " columns, the frame's edge at x = " << edge;
  }
}

TEST(Plot, ClearErrors) {
  const fs::path d = dir("errors");
  PlotSpec spec{"", {}, (d / "x.png").string()};
  expect_error([&] { plot_png(spec); }, {"no series"});
  spec.series.push_back({"a", "", {0, 1}, {1}});
  expect_error([&] { plot_png(spec); }, {"'a' has 2 times but 1 values"});
  spec.series[0].y = {NAN, NAN};
  expect_error([&] { plot_png(spec); }, {"'a' has no finite values"});
  spec.series[0].y = {1, 2};
  // a missing folder is made, as for every output (it was "the folder ... does not exist")
  spec.file = (d / "no such folder" / "x.png").string();
  plot_png(spec);
  EXPECT_TRUE(fs::is_regular_file(spec.file));
}

TEST(Gnuplot, ItsOwnMessageWhenAScriptFails) {
  expect_error([] { run_gnuplot("plot $nothing using 1:2\n"); }, {"gnuplot failed (exit", "no datablock named $nothing"});
  EXPECT_EQ(gnuplot_string("it's"), "'it''s'");
  EXPECT_EQ(gnuplot_string("a\nb"), "'a b'");
}

TEST(Gnuplot, MissingIsSaidSo) {
  const std::string path = std::getenv("PATH") ? std::getenv("PATH") : "";
  const fs::path empty = dir("empty path");
  ::setenv("PATH", empty.c_str(), 1);
  try {
    run_gnuplot("print 1\n");
    ADD_FAILURE() << "gnuplot ran with an empty PATH";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("gnuplot not found"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("gnuplot-nox"), std::string::npos) << e.what();
  }
  ::setenv("PATH", path.c_str(), 1);
}

// the Campbell diagram's speed axis names the pulley swept (it said 'crankshaft' for any), and the
// modes above its frequency axis (twice the highest order at the top speed) are counted on it
TEST(Campbell, NamesThePulleyAndCountsTheModesAboveTheAxis) {
  auto point = [](double rpm, std::vector<double> freqs) {
    CampbellPoint p;
    p.rpm = rpm;
    p.analysis.groups = {"span_a_b"};
    for (double f : freqs) {
      Mode m;
      m.frequency = f, m.damping = 0.1, m.participation = {1.0};
      p.analysis.modes.push_back(m);
    }
    return p;
  };
  // orders 2 and 4 at 600 rpm: the axis ends at 2·40 Hz = 80 Hz (84 with its 5 %)
  const std::string g =
      campbell_script({point(300, {20, 60}), point(600, {70, 120, 186})}, {2, 4}, "t", "driver", "x.png");
  EXPECT_NE(g.find("set xlabel 'driver speed [rpm]'"), std::string::npos) << g;
  EXPECT_EQ(g.find("crankshaft"), std::string::npos) << g;
  EXPECT_NE(g.find("2 of 5 modes lie above 84 Hz, up to 186 Hz: campbell.csv lists them"), std::string::npos) << g;
  const std::string none = campbell_script({point(600, {20, 60})}, {2, 4}, "t", "driver", "x.png");
  EXPECT_EQ(none.find("lie above"), std::string::npos) << none;
}

}  // namespace
// a column constant up to rounding is drawn flat about its value, and a narrow range gets the digits
// that tell its tics apart (a user read eleven tics all labelled 500.106 over 1e-10 N of noise)
TEST(Plot, AFlatColumnIsDrawnFlatAndANarrowOneGetsItsDigits) {
  PlotSpec spec;
  spec.file = "unused.png";
  Series flat = series("span_driver_driven.tension", "N");
  flat.y = {500.106, 500.106 + 1e-10, 500.106 - 1e-10};
  spec.series = {flat};
  // the range an axis is set to: ±1 % of 500.106 N
  auto flat_range = [](const std::string& script, const std::string& axis) {
    const size_t at = script.find("set " + axis + "range [4");
    if (at == std::string::npos) return false;
    char* end = nullptr;
    const double lo = std::strtod(script.c_str() + at + axis.size() + 11, &end);
    const double hi = std::strtod(end + 1, nullptr);
    return std::abs(lo - 495.10494) < 1e-6 && std::abs(hi - 505.10706) < 1e-6;
  };
  std::string g = plot_script(spec, "p.png");
  EXPECT_TRUE(flat_range(g, "y")) << g;
  // 68.42 rad/s with a ripple of 1e-4 of it: tics 1.7e-3 apart need 6 significant digits,
  // 1e-6 of it 8
  Series speed = series("driver.omega", "rad/s");
  speed.y = {68.42, 68.42 + 6.8e-3, 68.42 - 1e-4};
  spec.series = {speed};
  g = plot_script(spec, "p.png");
  EXPECT_EQ(g.find("set format y '%."), std::string::npos) << g;
  speed.y = {68.42, 68.42 + 6.8e-5, 68.42};
  spec.series = {speed};
  g = plot_script(spec, "p.png");
  EXPECT_NE(g.find("set format y '%.8g'"), std::string::npos) << g;
  // stacked panels (three units) and the second axis (two) likewise
  spec.series = {series("driver.omega", "rad/s"), flat, series("probe.slip_velocity", "m/s")};
  g = plot_script(spec, "p.png");
  EXPECT_TRUE(flat_range(g, "y")) << g;
  spec.series = {series("driver.omega", "rad/s"), flat};
  g = plot_script(spec, "p.png");
  EXPECT_TRUE(flat_range(g, "y2")) << g;
}

}  // namespace beltsim::plot
