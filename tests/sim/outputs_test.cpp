// A simulation's outputs (sim/simulation.hpp, io/output_dir.hpp): every fixed-name file it writes
// in its folder refuses a symbolic link planted under that name (the link's target untouched, the
// error naming the file); one simulation at a time writes a folder (a second live one, a batch run
// while one is open, a checkpoint resumed twice are refused before they write or cut anything);
// a file that cannot be written at close makes close() throw and is recorded.
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <sstream>

#include "io/number_text.hpp"
#include "io/output_dir.hpp"
#include "scene/scene.hpp"
#include "sim/settings_check.hpp"
#include "sim/simulation.hpp"
#include "support/dry_scene.hpp"
#include "support/file_size_limit.hpp"
#include "support/files.hpp"
#include "support/presets.hpp"
#include "support/scratch.hpp"
#include "support/warning_guard.hpp"

namespace beltsim {
namespace {

using test::dry_scene;
using test::slurp;
using test::what_of;

namespace fs = std::filesystem;

fs::path fresh(const std::string& name) {
  const fs::path p = beltsim::test::scratch_dir("beltsim_outputs_test") / name;
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

RunSettings settings(const fs::path& out) {
  RunSettings rs;
  rs.integrator = "esdirk32";
  rs.sample_dt = 1e-3;
  rs.snapshot_every = 0.002;  // snapshots.csv too
  rs.out_dir = out.string();
  return rs;
}

constexpr const char* kShellLine = "export PATH=/usr/bin\n";

std::string link_refusal(const fs::path& file) {
  return "cannot write " + file.string() + ": it is a symbolic link (beltsim never writes through a link)";
}

TEST(Outputs, EveryFixedNameRefusesAPlantedLink) {
  for (const char* name : {"parameters.csv", "timeseries.csv", "timeseries_units.csv", "events.csv", "snapshots.csv",
                           "snapshots_units.csv", ".beltsim.lock"}) {
    SCOPED_TRACE(name);
    const fs::path base = fresh(std::string("link_") + name), out = base / "out", target = base / "bashrc";
    fs::create_directories(out);
    std::ofstream(target) << kShellLine;
    fs::create_symlink(target, out / name);
    const std::string e = what_of([&] { Simulation s(dry_scene(), settings(out)); });
    EXPECT_EQ(e, link_refusal(out / name));
    EXPECT_EQ(slurp(target), kShellLine);
    EXPECT_TRUE(fs::is_symlink(out / name));
  }
  // the folder itself
  const fs::path base = fresh("link_folder");
  fs::create_directories(base / "home");
  fs::create_symlink(base / "home", base / "out");
  EXPECT_EQ(what_of([&] { Simulation s(dry_scene(), settings(base / "out")); }), link_refusal(base / "out"));
  EXPECT_TRUE(fs::is_empty(base / "home"));
}

TEST(Outputs, ACheckpointIsNeverWrittenThroughALinkAndLeavesNoPart) {
  const fs::path base = fresh("ckpt_link"), out = base / "out", target = base / "bashrc";
  std::ofstream(target) << kShellLine;
  Simulation s(dry_scene(), settings(out));
  s.run_to(0.002);
  fs::create_symlink(target, out / "run.ckpt");
  EXPECT_EQ(what_of([&] { s.save((out / "run.ckpt").string()); }), link_refusal(out / "run.ckpt"));
  EXPECT_EQ(slurp(target), kShellLine);
  s.save((out / "good.ckpt").string());
  EXPECT_FALSE(fs::exists(out / "good.ckpt.part"));
  EXPECT_FALSE(fs::exists(out / "run.ckpt.part"));
  EXPECT_NE(slurp(out / "good.ckpt").find("beltsim-checkpoint"), std::string::npos);
}

std::string in_use(const fs::path& out) {
  return "the output folder " + out.string() +
         " is in use by another simulation of this beltsim: two simulations writing one folder would mix their "
         "rows; give this one a folder of its own (out = ...) or close the other first";
}

TEST(Outputs, OneSimulationPerFolder) {
  const fs::path out = fresh("one_writer") / "out";
  auto a = std::make_unique<Simulation>(dry_scene(), settings(out));
  a->run_to(0.003);
  const std::string rows = slurp(out / "timeseries.csv"), params = slurp(out / "parameters.csv");
  // a second live one, a batch run: refused before they write anything
  EXPECT_EQ(what_of([&] { Simulation b(dry_scene(), settings(out)); }), in_use(out));
  RunSettings batch = settings(out);
  batch.t_end = 0.002;
  EXPECT_EQ(what_of([&] { run(dry_scene(), batch); }), in_use(out));
  EXPECT_EQ(slurp(out / "timeseries.csv"), rows);
  EXPECT_EQ(slurp(out / "parameters.csv"), params);
  EXPECT_TRUE(fs::exists(out / ".beltsim.lock"));
  // released at close, its file removed (issue 44: it was left in every output folder)
  a->close();
  EXPECT_FALSE(fs::exists(out / ".beltsim.lock"));
  EXPECT_EQ(what_of([&] { run(dry_scene(), batch); }), "");
  EXPECT_FALSE(fs::exists(out / ".beltsim.lock"));
  // a lock file a killed process left holds no lock: the next simulation takes the folder
  std::ofstream(out / ".beltsim.lock") << "99999\n";
  EXPECT_EQ(what_of([&] { run(dry_scene(), batch); }), "");
  EXPECT_FALSE(fs::exists(out / ".beltsim.lock"));
}

// the warnings a 2 ms run with rs gives of its output folder (those that begin "the output folder")
std::vector<std::string> folder_warnings(RunSettings rs) {
  std::vector<std::string> said;
  rs.t_end = 0.002;
  rs.on_warning = [&](const std::string& m) {  // (esdirk32's contract warning aside)
    if (m.rfind("the output folder", 0) == 0) said.push_back(m);
  };
  run(dry_scene(), rs);
  return said;
}

// a run into a folder that holds an earlier run's outputs it does not write says so as it starts
// (a user's console session beside an earlier batch run's snapshots and video found them mixed,
// without a word)
TEST(Outputs, AnEarlierRunsOutputsThisRunDoesNotWriteAreNamed) {
  const fs::path out = fresh("earlier") / "out";
  std::vector<std::string> said;
  auto runs = [&](bool snapshots) {
    RunSettings rs = settings(out);
    if (!snapshots) rs.snapshot_every = 0;
    said = folder_warnings(rs);
  };
  runs(true);
  EXPECT_TRUE(said.empty()) << said[0];
  fs::create_directories(out / "frames");  // an earlier run's PNG folder and video
  std::ofstream(out / "frames.mp4") << "x";
  runs(false);
  ASSERT_EQ(said.size(), 1u);
  EXPECT_EQ(said[0], "the output folder " + out.string() +
                         " holds an earlier run's snapshots.csv, snapshots_units.csv, frames.mp4 and frames/, which "
                         "this run does not "
                         "write: they are not this run's outputs (give each run its own --out or out = ..., or "
                         "remove them)");
  fs::remove_all(out / "frames");
  fs::remove(out / "frames.mp4");
  runs(true);  // it writes snapshots.csv again
  EXPECT_TRUE(said.empty()) << said[0];
}

// a sink that draws nothing: a run that asks for frames, for the names of its own video and PNG folder
class NoPictures final : public FrameSink {
 public:
  void frame(double, const double*, const Drive&, const Observation*) override {}
  void finish() override {}
  long frames_written() const override { return 0; }
};

// every video is named, whatever its name, and every PNG folder, but this run's own (a user's second
// run of scripts/paper_dry.lua with --no-frames said only frames/, while the first run's
// paper_dry.mp4 stayed beside the new timeseries.csv: the check knew the default name alone)
TEST(Outputs, AnEarlierRunsVideoAndPngFolderAreNamedWhateverTheirNames) {
  const fs::path out = fresh("earlier_named") / "out";
  std::vector<std::string> said;
  auto runs = [&](const char* video, const char* png) {
    RunSettings rs = settings(out);
    if (video || png) {
      rs.frames = FrameSettings{};
      rs.frames->video_path = video ? video : "";
      rs.frames->png_dir = png ? png : "";
      rs.frame_factory = [](const Scene&, const FrameSettings&) { return std::make_unique<NoPictures>(); };
    }
    said = folder_warnings(rs);
  };
  runs(nullptr, nullptr);
  EXPECT_TRUE(said.empty()) << said[0];
  // the first run's video and PNGs, by the names its script gave
  std::ofstream(out / "paper_dry.mp4") << "x";
  std::ofstream(out / "clip_resumed_0.1.MP4") << "x";
  fs::create_directories(out / "pics");
  std::ofstream(out / "pics" / "frame_00000.png") << "x";
  fs::create_directories(out / "notes");  // a folder without frames: not an output of a run
  std::ofstream(out / "notes" / "a.png") << "x";
  runs(nullptr, nullptr);
  ASSERT_EQ(said.size(), 1u);
  EXPECT_EQ(said[0], "the output folder " + out.string() +
                         " holds an earlier run's clip_resumed_0.1.MP4, paper_dry.mp4 and pics/, which this run does "
                         "not write: they are not this run's outputs (give each run its own --out or out = ..., or "
                         "remove them)");
  // a run that writes that video and that PNG folder itself names only the other video
  runs("paper_dry.mp4", "pics");
  ASSERT_EQ(said.size(), 1u);
  EXPECT_EQ(said[0], "the output folder " + out.string() +
                         " holds an earlier run's clip_resumed_0.1.MP4, which this run does not write: they are not "
                         "this run's outputs (give each run its own --out or out = ..., or remove them)");
  // its video given as an absolute path into the folder, the same (pics/ lost its frames to the run
  // before, which drew into it)
  runs((out / "clip_resumed_0.1.MP4").c_str(), nullptr);
  ASSERT_EQ(said.size(), 1u);
  EXPECT_EQ(said[0], "the output folder " + out.string() +
                         " holds an earlier run's paper_dry.mp4, which this run does not write: they are not this "
                         "run's outputs (give each run its own --out or out = ..., or remove them)");
}

// so are the checkpoints an earlier run saved into the folder: this run replaces the outputs they
// continue, and beltsim.resume refuses them after it (a user's rerun into the folder of a saved
// run, with another pretension, said nothing of its mid.ckpt, whose resume then spliced the runs)
TEST(Outputs, AnEarlierRunsCheckpointsAreNamed) {
  const fs::path out = fresh("earlier_ckpt") / "out";
  std::vector<std::string> said;
  auto runs = [&] { said = folder_warnings(settings(out)); };
  runs();
  EXPECT_TRUE(said.empty()) << said[0];
  std::ofstream(out / "mid.ckpt") << "x";
  fs::create_directories(out / "dir.ckpt");  // a folder of that name: not a checkpoint
  runs();
  ASSERT_EQ(said.size(), 1u);
  EXPECT_EQ(said[0], "the output folder " + out.string() +
                         " holds an earlier run's checkpoint mid.ckpt: this run replaces the outputs it continues, so "
                         "beltsim.resume will refuse it unless this run saves its own over it (give each run its own "
                         "--out or out = ..., or remove it)");
  std::ofstream(out / "a.ckpt") << "x";
  std::ofstream(out / "frames.mp4") << "x";
  runs();
  ASSERT_EQ(said.size(), 1u);
  EXPECT_EQ(said[0], "the output folder " + out.string() +
                         " holds an earlier run's frames.mp4, which this run does not write: they are not this run's "
                         "outputs (give each run its own --out or out = ..., or remove them); and its checkpoints "
                         "a.ckpt and mid.ckpt: this run replaces the outputs they continue, so beltsim.resume will "
                         "refuse them unless this run saves its own over them");
}

// and so are the pictures sim:show and sim:plot drew by their default names, and the checkpoints
// saved into a subfolder (a trial's replays of two console sessions went into one folder, the
// first's show_0.100000.png left among the second's without a word); a PNG of another name may be
// the user's, and a subfolder with its own parameters.csv is another run's folder (replay/)
TEST(Outputs, AnEarlierRunsPicturesAndCheckpointsInSubfoldersAreNamed) {
  const fs::path out = fresh("earlier_pictures") / "out";
  std::vector<std::string> said;
  auto runs = [&] { said = folder_warnings(settings(out)); };
  runs();
  EXPECT_TRUE(said.empty()) << said[0];
  for (const char* f : {"show_0.100000.png", "plot_0.250000.png", "a.png", "show_1.png", "show_0.1000000.png"})
    std::ofstream(out / f) << "x";
  fs::create_directories(out / "ck");
  std::ofstream(out / "ck" / "mid.ckpt") << "x";
  fs::create_directories(out / "replay");  // a replay's folder: its own run's
  std::ofstream(out / "replay" / "parameters.csv") << "x";
  std::ofstream(out / "replay" / "late.ckpt") << "x";
  runs();
  ASSERT_EQ(said.size(), 1u);
  EXPECT_EQ(said[0], "the output folder " + out.string() +
                         " holds an earlier run's plot_0.250000.png and show_0.100000.png, which this run does not "
                         "write: they are not this run's outputs (give each run its own --out or out = ..., or remove "
                         "them); and its checkpoint ck/mid.ckpt: this run replaces the outputs it continues, so "
                         "beltsim.resume will refuse it unless this run saves its own over it");
  // past four, three and their count
  for (const char* f : {"show_0.200000.png", "show_0.200000_2.png", "show_0.300000.png"}) std::ofstream(out / f) << "x";
  fs::remove(out / "ck" / "mid.ckpt");
  runs();
  ASSERT_EQ(said.size(), 1u);
  EXPECT_EQ(said[0], "the output folder " + out.string() +
                         " holds an earlier run's plot_0.250000.png, show_0.100000.png, show_0.200000.png and 2 more "
                         "pictures, which this run does not write: they are not this run's outputs (give each run its "
                         "own --out or out = ..., or remove them)");
}

// a fresh run's frames and kept states replace an earlier run's: the numbered files it does not
// write over (a longer run's last ones) go too, so that a golden test never compares a frame an
// earlier run left, and so do beltsim compare's difference images of them (frame_NNNNN_diff.png:
// they stayed after a passing run, a user's trial); a file of any other name stays, and a resumed
// run removes nothing
TEST(Outputs, AnEarlierRunsNumberedFramesAndStatesAreRemoved) {
  const fs::path out = fresh("numbered") / "out";
  fs::create_directories(out / "frames");
  fs::create_directories(out / "states");
  for (const char* f :
       {"frames/frame_00000.png", "frames/frame_00041.png", "frames/frame_123456.png", "frames/frame_00041.png.keep",
        "frames/my_frame_00041.png", "frames/frame_0004.png", "states/state_00041.ckpt", "states/notes.txt",
        "frames/frame_00015_diff.png", "frames/frame_00015_diff.png.keep", "frames/frame_0001_diff.png"})
    std::ofstream(out / f) << "x";
  RunSettings rs = settings(out);
  rs.t_end = 0.002;
  rs.keep_states = true;
  rs.frames = FrameSettings{};
  rs.frames->png_dir = "frames";
  rs.frame_factory = [](const Scene&, const FrameSettings&) { return std::unique_ptr<FrameSink>(); };
  run(dry_scene(), rs);
  for (const char* gone : {"frames/frame_00000.png", "frames/frame_00041.png", "frames/frame_123456.png",
                           "states/state_00041.ckpt", "frames/frame_00015_diff.png"})
    EXPECT_FALSE(fs::exists(out / gone)) << gone;
  for (const char* kept : {"frames/frame_00041.png.keep", "frames/my_frame_00041.png", "frames/frame_0004.png",
                           "states/notes.txt", "frames/frame_00015_diff.png.keep", "frames/frame_0001_diff.png"})
    EXPECT_TRUE(fs::exists(out / kept)) << kept;
  EXPECT_TRUE(fs::exists(out / "states" / "state_00000.ckpt"));  // this run's own
}

// a zero is written 0 in parameters.csv too (issue 44: the CSVs held -0): a centre given at y = -0
TEST(Outputs, ParametersHoldNoNegativeZero) {
  const fs::path out = fresh("negative_zero") / "out";
  SceneDef d = presets::paper_dry();
  d.pulleys[1].centre.y() = -0.0;
  {
    Simulation s(build_scene(d), settings(out));
    s.run_to(0.001);
  }
  const std::string p = slurp(out / "parameters.csv");
  EXPECT_NE(p.find("\npulley.driven.centre_y,0,m,derived,"), std::string::npos) << p;
  EXPECT_EQ(p.find(",-0,"), std::string::npos) << p;
}

// a units file (io/units.hpp) beside the CSV file `csv` in out: its header is "column,unit", its
// names in order are the CSV file's header (returned in *names, comma-joined); its units by name
std::map<std::string, std::string> units_beside(const fs::path& out, const std::string& csv, std::string* names) {
  std::istringstream data(slurp(out / csv)), units(slurp(out / (csv.substr(0, csv.size() - 4) + "_units.csv")));
  std::string header, line;
  std::getline(data, header);
  std::getline(units, line);
  EXPECT_EQ(line, "column,unit");
  std::map<std::string, std::string> unit;
  names->clear();
  while (std::getline(units, line)) {
    const size_t comma = line.find(',');
    EXPECT_NE(comma, std::string::npos) << line;
    if (comma == std::string::npos) continue;
    *names += (names->empty() ? "" : ",") + line.substr(0, comma);
    unit[line.substr(0, comma)] = line.substr(comma + 1);
  }
  EXPECT_EQ(*names, header) << csv;
  return unit;
}

// timeseries_units.csv names each column of timeseries.csv, in its order, with its SI unit ("1" for
// a dimensionless one): a reader given the folder alone (pandas, MATLAB) needs no docs for them
TEST(Outputs, TheTimeSeriesUnitsNameEveryColumn) {
  const fs::path out = fresh("units") / "out";
  {
    Simulation s(dry_scene(), settings(out));
    s.run_to(0.002);
  }
  std::string names;
  std::map<std::string, std::string> unit = units_beside(out, "timeseries.csv", &names);
  EXPECT_GT(unit.size(), 20u) << names;
  for (const auto& [name, u] : unit) EXPECT_FALSE(u.empty()) << name;  // every column a number with a unit
  EXPECT_EQ(unit["t"], "s");
  EXPECT_EQ(unit["driver.omega"], "rad/s");
  EXPECT_EQ(unit["driver.torque"], "N·m");
  EXPECT_EQ(unit["driver.creep"], "1");
  EXPECT_EQ(unit["span_driver_driven.tension"], "N");
}

// snapshots_units.csv does the same for snapshots.csv: SI units, "1" for the element's number and
// μ, none for the text columns (the pulley's name, the state)
TEST(Outputs, TheSnapshotsUnitsNameEveryColumn) {
  const fs::path out = fresh("snapshot_units") / "out";
  {
    Simulation s(dry_scene(), settings(out));
    s.run_to(0.002);
  }
  std::string names;
  const std::map<std::string, std::string> unit = units_beside(out, "snapshots.csv", &names);
  EXPECT_EQ(unit, (std::map<std::string, std::string>{{"t", "s"},
                                                      {"element", "1"},
                                                      {"s", "m"},
                                                      {"x", "m"},
                                                      {"y", "m"},
                                                      {"tension", "N"},
                                                      {"normal", "N"},
                                                      {"friction", "N"},
                                                      {"slip", "m/s"},
                                                      {"mu", "1"},
                                                      {"pulley", ""},
                                                      {"state", ""}}))
      << names;
}

TEST(Outputs, ACheckpointResumedTwiceIsRefusedTheSecondTime) {
  const fs::path out = fresh("resume_twice") / "out";
  const std::string ck = (out.parent_path() / "run.ckpt").string();
  {
    Simulation s(dry_scene(), settings(out));
    s.run_to(0.002);
    s.save(ck);
  }
  auto first = Simulation::resume(ck, {});
  first->run_to(0.004);
  const std::string rows = slurp(out / "timeseries.csv");
  EXPECT_EQ(what_of([&] { Simulation::resume(ck, {}); }), in_use(out));
  EXPECT_EQ(slurp(out / "timeseries.csv"), rows);  // not cut back by the second
  first->run_to(0.005);
  EXPECT_GT(slurp(out / "timeseries.csv").size(), rows.size());
}

// parameters.csv cannot be written at close (here it became a second name of another file, which
// is refused as a full disk would fail it): close() throws naming it, the failure is recorded for
// the exit status, and the other outputs are closed all the same
TEST(Outputs, AFailureAtCloseIsThrownAndRecorded) {
  const fs::path out = fresh("close_fails") / "out";
  Simulation s(dry_scene(), settings(out));
  s.run_to(0.002);
  fs::create_hard_link(out / "parameters.csv", out.parent_path() / "second_name.csv");
  const size_t before = output_failures().size();
  const std::string e = what_of([&] { s.close(); });
  EXPECT_EQ(e, "cannot write " + (out / "parameters.csv").string() +
                   ": it has 2 hard links (beltsim writes only files of its own)");
  ASSERT_EQ(output_failures().size(), before + 1);
  EXPECT_EQ(output_failures().back(), e);
  // the folder was released all the same
  EXPECT_EQ(what_of([&] { Simulation b(dry_scene(), settings(out)); }).find("in use"), std::string::npos);
}

// a disk that fills while the time series is written (here a file-size limit, which fails write(2)
// the same way): the error says where the run stopped and that the outputs so far are kept, the
// simulation cannot go on (a row is missing), and parameters.csv says how it ended. A user's full
// disk said only "big.lua:19: cannot write small/full/timeseries.csv: No space left on device",
// and parameters.csv had no end rows
TEST(Outputs, AFullDiskStopsTheRunSayingWhereAndKeepsTheOutputs) {
  const fs::path out = fresh("full") / "out";
  RunSettings rs = settings(out);
  rs.snapshot_every = 0;
  rs.sample_dt = 1e-4;
  const long limit = 64 * 1024;  // parameters.csv (7 KB) fits, timeseries.csv passes it at about 0.01 s
  const std::string csv = (out / "timeseries.csv").string();
  // the child ends with _exit, not a return: the simulation's destructor would close its outputs,
  // and they are checked below as the failure left them
  const int status = test::exit_status_under_file_size_limit(limit, [&]() -> int {
    Simulation s(dry_scene(), rs);
    std::string e;
    try {
      s.run_to(1);
      _exit(1);  // never stopped
    } catch (const OutputError& x) {
      e = x.what();
    }
    const std::string want = "cannot write " + csv + ": " + std::strerror(EFBIG) + "; the run stopped at t = ";
    if (e.compare(0, want.size(), want) != 0 || e.find(" s of 1 s, and the outputs written so far are kept, their "
                                                       "rows whole (timeseries.csv up to t = ") == std::string::npos) {
      std::fprintf(stderr, "the message: %s\n", e.c_str());
      _exit(2);
    }
    // the run cannot go on: its time series would miss the row that did not fit
    const std::string again = what_of([&] { s.run_to(1); });
    _exit(again.find("the simulation cannot continue: " + e) != std::string::npos ? 0 : 3);
  });
  ASSERT_EQ(status, 0) << "1: no error, 2: not the expected message, 3: the run went on, " << test::kChildThrew
                       << ": it threw, " << test::kNoExitStatus << ": no child or one killed by a signal";
  const std::string series = slurp(csv), parameters = slurp(out / "parameters.csv");
  EXPECT_GT(series.size(), static_cast<size_t>(limit) - 1000);
  EXPECT_EQ(series.back(), '\n');
  const std::string last = series.substr(series.rfind('\n', series.size() - 2) + 1);
  EXPECT_NE(parameters.find("\nend.last_row_t," + last.substr(0, last.find(',')) + ",s,"), std::string::npos)
      << parameters;
  EXPECT_NE(parameters.find("\nend.status,failed,,derived,\"cannot write " + csv), std::string::npos) << parameters;
}

// the size of a run's time series, estimated before it runs (the 1e7-row refusal's figure, the
// warning of large outputs), is that of the rows it writes: a user's run read "481 B a row" where
// the rows took 620 (13 bytes a value; the rows in motion take about 17)
TEST(Outputs, TheTimeSeriesSizeIsEstimatedAsWritten) {
  const fs::path out = fresh("estimate") / "out";
  RunSettings rs = settings(out);
  rs.snapshot_every = 0;
  rs.t_end = 0.3;  // the paper's torque ramp: at rest at first, 50 rad/s at the end
  const RunResult r = run(dry_scene(), rs);
  const OutputVolume v = output_volume(dry_scene(), rs, 0, rs.t_end);
  EXPECT_NEAR(v.rows, 300, 1e-9);
  const double written = static_cast<double>(fs::file_size(r.csv_path));
  EXPECT_NEAR(v.rows * v.row_bytes / written, 1, 0.06)
      << v.row_bytes << " bytes a row estimated, " << written / 301 << " written";
}

// the warnings said before a run whose outputs will be large, or more than its disk has room for
// (a user's 9.9e6-row run of 6 GB started without a word, as did 2400 elements' kept states at
// 660 MB a simulated second): said once, before anything is integrated, with the figures
TEST(Outputs, LargeOutputsAreWarnedOfBeforeTheRun) {
  const fs::path out = fresh("large") / "out";
  std::vector<std::string> said;
  auto starts = [&](RunSettings rs) {
    said.clear();
    rs.snapshot_every = 0;
    rs.on_warning = [&](const std::string& m) {
      if (m.rfind("the outputs in", 0) == 0) said.push_back(m);
    };
    std::atomic<bool> stop{true};  // stopped at its first step: the warning comes before it
    const RunResult r = run(dry_scene(), rs, &stop);
    EXPECT_EQ(r.t_reached, 0.0);
  };
  RunSettings rs = settings(out);
  rs.t_end = 9;
  rs.sample_dt = 1e-6;  // 9e6 rows, 5.7 GB
  starts(rs);
  const double row = static_cast<double>(timeseries_columns(dry_scene()).size()) * 17;
  ASSERT_EQ(said.size(), 1u);
  EXPECT_EQ(said[0], "the outputs in " + out.string() + " will grow by about 5.7 GB by t = 9 s (timeseries.csv: " +
                         "9000000 rows of about " + number_text(row) +
                         " bytes), past 1 GB: if that is more than meant, stop the run (Ctrl-C) and sample less "
                         "often (sample)");
  rs.t_end = 1;  // 0.63 GB: none
  starts(rs);
  EXPECT_TRUE(said.empty()) << said[0];
  // kept states: about the size they take in motion (not at rest, where the speeds are "0")
  RunSettings kept = settings(out);
  kept.t_end = 0.05;
  kept.snapshot_every = 0;
  kept.keep_states = true;
  run(dry_scene(), kept);
  const double state = static_cast<double>(fs::file_size(out / "states" / "state_00015.ckpt"));
  kept.t_end = 300;  // 90 000 states
  starts(kept);
  ASSERT_EQ(said.size(), 1u);
  const std::string head = "the outputs in " + out.string() + " will grow by about ";
  ASSERT_EQ(said[0].compare(0, head.size(), head), 0) << said[0];
  const size_t at = said[0].find("states/: 90000 kept states of about ");
  ASSERT_NE(at, std::string::npos) << said[0];
  const double estimate = std::stod(said[0].substr(at + 36)) * 1e3;  // "58 kB"
  EXPECT_NEAR(estimate / state, 1, 0.15) << said[0] << "; a state in motion: " << state << " bytes";
  EXPECT_NE(said[0].find("keep fewer states (frames.fps, frames.slowdown)"), std::string::npos) << said[0];
}

// more than the file system has room for: said with the free space, and what comes of it
TEST(Outputs, OutputsPastTheFreeSpaceAreWarnedOf) {
  OutputVolume v;
  v.rows = 100000, v.row_bytes = 629;
  EXPECT_EQ(volume_warning(v, 1, 0, 1e9, "out/x"), "");
  EXPECT_EQ(volume_warning(v, 1, 0, 3.1e6, "out/x"),
            "the outputs in out/x will grow by about 63 MB by t = 1 s (timeseries.csv: 100000 rows of about 629 "
            "bytes): that is more than the 3.1 MB free on the file system that holds it: the run will stop with an "
            "error when the disk is full (the outputs up to then kept); give it a folder with room (--out, out = "
            "...) or free some space");
  // both, with what the folder holds already
  v.rows = 2e6;
  EXPECT_EQ(volume_warning(v, 20, 5e8, 1e9, "out/x"),
            "the outputs in out/x will grow by about 1.3 GB by t = 20 s (timeseries.csv: 2000000 rows of about 629 "
            "bytes), to about 1.8 GB, past 1 GB: if that is more than meant, stop the run (Ctrl-C) and sample less "
            "often (sample); and that is more than the 1 GB free on the file system that holds it: the run will stop "
            "with an error when the disk is full (the outputs up to then kept); give it a folder with room (--out, "
            "out = ...) or free some space");
}

}  // namespace
}  // namespace beltsim
