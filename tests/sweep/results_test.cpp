// A point's point.csv and the summary (src/sweep/results.hpp): every value, with line breaks,
// carriage returns, commas and quotes in it, read back exactly; the columns' names each once.
#include "sweep/results.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "io/csv_writer.hpp"
#include "support/files.hpp"
#include "support/scratch.hpp"

namespace beltsim::sweep {
namespace {

namespace fs = std::filesystem;

// a fresh folder for one test
std::string results_folder(const std::string& name) {
  const fs::path d = test::scratch_dir("beltsim_sweep_results_test") / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d.string();
}

const std::vector<std::string> kAwkward = {"a\rb", "c\nd", "e\r\nf", "g,\"h\"", "\"", "", " i ", "j\n", "\n"};

// a carriage return is quoted as a line break is (RFC 4180): a reader that ends lines at \r\n
// must not split the cell
TEST(SweepResults, CsvQuotesCarriageReturnsAndReadsRowsWithLineBreaks) {
  EXPECT_EQ(csv_text("a\rb"), "\"a\rb\"");
  EXPECT_EQ(csv_text("plain"), "plain");
  std::string text;
  for (const std::string& v : kAwkward) text += csv_text(v) + "," + csv_text(v + v) + "\n";
  std::vector<std::vector<std::string>> expected;
  for (const std::string& v : kAwkward) expected.push_back({v, v + v});
  EXPECT_EQ(csv_rows(text), expected);
  EXPECT_EQ(csv_rows("a,b\n\n1,\"2\n3\""), (std::vector<std::vector<std::string>>{{"a", "b"}, {""}, {"1", "2\n3"}}));
}

// each awkward value as a parameter and as a figure: written and read back the same, so the
// point is done and is not run again by the next sweep
TEST(SweepResults, PointValuesReadBackExactly) {
  const std::string dir = results_folder("round trip");
  std::vector<Value> values;
  for (const std::string& v : kAwkward) values.emplace_back(v);
  const std::vector<Point> points = grid_points(Grid{{"how"}, {values}});
  // what defined the points: a file with a comma, a quote and a space in its path
  const Inputs in{"test program", "--set 'a=1,\"2\"'", {{dir + "/a \"b\",c.lua", std::string(64, 'f')}}};
  for (const Point& p : points) {
    PointResult r;
    r.figures = {{"echo", value_text(p.params[0].second) + "\r\n!"}, {"n\nl", "x"}};
    r.inputs = inputs_text(in);
    write_point_result(dir, p, r);
    const auto back = read_point_result(dir, p);
    ASSERT_TRUE(back) << test::slurp(dir + "/" + p.id + "/point.csv");
    EXPECT_TRUE(back->ok());
    EXPECT_EQ(back->figures, r.figures);
    EXPECT_EQ(back->inputs, r.inputs);
    const auto parsed = parse_inputs(back->inputs);
    ASSERT_TRUE(parsed);
    EXPECT_EQ(parsed->files, in.files);
    EXPECT_EQ(parsed->options, in.options);
  }
  // the file is not there: no point is done now, each outdated, saying why
  Definition now{"test program", in.options, {}, {}};
  const SummaryCounts gone = write_summary(dir, points, now, Figures::kOwn);
  EXPECT_EQ(gone.not_run, static_cast<int>(points.size()));
  EXPECT_EQ(check_point(dir, points[0], now).changed,
            "the file " + in.files[0].first + ", which the point loaded, is gone or unreadable");
  now.hashes[in.files[0].first] = in.files[0].second;  // as if it were there with these bytes
  EXPECT_EQ(check_point(dir, points[0], now).changed, "");
  now.program = "another";
  EXPECT_EQ(check_point(dir, points[0], now).changed, "the program has changed (was test program)");
  now.program = "test program";
  const SummaryCounts c = write_summary(dir, points, now, Figures::kOwn);
  EXPECT_EQ(c.ok, static_cast<int>(points.size()));
  const auto rows = csv_rows(test::slurp(dir + "/summary.csv"));
  ASSERT_EQ(rows.size(), points.size() + 1);
  EXPECT_EQ(rows[0], (std::vector<std::string>{"point", "how", "status", "echo", "n\nl"}));
  for (std::size_t k = 0; k < points.size(); ++k)
    EXPECT_EQ(rows[k + 1], (std::vector<std::string>{points[k].id, kAwkward[k], "ok", kAwkward[k] + "\r\n!", "x"}));
}

// summary_units.csv names summary.csv's columns in order (rewritten with it as figures come): the
// unit a parameter's or a sweep file's figure's name gives in brackets, else none (a sweep's names
// are its own: "slip" is not read as an element's m/s); point and status are text
// A point whose run estimated its own error past the contract (check.over true) counts ok, and the
// sweep's lines say how many of the ok did (a trial's sweep said "3 ok" with one point's log
// saying "do not trust this run's answer")
TEST(SweepResults, PointsPastTheirCheckAreCountedAmongTheOk) {
  PointResult trusted, untrusted, unchecked, failed;
  trusted.figures = {{"check.over", "false"}, {"check.tension", "0.006"}};
  untrusted.figures = {{"check.tension", "0.0144"}, {"check.over", "true"}};
  failed.status = error_status("boom");
  failed.figures = {{"check.over", "true"}};
  SummaryCounts c;
  for (const PointResult& r : {trusted, unchecked, failed}) c.add(r);
  EXPECT_EQ(c.ok, 2);
  EXPECT_EQ(c.failed, 1);
  EXPECT_EQ(c.over, 0);
  EXPECT_EQ(c.over_text(), "");
  c.add(untrusted);
  EXPECT_EQ(c.ok, 3);
  EXPECT_EQ(c.over, 1);
  EXPECT_EQ(c.over_text(true), " (1 past its check)");
  EXPECT_NE(c.over_text().find("1 of them past its accuracy check (check.over in summary.csv"), std::string::npos)
      << c.over_text();
}

TEST(SweepResults, SummaryUnitsNameEveryColumn) {
  const std::string dir = results_folder("units");
  const std::vector<Point> points = grid_points(Grid{{"mu"}, {{Value(0.3), Value(1.0)}}});
  const Inputs in{"test program", "", {}};
  write_point_result(dir, points[0], PointResult{"ok", {{"slip", "0.1"}, {"hub load [N]", "800"}}, inputs_text(in)});
  write_point_result(dir, points[1],
                     PointResult{"ok", {{"slip", "0.2"}, {"odd,\"name\"\n[N.m]", "3"}}, inputs_text(in)});
  write_summary(dir, points, Definition{in.program, in.options, {}, {}}, Figures::kOwn);
  const auto summary = csv_rows(test::slurp(dir + "/summary.csv"));
  const auto units = csv_rows(test::slurp(dir + "/summary_units.csv"));
  ASSERT_FALSE(summary.empty());
  ASSERT_EQ(units.size(), summary[0].size() + 1);
  EXPECT_EQ(units[0], (std::vector<std::string>{"column", "unit"}));
  std::vector<std::string> names;
  for (std::size_t k = 1; k < units.size(); ++k) names.push_back(units[k][0]);
  EXPECT_EQ(names, summary[0]);
  EXPECT_EQ(units, (std::vector<std::vector<std::string>>{{"column", "unit"},
                                                          {"point", ""},
                                                          {"mu", ""},
                                                          {"status", ""},
                                                          {"slip", ""},
                                                          {"hub load [N]", "N"},
                                                          {"odd,\"name\"\n[N.m]", "N·m"}}));
}

// the quick form's figures are scene:run{}'s result table: their units come from the program's
// table of units (io/units.hpp, run_result_unit), not from their names' brackets, which they have
// none of (omega.driver had no unit); text and booleans have none, nor does a field a script
// added to the table (its own name, as a sweep file's)
TEST(SweepResults, TheQuickFormsUnitsAreTheResultTables) {
  const std::string dir = results_folder("quick_units");
  const std::vector<Point> points = grid_points(Grid{{"pretension"}, {{Value(300LL)}}});
  const Inputs in{"test program", "", {}};
  write_point_result(dir, points[0],
                     PointResult{"ok",
                                 {{"check.speed", "1e-4"},
                                  {"check.tension", "2e-3"},
                                  {"check.over", "false"},
                                  {"check.warned_t", "0.2"},
                                  {"csv", "out/p/0/timeseries.csv"},
                                  {"interrupted", "false"},
                                  {"omega.driven", "-68"},
                                  {"omega.driver", "-69"},
                                  {"slip", "0.4"},
                                  {"steps", "4982"},
                                  {"t", "1"},
                                  {"wall", "0.7"}},
                                 inputs_text(in)});
  write_summary(dir, points, Definition{in.program, in.options, {}, {}}, Figures::kRunResult);
  EXPECT_EQ(csv_rows(test::slurp(dir + "/summary_units.csv")),
            (std::vector<std::vector<std::string>>{{"column", "unit"},
                                                   {"point", ""},
                                                   {"pretension", ""},
                                                   {"status", ""},
                                                   {"check.speed", "1"},
                                                   {"check.tension", "1"},
                                                   {"check.over", ""},
                                                   {"check.warned_t", "s"},
                                                   {"csv", ""},
                                                   {"interrupted", ""},
                                                   {"omega.driven", "rad/s"},
                                                   {"omega.driver", "rad/s"},
                                                   {"slip", ""},
                                                   {"steps", "1"},
                                                   {"t", "s"},
                                                   {"wall", "s"}}));
}

// point.csv and summary.csv have the columns point, the parameters, status, the figures: a
// parameter may not take the name of another column, and a point whose figure does fails, saying so
TEST(SweepResults, EveryColumnHasItsOwnName) {
  for (const char* name : {"point", "status", "inputs"}) {
    EXPECT_THROW(grid_points(Grid{{"mu", name}, {{Value(1LL)}, {Value(2LL)}}}), std::invalid_argument) << name;
    EXPECT_THROW(sample_points(Samples{2, {name}, {{0, 1}}, 1}), std::invalid_argument) << name;
  }
  const Point p = grid_points(Grid{{"mu"}, {{Value(0.5)}}})[0];
  const PointResult good{"ok", {{"slip", "1"}, {"mu.x", "2"}}};
  EXPECT_EQ(unique_columns(p, good).status, "ok");
  EXPECT_EQ(unique_columns(p, good).figures, good.figures);
  const PointResult failed{"error: x.lua:3: boom", {}};
  EXPECT_EQ(unique_columns(p, failed).status, failed.status);
  for (const char* clash : {"point", "status", "mu", "slip"}) {
    const PointResult r = unique_columns(p, PointResult{"ok", {{"slip", "1"}, {clash, "2"}}});
    EXPECT_EQ(r.status.rfind("error: ", 0), 0u) << clash << ": " << r.status;
    EXPECT_NE(r.status.find(std::string("'") + clash + "'"), std::string::npos) << r.status;
    EXPECT_TRUE(r.figures.empty());
  }
}

// a point is matched by its folder, its number in the sweep's order: one that ran under another
// number (a value added inside a list) runs again, saying why, and the folders of numbers no point
// has now (the ids widened: 0..8 to 00..11) are moved out of the way, not taken for results
TEST(SweepResults, RenumberedPointsRunAgainAndStaleFoldersMoveAside) {
  const std::string dir = results_folder("renumbered");
  const Inputs in{"test program", "", {}};
  const auto write_all = [&](const std::vector<Point>& points) {
    for (const Point& p : points) write_point_result(dir, p, PointResult{"ok", {{"x", p.id}}, inputs_text(in)});
  };
  write_all(grid_points(Grid{{"mu"}, {{Value(0.3), Value(1.0)}}}));  // 0: 0.3, 1: 1
  Definition now{in.program, in.options, {}, {}};
  const std::vector<Point> added = grid_points(Grid{{"mu"}, {{Value(0.3), Value(0.5), Value(1.0)}}});
  const Results r = current_results(dir, added, now);
  ASSERT_EQ(r.size(), 3u);
  EXPECT_TRUE(r[0] && r[0]->ok());
  EXPECT_FALSE(r[1]);  // new: its folder holds mu = 1
  ASSERT_TRUE(r[2]);
  EXPECT_EQ(r[2]->status, std::string(kOutdated) + kRenumbered);
  EXPECT_EQ(rerun_reasons(r), (Reasons{{kRenumbered, 1}}));
  now.program = "another";  // its result's inputs not now's: that is the reason
  EXPECT_EQ(current_results(dir, added, now)[2]->status,
            std::string(kOutdated) + "the program has changed (was test program)");
  now.program = in.program;

  // ids widened: 0..10 to 00..11; a folder of no point (7, with a log only), "notes" and a
  // numbered folder of the user's are left where they are but for 7
  write_all(grid_points(Grid{{"k"}, {{Value(1LL), Value(2LL)}}}));
  std::vector<Value> twelve;
  for (long long k = 0; k < 12; ++k) twelve.emplace_back(k);
  const std::vector<Point> wide = grid_points(Grid{{"k"}, {twelve}});
  fs::create_directories(dir + "/7");
  test::spit(dir + "/7/log.txt", "beltsim sweep: point 7 of 8\n");
  fs::create_directories(dir + "/notes");
  fs::create_directories(dir + "/2024");
  fs::create_directories(dir + "/earlier/0");  // from before: 0 goes in as 0-2
  const OutputDir top(dir);
  EXPECT_EQ(move_stale_folders(top, wide), (std::vector<std::string>{"0", "1", "7"}));
  EXPECT_TRUE(fs::exists(dir + "/earlier/0-2/point.csv"));
  EXPECT_TRUE(fs::exists(dir + "/earlier/1/point.csv"));
  EXPECT_TRUE(fs::exists(dir + "/earlier/7/log.txt"));
  EXPECT_FALSE(fs::exists(dir + "/0"));
  EXPECT_TRUE(fs::is_directory(dir + "/notes"));
  EXPECT_TRUE(fs::is_directory(dir + "/2024"));
  EXPECT_EQ(moved_line("s", top, {"0", "1"}), "sweep s: 2 folders of no point now moved to " + dir + "/earlier/: 0, 1");
  EXPECT_EQ(move_stale_folders(top, wide), std::vector<std::string>{});
}

// a folder moved to DIR/earlier/ names itself there in point.csv (its status and figures, not its
// parameters or inputs) and in every parameters.csv in it; a path that only looks like it (DIR/10,
// /x/DIR/1, DIR/1x, DIR/1.csv) and the other files stay as they were
TEST(SweepResults, MovedFoldersNameTheirNewPlace) {
  const std::string dir = results_folder("moved");
  const std::string one = dir + "/1", ten = dir + "/10", new_one = dir + "/earlier/1";
  const std::vector<Point> before = grid_points(Grid{{"at"}, {{Value(std::string("b")), Value(one)}}});
  write_point_result(dir, before[1],
                     PointResult{"diverged at t = 0.1 s: s.lua:3: runs away (the samples up to then are in " + one +
                                     "/timeseries.csv)",
                                 {{"csv", one + "/timeseries.csv"},
                                  {"folder", one},
                                  {"quoted", "\"" + one + "\",\n" + one + "/a"},
                                  {"others", ten + " /x" + one + " " + one + "x " + one + ".csv"}},
                                 "program: p\noptions: \nfile " + std::string(64, 'a') + " " + one + "/s.lua\n"});
  const std::string params = "name,value,unit,source,note\nbelt.mu,1,,given,\"a, note\"\nrun.out," + one +
                             ",,run,the output folder\nrun.frames.png,\"" + one + "/a,b\",,run,\"x\"\"y\"\n";
  test::spit(one + "/parameters.csv", params);
  fs::create_directories(one + "/sub");
  test::spit(one + "/sub/parameters.csv", "run.out," + one + "/sub,,run,\n");
  test::spit(one + "/log.txt", "the samples are in " + one + "/timeseries.csv\n");
  const std::vector<Point> now = grid_points(Grid{{"at"}, {{Value(std::string("c"))}}});
  EXPECT_EQ(move_stale_folders(OutputDir(dir), now), std::vector<std::string>{"1"});
  const std::optional<PointResult> r = read_point_result(dir + "/earlier", Point{1, "1", before[1].params});
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status,
            "diverged at t = 0.1 s: s.lua:3: runs away (the samples up to then are in " + new_one + "/timeseries.csv)");
  EXPECT_EQ(r->figures, (std::vector<std::pair<std::string, std::string>>{
                            {"csv", new_one + "/timeseries.csv"},
                            {"folder", new_one},
                            {"quoted", "\"" + new_one + "\",\n" + new_one + "/a"},
                            {"others", ten + " /x" + one + " " + one + "x " + one + ".csv"}}));
  EXPECT_EQ(r->inputs, "program: p\noptions: \nfile " + std::string(64, 'a') + " " + one + "/s.lua\n");
  EXPECT_EQ(test::slurp(new_one + "/parameters.csv"),
            "name,value,unit,source,note\nbelt.mu,1,,given,\"a, note\"\nrun.out," + new_one +
                ",,run,the output folder\nrun.frames.png,\"" + new_one + "/a,b\",,run,\"x\"\"y\"\n");
  EXPECT_EQ(test::slurp(new_one + "/sub/parameters.csv"), "run.out," + new_one + "/sub,,run,\n");
  EXPECT_EQ(test::slurp(new_one + "/log.txt"), "the samples are in " + one + "/timeseries.csv\n");
}

// the parameters of the study a folder holds: summary.csv's header (read no further: a quoted name
// may hold a line break, a row need not be whole), else a point's point.csv, else none
TEST(SweepResults, StudyParametersAreReadFromTheHeaders) {
  const std::string dir = results_folder("study");
  EXPECT_EQ(study_parameters(dir), std::vector<std::string>{});
  EXPECT_EQ(study_parameters(dir + "/missing"), std::vector<std::string>{});
  const std::vector<Point> points = grid_points(Grid{{"a\nb", "mu"}, {{Value(1LL)}, {Value(0.3), Value(1.0)}}});
  write_point_result(dir, points[1], PointResult{"ok", {{"x", "1"}}, ""});
  EXPECT_EQ(study_parameters(dir), (std::vector<std::string>{"a\nb", "mu"}));
  test::spit(dir + "/summary.csv", "point,\"p\nq\",status,x\n0,1,ok,\"unfinished");
  EXPECT_EQ(study_parameters(dir), (std::vector<std::string>{"p\nq"}));
  test::spit(dir + "/summary.csv", "a,b\n");  // not a summary: the points' folders say
  EXPECT_EQ(study_parameters(dir), (std::vector<std::string>{"a\nb", "mu"}));
}

}  // namespace
}  // namespace beltsim::sweep
