// The one check of a run's settings (sim/settings_check.hpp): an event's time is judged by
// event_time_problem wherever it comes from (a live simulation, a batch run, run.events in Lua).
#include "sim/run_settings.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <map>

#include "io/csv_writer.hpp"
#include "io/number_text.hpp"
#include "scene/scene.hpp"
#include "sim/run_table.hpp"
#include "sim/settings_check.hpp"
#include "sim/simulation.hpp"
#include "support/dry_scene.hpp"
#include "support/files.hpp"
#include "support/scratch.hpp"

namespace beltsim {
namespace {

using test::dry_scene;

namespace fs = std::filesystem;

MuEvent event_at(double t) {
  MuEvent ev;
  ev.t = t;
  ev.mu.assign(dry_scene().model.n_el(), 0.2);
  return ev;
}

RunSettings with_event(double t, const std::string& name) {
  RunSettings rs;
  rs.t_end = 0.004;
  rs.out_dir = (beltsim::test::scratch_dir("beltsim_run_settings_test") / name).string();
  fs::remove_all(rs.out_dir);
  rs.mu_events.push_back(event_at(t));
  return rs;
}

std::string refusal(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(RunSettings, EventTimeProblemNamesTheRuleAndTheValue) {
  EXPECT_EQ(event_time_problem(0.5), "");
  EXPECT_EQ(event_time_problem(0.5, 1.0), "");
  EXPECT_EQ(event_time_problem(0), "must be > 0 s and finite (got 0 s)");
  EXPECT_EQ(event_time_problem(-0.25, 1.0), "must be > 0 s and finite (got -0.25 s)");
  EXPECT_EQ(event_time_problem(INFINITY), "must be > 0 s and finite (got inf s)");
  EXPECT_EQ(event_time_problem(NAN, 1.0), "must be > 0 s and finite (got nan s)");
  EXPECT_EQ(event_time_problem(1.0, 1.0), "must be before t_end = 1 s (got 1 s)");
}

// a live simulation, a batch run and check() refuse the same times with the same words
TEST(RunSettings, EveryCallerChecksEventTimesAlike) {
  const std::string live = refusal([] { Simulation s(dry_scene(), with_event(0, "live")); });
  EXPECT_EQ(live, "events: an event's time must be > 0 s and finite (got 0 s)");
  const std::string batch = refusal([] { run(dry_scene(), with_event(-1, "batch")); });
  EXPECT_EQ(batch, "events: an event's time must be > 0 s and finite (got -1 s)");
  // at t_end: skipped by a batch run (drop_after_end), refused by check() for one
  RunSettings at_end = with_event(0.004, "at_end");
  EXPECT_EQ(refusal([&] { check(dry_scene(), at_end, true); }),
            "events: an event's time must be before t_end = 0.004 s (got 0.004 s)");
  EXPECT_EQ(refusal([&] { check(dry_scene(), at_end, false); }), "");
  const std::vector<std::string> notes = drop_after_end(at_end);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_TRUE(at_end.mu_events.empty());
  // one wrong by itself is kept for check() to refuse
  RunSettings bad = with_event(NAN, "nan");
  EXPECT_TRUE(drop_after_end(bad).empty());
  EXPECT_EQ(bad.mu_events.size(), 1u);
}

// what a run shortened by --t-end cannot reach is left out with a note each, and the rest passes check()
TEST(RunSettings, ARunLeavesOutWhatComesAfterItsEnd) {
  RunSettings rs = with_event(0.01, "after_end");
  rs.mu_events.back().what = "wet";
  rs.snapshot_times = {0.002, 0.01};
  rs.frames = FrameSettings{};
  rs.frames->t_start = 0.01;
  rs.keep_states = true;
  EXPECT_NE(refusal([&] { check(dry_scene(), rs, true); }), "");
  const std::vector<std::string> notes = drop_after_end(rs, "--t-end");
  ASSERT_EQ(notes.size(), 3u);
  EXPECT_EQ(notes[0], "events: the event at 0.01 s (wet) is at or after t_end = 0.004 s (from --t-end): skipped");
  EXPECT_EQ(notes[1], "snapshots: the snapshot at 0.01 s is after t_end = 0.004 s (from --t-end): skipped");
  EXPECT_EQ(notes[2],
            "frames: they start at 0.01 s, after t_end = 0.004 s (from --t-end): none drawn and no states kept");
  EXPECT_TRUE(rs.mu_events.empty());
  EXPECT_EQ(rs.snapshot_times, std::vector<double>{0.002});
  EXPECT_FALSE(rs.frames.has_value());
  EXPECT_FALSE(rs.keep_states);
  EXPECT_EQ(refusal([&] { check(dry_scene(), rs, true); }), "");
  // a snapshot at t_end is taken: nothing to leave out
  rs.snapshot_times = {0.004};
  EXPECT_TRUE(drop_after_end(rs, "--t-end").empty());
  // a script's own t_end: its snapshots after it are its contradiction, for check() to refuse
  rs.snapshot_times = {0.01};
  EXPECT_TRUE(drop_after_end(rs).empty());
  EXPECT_EQ(rs.snapshot_times.size(), 1u);
}

// parameters.csv records every setting the run used, one row run.<key> for each of the table's
// (sim/run_table.hpp) with the value the run had
TEST(RunSettings, ParametersCsvRecordsEverySetting) {
  RunSettings rs = with_event(0.002, "every_setting");
  rs.integrator = "esdirk32";
  rs.rtol = 3e-4;
  rs.atol = 2e-5;
  rs.sample_dt = 5e-4;
  rs.probes = {3, 7};
  rs.snapshot_every = 1e-3;
  rs.wall_limit = 60;
  rs.check = true;
  rs.allow_large = true;
  Simulation(dry_scene(), rs).run_to(0.001);
  std::map<std::string, std::vector<std::string>> rows;
  for (const auto& r : csv_rows(test::slurp(fs::path(rs.out_dir) / "parameters.csv"))) rows[r[0]] = r;
  for (const RunSetting& s : run_settings()) {
    const std::string name = "run." + std::string(s.key);
    ASSERT_TRUE(rows.count(name)) << name << " is not in parameters.csv";
    EXPECT_EQ(rows[name][1], run_value_text(s, rs)) << name;
    EXPECT_EQ(rows[name][2], s.unit) << name;
    EXPECT_EQ(rows[name][3], "run") << name;
  }
  // the values set above, read back
  EXPECT_EQ(parse_number(rows["run.rtol"][1]), 3e-4);
  EXPECT_EQ(parse_number(rows["run.atol"][1]), 2e-5);
  EXPECT_EQ(parse_number(rows["run.max_wall"][1]), 60);
  EXPECT_EQ(rows["run.probe"][1], "3 7");
  EXPECT_EQ(rows["run.integrator"][1], "esdirk32");
}

// a setting left unset reads as the run-settings table's default says, not as the number that
// stands for it: no wall-time limit is "none", where 0 would read as a limit of 0 s
TEST(RunSettings, ParametersCsvWritesAnUnsetLimitAsNone) {
  RunSettings rs = with_event(0.002, "unset_limit");
  Simulation(dry_scene(), rs).run_to(0.001);
  std::map<std::string, std::vector<std::string>> rows;
  for (const auto& r : csv_rows(test::slurp(fs::path(rs.out_dir) / "parameters.csv"))) rows[r[0]] = r;
  EXPECT_EQ(rows["run.max_wall"][1], "none");
  EXPECT_NE(run_settings_markdown().find("| `max_wall` | s | none |"), std::string::npos)
      << "the table's default is no longer \"none\": " << run_settings_markdown();
}

}  // namespace
}  // namespace beltsim
