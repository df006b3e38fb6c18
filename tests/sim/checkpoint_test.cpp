// Resuming a saved checkpoint (sim/checkpoint.cpp) and the outputs it continues: results after it
// are cut only when asked; outputs another run wrote since, or a folder moved away, are refused
// with nothing touched; a version 12 checkpoint resumes unchecked; every kept run setting is kept.
// A checkpoint damaged, forged or mutated is checkpoint_damage_test.cpp's.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "checkpoint_support.hpp"
#include "scene/scene.hpp"
#include "sim/run_table.hpp"
#include "sim/simulation.hpp"
#include "support/checkpoint_edit.hpp"
#include "support/files.hpp"
#include "support/presets.hpp"

namespace beltsim::checkpoint_test {
namespace {

using test::resealed;
using test::slurp;
using test::spit;

TEST(Checkpoint, ResumesTheSavedText) {
  const Outcome o = resume_text(saved().text);
  EXPECT_TRUE(o.resumed) << o.message << o.failure;
}

// the run went on past its checkpoint: resuming it would cut those rows, which is refused, naming
// them, unless asked (rewind); refused, nothing is touched
TEST(Checkpoint, ResultsAfterTheCheckpointAreCutOnlyWhenAsked) {
  saved().restore();
  const std::string ck = saved().ck.string(), csv = (saved().out / "timeseries.csv").string();
  const std::string m = test::what_of([&] { Simulation::resume(ck, {}); });
  EXPECT_NE(m.find(ck + ": resuming at t = 0.0137 s would cut the run's results after it (7 rows of " + csv +
                   " after it, to t = 0.02 s); "),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("resume with rewind = true"), std::string::npos) << m;
  EXPECT_TRUE(saved().outputs_untouched());
  auto s = Simulation::resume(ck, {}, nullptr, {}, true);
  s->close();
  EXPECT_EQ(slurp(csv), saved().outputs.at("timeseries.csv").substr(0, slurp(csv).size()));
  EXPECT_LT(slurp(csv).size(), saved().outputs.at("timeseries.csv").size());
  saved().restore();
}

// the rows kept must be this run's: a folder another scene's run wrote since the save (whose rows
// may end where the checkpoint's do, by chance) is refused by its header, nothing touched
TEST(Checkpoint, AnotherRunsTimeseriesIsRefused) {
  saved().restore();
  const std::string ck = saved().ck.string(), csv = (saved().out / "timeseries.csv").string();
  std::string other = saved().outputs.at("timeseries.csv");
  other[0] = 'T';  // the same sizes and row ends, another header
  test::spit(csv, other);
  const std::string m = test::what_of([&] { Simulation::resume(ck, {}, nullptr, {}, true); });
  EXPECT_NE(m.find("the run's output " + csv + " is not this run's: its header is not the one this simulation writes"),
            std::string::npos)
      << m;
  EXPECT_EQ(slurp(csv), other);
  saved().restore();
}

// The outputs up to the checkpoint must be the ones its run wrote, byte for byte: a later run of the
// same scene into the folder writes the same header, and its rows may end at the checkpoint's byte
// by chance (a user's rerun with another pretension was spliced to the checkpoint's run so, exit 0,
// parameters.csv the later run's). Each change below keeps the header, the sizes and the row ends;
// each is refused with and without rewind, naming the file and what differs, nothing touched.
TEST(Checkpoint, OutputsAnotherRunWroteSinceAreRefused) {
  saved().restore();
  const std::string ck = saved().ck.string();
  const fs::path out = saved().out;
  const std::string& series = saved().outputs.at("timeseries.csv");
  const long cut = std::stol(test::value_of(saved().text, "csv_bytes"));
  ASSERT_EQ(series[static_cast<size_t>(cut) - 1], '\n');
  const size_t last_row = series.rfind('\n', static_cast<size_t>(cut) - 2) + 1;
  const std::string last_t = series.substr(last_row, series.find(',', last_row) - last_row);
  EXPECT_EQ(test::value_of(saved().text, "csv_last_t"), last_t);
  const std::string parameters = slurp(out / "parameters.csv");
  const std::string refusal_end =
      ". Another run has written the folder since the checkpoint was saved, and continuing would join this "
      "checkpoint's run to that run's rows. Nothing was changed: resume a checkpoint the later run saved, or run "
      "the script that saved this one again (each run its own folder: --out or out = ...)";
  auto refused = [&](const std::string& file, const std::string& changed, const std::string& what) {
    saved().restore();
    spit(out / file, changed);
    for (const bool rewind : {false, true}) {
      const std::string m = test::what_of([&] { Simulation::resume(ck, {}, nullptr, {}, rewind); });
      EXPECT_EQ(m, ck + ": the outputs in " + out.string() + " are not the ones this checkpoint's run wrote: " + file +
                       " (" + what + ")" + refusal_end);
      EXPECT_EQ(slurp(out / file), changed);
    }
    EXPECT_EQ(slurp(out / "parameters.csv"), file == "parameters.csv" ? changed : parameters);
  };
  // a digit of a row before the last: the same length, header and row ends
  std::string other = series;
  const size_t digit = series.find_last_of("0123456789", last_row - 2);
  ASSERT_TRUE(digit != std::string::npos && digit > series.find('\n'));
  other[digit] = other[digit] == '1' ? '2' : '1';
  refused("timeseries.csv", other,
          "its first " + std::to_string(cut) + " bytes, to t = " + last_t +
              " s, are not the ones the checkpoint's run wrote");
  // the last row's time
  other = series;
  other[last_row + last_t.size() - 1] = last_t.back() == '1' ? '2' : '1';
  const std::string other_t = other.substr(last_row, last_t.size());
  refused("timeseries.csv", other,
          "its row ending at byte " + std::to_string(cut) + " is at t = " + other_t +
              " s, where the checkpoint's run had written its last at t = " + last_t + " s");
  // a snapshot's value (the one at 0.01 s)
  other = saved().outputs.at("snapshots.csv");
  const long snapshots_cut = std::stol(test::value_of(saved().text, "snapshots_bytes"));
  const size_t e = other.find_last_of("0123456789", static_cast<size_t>(snapshots_cut) - 2);
  ASSERT_TRUE(e != std::string::npos && e > other.find('\n'));  // (a row's, not the header's)
  other[e] = other[e] == '1' ? '2' : '1';
  refused("snapshots.csv", other,
          "its first " + std::to_string(snapshots_cut) + " bytes are not the ones the checkpoint's run wrote");
  // parameters.csv: another value (a pretension, say), written at the later run's start
  other = parameters;
  const size_t p = other.find_first_of("0123456789", other.find('\n'));
  other[p] = other[p] == '1' ? '2' : '1';
  refused("parameters.csv", other,
          "its first " + test::value_of(saved().text, "parameters_bytes") +
              " bytes, the parameters the checkpoint's run wrote at its start, differ");
  spit(out / "parameters.csv", parameters);
  saved().restore();
  // as they were: it resumes
  Simulation::resume(ck, {}, nullptr, {}, true)->close();
  spit(out / "parameters.csv", parameters);
  saved().restore();
}

// a run's folder moved away (archived under another name): the resume is refused, naming the
// folder and where it may have gone, and no empty folder is made in its place
TEST(Checkpoint, AFolderMovedAwayIsRefusedAndNotMade) {
  saved().restore();
  const fs::path out = saved().out, moved = dir() / "archived";
  fs::remove_all(moved);
  fs::rename(out, moved);
  const std::string ck = (moved / "ck.txt").string();
  fs::copy_file(saved().ck, ck);
  const std::string m = test::what_of([&] { Simulation::resume(ck, {}, nullptr, {}, true); });
  EXPECT_EQ(m, ck + ": the run's output folder " + out.string() +
                   ", whose files this checkpoint continues, is not there (" + moved.string() +
                   ", where the checkpoint lies, holds a timeseries.csv: if it is that folder moved, move it back to " +
                   out.string() +
                   "): put the run's folder back where it was to resume it, or run the scene again; "
                   "nothing was written");
  EXPECT_FALSE(fs::exists(out));
  fs::remove(ck);
  fs::rename(moved, out);
  saved().restore();
}

// a version 12 checkpoint (no fingerprints of its outputs) is still resumed, saying what it could
// not check; a checkpoint saved after it holds the fingerprints of the files as they are
TEST(Checkpoint, AVersion12CheckpointResumesUnchecked) {
  saved().restore();
  std::string v12 = saved().text;
  v12.replace(0, v12.find('\n'), "beltsim-checkpoint 12");
  for (const char* key :
       {"csv_last_t", "csv_fnv1a64", "events_fnv1a64", "snapshots_fnv1a64", "parameters_bytes", "parameters_fnv1a64"}) {
    const size_t at = v12.find(std::string("\n") + key + " ");
    ASSERT_NE(at, std::string::npos) << key;
    v12.erase(at + 1, v12.find('\n', at + 1) - at);
  }
  const fs::path ck = dir() / "v12.ckpt", again = dir() / "v12_again.ckpt";
  spit(ck, resealed(v12));
  std::vector<std::string> said;
  {
    auto s = Simulation::resume(ck.string(), {}, nullptr, {}, true, [&](const std::string& m) { said.push_back(m); });
    s->save(again.string());
    s->close();
  }
  ASSERT_EQ(said.size(), 1u);
  EXPECT_EQ(said[0], ck.string() +
                         ": a version 12 checkpoint holds no fingerprint of its outputs, so whether the "
                         "files in " +
                         saved().out.string() +
                         " up to it are its own run's (not a later run's into the folder) could not be checked; a "
                         "checkpoint saved by this beltsim is checked");
  // the one saved after it: the fingerprints of the files up to the same point, as the run's own were
  const std::string text = slurp(again);
  for (const char* key : {"csv_bytes", "csv_last_t", "csv_fnv1a64", "snapshots_bytes", "snapshots_fnv1a64"})
    EXPECT_EQ(test::value_of(text, key), test::value_of(saved().text, key)) << key;
  EXPECT_NE(test::value_of(text, "events_fnv1a64"), test::value_of(saved().text, "events_fnv1a64"));  // "resume"
  said.clear();
  Simulation::resume(again.string(), {}, nullptr, {}, true, [&](const std::string& m) { said.push_back(m); })->close();
  EXPECT_TRUE(said.empty());
  saved().restore();
}

// A version 13 checkpoint of a run that tracked energy: `energy` with the two integrals added in
// version 14 (the arms' and the couplings' losses) taken out of every state it holds, as such a
// run wrote them (`at`: where they sit in the state; `count`: the values of a line are that many
// states)
std::string as_version_13(std::string text, const Model& m) {
  text.replace(0, text.find('\n'), "beltsim-checkpoint 13");
  const size_t n = static_cast<size_t>(m.n_state()), at = static_cast<size_t>(2 * m.n_coord() + kDissArms);
  const size_t gone = kEnergyCount - kDissArms;
  for (const char* key :
       {"integrator.y", "integrator.f", "integrator.y_prev", "integrator.f_prev", "integrator.interior"}) {
    const size_t from = text.find(std::string("\n") + key + " ") + 1, to = text.find('\n', from);
    std::istringstream in(text.substr(from, to - from));
    std::string k, v;
    size_t count = 0;
    in >> k >> count;
    std::string line = k + " " + std::to_string(count - count / n * gone);
    for (size_t i = 0; i < count && in >> v; ++i)
      if (i % n < at || i % n >= at + gone) line += " " + v;
    text.replace(from, to - from, line);
  }
  return resealed(text);
}

// a version 13 checkpoint of a run that tracked energy held five integrals, not seven: it resumes
// with the arms' and couplings' at zero (a drive without either, whose are zero anyway); one of a
// drive with a tensioner arm, whose friction integral held the arm's losses, is refused, saying why
TEST(Checkpoint, AVersion13CheckpointOfAnEnergyRunResumes) {
  for (const bool arm : {false, true}) {
    SceneDef d = arm ? presets::automotive_tensioner() : presets::paper_dry();
    d.track_energy = true;
    const Scene sc = build_scene(d);
    RunSettings rs;
    rs.out_dir = (dir() / (arm ? "v13_arm" : "v13_energy")).string();
    fs::remove_all(rs.out_dir);
    const fs::path ck = dir() / "v14.ckpt", old = dir() / "v13.ckpt";
    std::vector<double> e;
    {
      Simulation s(sc, rs);
      s.run_to(0.003);
      s.save(ck.string());
      e = s.energy_integrals();
    }
    spit(old, as_version_13(slurp(ck), sc.model));
    if (!arm) {
      auto s = Simulation::resume(old.string(), {}, nullptr, {}, true, [](const std::string&) {});
      EXPECT_EQ(s->energy_integrals(), e);
      s->run_to(0.004);
      s->close();
      continue;
    }
    try {
      Simulation::resume(old.string(), {}, nullptr, {}, true, [](const std::string&) {})->close();
      ADD_FAILURE() << "resumed";
    } catch (const std::exception& x) {
      EXPECT_NE(std::string(x.what()).find("counted the tensioner arms' and couplings' losses as friction"),
                std::string::npos)
          << x.what();
    }
  }
}

// a two-way coupling has no clutch hub (its model holds zeros there): its checkpoint resumes (a
// user's trial: "hub_inertia must be > 0 (got 0)") and goes on as the run it left did
TEST(Checkpoint, ATwoWayCouplingResumes) {
  SceneDef d = presets::paper_dry();
  CouplingDef c;
  c.inertia = 0.01, c.stiffness = 50, c.one_way = false;
  d.pulleys[1].coupling = c;
  const Scene sc = build_scene(d);
  RunSettings rs;
  rs.out_dir = (dir() / "two_way").string();
  fs::remove_all(rs.out_dir);
  const fs::path ck = dir() / "two_way.ckpt";
  Eigen::VectorXd y;
  {
    Simulation s(sc, rs);
    s.run_to(0.002);
    s.save(ck.string());
    s.run_to(0.003);
    y = s.state();
  }
  auto s = Simulation::resume(ck.string(), {}, nullptr, {}, true, [](const std::string&) {});
  s->run_to(0.003);
  EXPECT_EQ(s->state(), y);
  s->close();
}

// a checkpoint keeps every setting the run-settings table marks kept (sim/run_table.hpp): each set
// to a value other than its default, saved, and read back the same
TEST(Checkpoint, KeepsEveryRunSettingTheTableMarksKept) {
  const Scene sc = build_scene(presets::paper_dry());
  RunSettings rs;
  rs.integrator = "esdirk32";
  rs.rtol = 3e-4;
  rs.atol = 2e-5;
  rs.sample_dt = 5e-4;
  rs.out_dir = fs::absolute(dir() / "all_settings").string();
  fs::remove_all(rs.out_dir);
  rs.probes = {3, 7};
  rs.snapshot_every = 2e-3;
  rs.snapshot_times = {1e-3, 5e-3};
  rs.keep_samples = true;
  rs.allow_large = true;
  rs.keep_states = true;
  rs.frames.emplace();  // the times alone (kept states), so no renderer is needed
  rs.frames->fps = 60, rs.frames->slowdown = 50, rs.frames->t_start = 1e-3;
  const fs::path ck = dir() / "all_settings.ckpt";
  {
    Simulation s(sc, rs);
    s.run_to(2e-3);
    s.save(ck.string());
  }
  const RunSettings back = Simulation::open_checkpoint(ck.string())->settings();
  const RunSettings fallback;
  int kept = 0;
  for (const RunSetting& s : run_settings()) {
    if (!(s.where & kSaved)) continue;
    ++kept;
    EXPECT_NE(run_value_text(s, rs), run_value_text(s, fallback)) << s.key << ": the test sets it to its default";
    EXPECT_EQ(run_value_text(s, back), run_value_text(s, rs)) << s.key;
  }
  EXPECT_GE(kept, 11);  // (the eleven a checkpoint kept before the table)
}

}  // namespace
}  // namespace beltsim::checkpoint_test
