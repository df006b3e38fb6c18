// Reading a checkpoint that cannot hurt (sim/checkpoint.cpp, issue 31 §3): only a regular file of
// bounded size is read, every count is bounded by the text and the scene, the scene and settings
// are validated as a script's, the outputs are cut only at row ends past their headers and only
// after everything passed, a checksum catches the rest, and no message is a raw C++ text. The
// mutator at the end damages a saved checkpoint a few hundred ways (a fixed seed) and resumes each
// in a child process with bounded memory and time: each resumes or is refused with a message.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "io/checkpoint_text.hpp"
#include "io/number_text.hpp"
#include "scene/parameters.hpp"
#include "support/presets.hpp"
#include "scene/scene.hpp"
#include "sim/run_table.hpp"
#include "sim/simulation.hpp"
#include "support/checkpoint_edit.hpp"
#include "support/files.hpp"
#include "support/scratch.hpp"
#include "support/warning_guard.hpp"

namespace beltsim {
namespace {

using test::line_of;
using test::resealed;
using test::slurp;
using test::spit;
using test::with_line;

namespace fs = std::filesystem;


fs::path dir() { return test::scratch_dir("beltsim_checkpoint_test"); }

const char* const kOutputs[] = {"timeseries.csv", "events.csv", "snapshots.csv"};

// A run of the paper's dry drive with snapshots, saved at 0.0137 s and continued to 0.02 s: its
// checkpoint's text, and its outputs as the run left them (restored before every resume).
struct Saved {
  std::string text;
  fs::path out, ck;
  std::map<std::string, std::string> outputs;

  Saved() {
    out = dir() / "out";
    ck = dir() / "ck.txt";
    fs::remove_all(out);
    const Scene sc = build_scene(presets::paper_dry());
    RunSettings rs;
    rs.integrator = "esdirk32";
    rs.out_dir = out.string();
    rs.snapshot_times = {0.01, 0.019};
    {
      Simulation s(sc, rs);
      s.run_to(0.0137);
      s.save(ck.string());
      s.run_to(0.02);
    }
    text = slurp(ck);
    for (const char* f : kOutputs) outputs[f] = slurp(out / f);
  }
  void restore() const {
    for (const auto& [f, bytes] : outputs) spit(out / f, bytes);
  }
  bool outputs_untouched() const {
    for (const auto& [f, bytes] : outputs)
      if (slurp(out / f) != bytes) return false;
    return true;
  }
};

const Saved& saved() {
  static const Saved s;
  return s;
}

// The address space a child may add to what this process has mapped: room for a resumed 60-element
// run (a few MB) many times over, far below what an unbounded count would take.
constexpr long kHeadroom = 512L << 20;

struct Outcome {
  bool resumed = false;
  std::string message;     // why it was refused
  std::string failure;     // a crash, a hang, a refusal without words: what happened
  bool untouched = true;   // the outputs were as the run left them after the refusal
};

// What a child reports of each checkpoint it tried, on its pipe: this header, then `length` bytes
// of the refusal's message.
struct Record {
  int32_t code;  // 0 resumed, 3 refused with the message
  int32_t untouched;
  uint32_t length;
};

// Resumes each checkpoint of `paths` in turn in a child process (address space bounded; each
// resume given 30 s) and runs it on for 2 ms, the outputs restored before each. One child takes
// as many as it can: a fork of a process under AddressSanitizer costs some 0.2 s (its stack depot
// is locked, and so copied page by page, at every fork), so a child per checkpoint made the
// mutants below a minute of the sanitizer tests. A checkpoint that kills or hangs the child is
// that checkpoint's failure, and a new child takes the ones after it.
std::vector<Outcome> resume_in_child(const std::vector<fs::path>& paths) {
  saved();  // made here, not in a child
  std::vector<Outcome> out(paths.size());
  long pages = 0;
  std::ifstream("/proc/self/statm") >> pages;
  for (size_t next = 0; next < paths.size();) {
    int fds[2];
    if (pipe(fds) != 0) {
      out[next++].failure = "pipe failed";
      continue;
    }
    const pid_t pid = fork();
    if (pid == 0) {
      close(fds[0]);
#if !defined(__SANITIZE_ADDRESS__)
      // (the sanitizers map terabytes of shadow memory, and stop a huge allocation themselves)
      const rlim_t limit = static_cast<rlim_t>(pages * sysconf(_SC_PAGESIZE) + kHeadroom);
      const rlimit rl{limit, limit};
      setrlimit(RLIMIT_AS, &rl);
#endif
      for (size_t i = next; i < paths.size(); ++i) {
        alarm(30);
        saved().restore();
        std::string msg;
        Record r{0, 1, 0};
        try {
          auto s = Simulation::resume(paths[i].string(), {}, nullptr, {}, true);  // (the run went on to 0.02 s)
          try {
            s->run_to(s->now() + 2e-3);
          } catch (const DivergenceError&) {
            // a state changed on purpose may diverge: that is said, and is not a finding
          }
        } catch (const std::exception& e) {
          msg = e.what();
          r.code = 3;
          r.untouched = saved().outputs_untouched();
        }
        r.length = static_cast<uint32_t>(msg.size());
        if (write(fds[1], &r, sizeof r) != sizeof r ||
            write(fds[1], msg.data(), msg.size()) != static_cast<ssize_t>(msg.size()))
          _exit(4);
      }
      _exit(0);  // (no exit handlers: they belong to the parent)
    }
    close(fds[1]);
    std::string bytes;
    char buf[4096];
    for (ssize_t n; (n = read(fds[0], buf, sizeof buf)) > 0;) bytes.append(buf, static_cast<size_t>(n));
    close(fds[0]);
    int status = 0;
    waitpid(pid, &status, 0);
    for (size_t at = 0; at + sizeof(Record) <= bytes.size() && next < paths.size(); ++next) {
      Record r;
      std::memcpy(&r, bytes.data() + at, sizeof r);
      at += sizeof r;
      Outcome& o = out[next];
      o.message = bytes.substr(at, r.length);
      at += r.length;
      o.resumed = r.code == 0;
      o.untouched = r.untouched != 0;
      if (r.code == 3 && o.message.empty()) o.failure = "refused without a message";
    }
    if (next < paths.size() && !(WIFEXITED(status) && WEXITSTATUS(status) == 0)) {
      // the checkpoint it was on when it died
      out[next++].failure = WIFSIGNALED(status) ? std::string("killed by signal ") + strsignal(WTERMSIG(status))
                                                 : "exit status " + std::to_string(WEXITSTATUS(status));
    }
  }
  return out;
}

fs::path mutant_path(int m = -1) { return dir() / (m < 0 ? "mutant.txt" : "mutant_" + std::to_string(m) + ".txt"); }

Outcome resume_text(const std::string& text) {
  spit(mutant_path(), text);
  return resume_in_child({mutant_path()})[0];
}

// the message of a refusal of `text` (a failure of the test when it resumes or crashes)
std::string refusal(const std::string& text) {
  const Outcome o = resume_text(text);
  EXPECT_TRUE(o.failure.empty()) << o.failure;
  EXPECT_FALSE(o.resumed);
  EXPECT_TRUE(o.untouched);
  return o.message;
}

std::string prefix(int m = -1) { return mutant_path(m).string() + ": "; }

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

// a FIFO or a device would block or never end; a folder is not a file; a huge file is not read
TEST(Checkpoint, ReadsOnlyRegularFilesOfBoundedSize) {
  const fs::path fifo = dir() / "fifo";
  fs::remove(fifo);
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  for (const fs::path& p : {fifo, fs::path("/dev/zero"), dir()}) {
    try {
      Simulation::resume(p.string(), {});
      ADD_FAILURE() << p;
    } catch (const std::runtime_error& e) {
      EXPECT_EQ(std::string(e.what()), p.string() + ": not a regular file, so not a checkpoint");
    }
  }
  const fs::path big = dir() / "big.txt";
  {
    std::ofstream(big) << "beltsim-checkpoint";
  }
  fs::resize_file(big, (1ull << 30) + 1);  // sparse: no disk used
  try {
    Simulation::resume(big.string(), {});
    ADD_FAILURE() << "read a 1 GiB file";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()),
              big.string() + ": 1073741825 bytes, more than any checkpoint (at most 1073741824)");
  }
  fs::remove(big);
}

TEST(Checkpoint, OldVersionsAreRefusedNamingBoth) {
  EXPECT_EQ(refusal("beltsim-checkpoint 3\nintegrator 8 esdirk32\n"),
            prefix() +
                "line 1: a version 3 checkpoint; this beltsim reads versions 12 and 13 only: resume it with the "
                "beltsim that wrote it, or run the scene again from its script");
}

// the counts of issue 31: a billion streams, pending events, interval means
TEST(Checkpoint, HugeCountsAllocateNothing) {
  const std::string& t = saved().text;
  EXPECT_EQ(refusal(resealed(with_line(t, "streams", "streams 1000000000"))),
            prefix() + "line " + std::to_string(line_of(t, "streams")) +
                ": 'streams': 1000000000 values announced, the line holds 0");
  EXPECT_EQ(refusal(resealed(with_line(t, "pending", "pending 1000000000"))),
            prefix() + "line " + std::to_string(line_of(t, "pending")) + ": 'pending': 1000000000 entries of 5 lines " +
                "announced, the file has " + std::to_string(std::count(t.begin(), t.end(), '\n') - line_of(t, "pending") - 1) +
                " lines left");
  EXPECT_EQ(refusal(resealed(with_line(t, "mean_acc", "mean_acc 1000000000 1"))),
            prefix() + "line " + std::to_string(line_of(t, "mean_acc")) +
                ": 'mean_acc': 1000000000 values announced, the line holds 1");
  EXPECT_EQ(refusal(resealed(with_line(t, "integrator.y", "integrator.y 4000000000000 1"))),
            prefix() + "line " + std::to_string(line_of(t, "integrator.y")) +
                ": 'integrator.y': 4000000000000 values announced, the line holds 1");
}

TEST(Checkpoint, MalformedHexFloatIsRefused) {
  const std::string& t = saved().text;
  EXPECT_EQ(refusal(resealed(with_line(t, "rtol", "rtol 0x1.a36e2eb1c432dp-14"))),
            prefix() + "line " + std::to_string(line_of(t, "rtol")) +
                ": 'rtol': expected a number, got '0x1.a36e2eb1c432dp-14'");
  EXPECT_EQ(refusal(resealed(with_line(t, "now", "now 0x1.zzp-7"))),
            prefix() + "line " + std::to_string(line_of(t, "now")) + ": 'now': expected a number, got '0x1.zzp-7'");
}

// the scene inside is checked as a script's scene: issue 31's four cases and a settings' one
TEST(Checkpoint, SceneAndSettingsAreValidated) {
  const std::string& t = saved().text;
  // (the scene's lines: from its first key to the last element site)
  const std::string scene = prefix() + "lines " + std::to_string(line_of(t, "pulleys")) + " to " +
                            std::to_string(line_of(t, "part drive", "\n") - 1) + ": the scene: ";
  auto refused = [&](const std::string& key, const std::string& line, const std::string& expected) {
    const std::string m = refusal(resealed(with_line(t, key, line)));
    EXPECT_NE(m.find(expected), std::string::npos) << m;
    EXPECT_EQ(m.rfind(prefix(), 0), 0u) << m;
    if (expected.rfind("the scene: ", 0) == 0) {
      EXPECT_EQ(m, scene + expected.substr(11));
    }
  };
  refused("pulley.inertia", "pulley.inertia -0.025", "the scene: pulley 'driver'.inertia must be > 0 (got -0.025 kg·m²)");
  refused("contact.p_max", "contact.p_max 0", "the scene: contact.p_max must be > 0 (got 0 m)");
  refused("friction.dv", "friction.dv 0",
          "the scene: friction.dv " + std::string(rule_text(Rule::slip_band)) + " (got 0 m/s)");
  refused("belt.mu", "belt.mu 3 0.3 0.3 0.3", "'belt.mu': 3 values for 60 elements");
  std::string mu = "belt.mu 60 -1";
  for (int i = 1; i < 60; ++i) mu += " 0.3";
  refused("belt.mu", mu, "'belt.mu': belt.mu of element 0 must be in [0, 10]: a friction coefficient");
  refused("sample", "sample 0", "the run settings: sample: must be > 0 s and finite (got 0 s)");
  refused("integrator", "integrator \"euler\"", "the run settings: ");
}

// forgeries sealed with a matching checksum (issue 45 §5): settings a script could not give, a
// scene a script could not give, a time outside the run and counts the run cannot have reached
TEST(Checkpoint, ForgeriesAreRefused) {
  const std::string& t = saved().text;
  auto refused = [&](const std::string& text, const std::string& expected) {
    SCOPED_TRACE(expected);
    const std::string m = refusal(resealed(text));
    EXPECT_NE(m.find(expected), std::string::npos) << m;
    EXPECT_EQ(m.rfind(prefix(), 0), 0u) << m;
  };
  const std::string settings =
      prefix() + "lines 3 to " + std::to_string(line_of(t, "part scene", "\n") - 1) + ": the run settings: ";
  refused(with_line(t, "atol", "atol -2"),
          settings + "atol: must be > 0 and finite, or left out to mean rtol (got -2)");
  refused(with_line(t, "atol", "atol nan"), "'atol': expected a finite number, got nan");
  refused(with_line(t, "out", "out \"\""), settings + "out: an empty path");
  // two pulleys of one name: the driven pulley renamed wherever the text names it
  std::string twins = t;
  for (const std::string from : {"name \"driven\"", "drive \"driven\"", "\"driver\" \"driven\"", "pulley.driven."}) {
    const std::string to = std::string(from).replace(from.find("driven"), 6, "driver");
    for (size_t at; (at = twins.find(from)) != std::string::npos;) twins.replace(at, from.size(), to);
  }
  refused(twins, "the scene: pulley 2.name: pulleys 1 and 2 are both named 'driver'");
  refused(with_line(t, "friction.dv", "friction.dv 1e300"), "the scene: friction.dv must be in (0, 1] m/s: ");
  // the integrator's step: its end far past the checkpoint's time (its dense output would span
  // it), alone and with the step's length to match; the next step far longer than the last
  const std::string h_used = "line " + std::to_string(line_of(t, "integrator.h_used")) + ": 'integrator.h_used': ";
  refused(with_line(t, "integrator.t", "integrator.t 1e300"),
          h_used + "the last step's length must be the distance between its ends, integrator.t - integrator.t_prev = ");
  const double t_prev = std::stod(test::value_of(t, "integrator.t_prev"));
  refused(
      with_line(with_line(t, "integrator.t", "integrator.t 1e300"), "integrator.h_used",
                "integrator.h_used " + number_text(1e300 - t_prev)),
      h_used + "a step of 1e+300 s from t = " + number_text(t_prev) + " s is longer than any this integrator takes");
  refused(
      with_line(t, "integrator.h", "integrator.h 1e300"),
      "line " + std::to_string(line_of(t, "integrator.h")) + ": 'integrator.h': a next step of 1e+300 s after one of ");
  // counts the run cannot have reached by its time at its sample interval and frame rate
  refused(with_line(t, "frames_written", "frames_written 99999999999"),
          "line " + std::to_string(line_of(t, "frames_written")) +
              ": 'frames_written': 99999999999 frames written by t = 0.0137 s, at most the 0 frame times by then");
  refused(with_line(t, "rows", "rows 99999999999"),
          "line " + std::to_string(line_of(t, "rows")) +
              ": 'rows': 99999999999 samples written by t = 0.0137 s, at most 14 at a sample every 0.001 s");
}

// the outputs are cut at the saved positions only when those are row ends past the header, and
// only after the whole checkpoint passed
TEST(Checkpoint, OutputsAreCutOnlyAtRowEndsPastTheirHeaders) {
  const std::string& t = saved().text;
  const std::string csv = (saved().out / "timeseries.csv").string();
  EXPECT_EQ(refusal(resealed(with_line(t, "csv_bytes", "csv_bytes 0"))),
            prefix() + "the checkpoint continues " + csv + " from byte 0, inside its header line: cutting it there " +
                "would lose the header");
  EXPECT_EQ(refusal(resealed(with_line(t, "csv_bytes", "csv_bytes 20"))),
            prefix() + "the checkpoint continues " + csv + " from byte 20, inside its header line: cutting it there " +
                "would lose the header");
  const size_t header = saved().outputs.at("timeseries.csv").find('\n') + 1;
  EXPECT_EQ(refusal(resealed(with_line(t, "csv_bytes", "csv_bytes " + std::to_string(header + 5)))),
            prefix() + "the checkpoint continues " + csv + " from byte " + std::to_string(header + 5) +
                ", which is not the end of a row");
  // a later output wrong: the earlier ones are not cut either (refusal() checks them all)
  refusal(resealed(with_line(t, "snapshots_bytes", "snapshots_bytes 3")));
}

// a damaged file: the line when the damage shows in it, else the checksum's line
TEST(Checkpoint, DamageIsRefusedNamingTheLine) {
  const std::string& t = saved().text;
  const int last = static_cast<int>(std::count(t.begin(), t.end(), '\n'));
  EXPECT_EQ(refusal(with_line(t, "rtol", "rtol 0.0002")),
            prefix() + "line " + std::to_string(last) +
                ": the checksum does not match the text before it: the file was damaged or changed after it was "
                "written");
  EXPECT_EQ(refusal(with_line(t, "rtol", "rtol 0.0@01")),
            prefix() + "line " + std::to_string(line_of(t, "rtol")) + ": 'rtol': expected a number, got '0.0@01' " +
                "(and the file does not match its checksum, line " + std::to_string(last) +
                ": it was damaged or changed after it was written)");
  EXPECT_EQ(refusal(t.substr(0, t.size() / 2)).rfind(prefix() + "line ", 0), 0u);
}

// C++'s own texts for what went wrong inside it (none of them means anything to a user)
bool raw(const std::string& m) {
  for (const char* s : {"basic_string", "bad_alloc", "_M_", "std::", "vector::", "stoi", "stod", "bad_optional",
                        "bad_variant", "out_of_range", "filesystem error"})
    if (m.find(s) != std::string::npos) return true;
  return false;
}

// A few hundred mutants of the saved checkpoint (a fixed seed): bytes flipped, deleted or
// inserted, lines deleted, duplicated or swapped, numbers replaced by extreme values; every
// second one sealed again with a matching checksum, so that the reader's own checks are reached.
TEST(Checkpoint, MutantsResumeOrAreRefusedWithAMessage) {
  // a changed state may fail steps, and a changed law jump: the warnings are not findings here
  test::expect_warnings({WarningKind::failed_step});
  const std::string& t = saved().text;
  std::vector<std::string> lines;
  for (size_t b = 0, e; b < t.size(); b = e + 1) lines.push_back(t.substr(b, (e = t.find('\n', b)) - b));
  const char* const extremes[] = {"0", "-1", "1e308", "-1e308", "1000000000", "-0", "5e-324", "nan", "inf",
                                  "9223372036854775807", "-9223372036854775808", "2147483648", "1e-300", "3"};
  std::mt19937 rng(20240531);
  auto pick = [&](size_t n) { return std::uniform_int_distribution<size_t>(0, n - 1)(rng); };
  constexpr int kMutants = 300;
  struct Mutant {
    int m;
    bool sealed;
    std::string what;
  };
  std::vector<Mutant> mutants;
  for (int m = 0; m < kMutants; ++m) {
    std::vector<std::string> l = lines;
    std::string text, what;
    const size_t i = 1 + pick(l.size() - 2);  // never the first line (its own test) nor the checksum
    switch (pick(7)) {
      case 0: {  // a byte changed
        std::string& s = l[i];
        if (s.empty()) break;
        const size_t k = pick(s.size());
        s[k] = static_cast<char>(s[k] ^ (1 + pick(255)));
        what = "byte " + std::to_string(k) + " of line " + std::to_string(i + 1) + " changed";
        break;
      }
      case 1: what = "line " + std::to_string(i + 1) + " deleted", l.erase(l.begin() + static_cast<long>(i)); break;
      case 2: what = "line " + std::to_string(i + 1) + " duplicated", l.insert(l.begin() + static_cast<long>(i), l[i]); break;
      case 3: what = "lines " + std::to_string(i + 1) + " and " + std::to_string(i + 2) + " swapped";
              if (i + 2 < l.size()) std::swap(l[i], l[i + 1]);
              break;
      case 4: {  // a byte deleted
        if (l[i].empty()) break;
        const size_t k = pick(l[i].size());
        l[i].erase(k, 1);
        what = "byte " + std::to_string(k) + " of line " + std::to_string(i + 1) + " deleted";
        break;
      }
      case 5: {  // a digit inserted
        const size_t k = pick(l[i].size() + 1);
        l[i].insert(k, 1, static_cast<char>('0' + pick(10)));
        what = "a digit inserted at " + std::to_string(k) + " of line " + std::to_string(i + 1);
        break;
      }
      default: {  // one value of the line replaced by an extreme one
        std::vector<size_t> starts;
        for (size_t k = 0; k < l[i].size(); ++k)
          if (l[i][k] == ' ') starts.push_back(k + 1);
        if (starts.empty()) break;
        const size_t b = starts[pick(starts.size())];
        const size_t e = std::min(l[i].find(' ', b), l[i].size());
        const std::string x = extremes[pick(std::size(extremes))];
        what = "value '" + l[i].substr(b, e - b) + "' of line " + std::to_string(i + 1) + " replaced by " + x;
        l[i].replace(b, e - b, x);
      }
    }
    for (const std::string& s : l) text += s + '\n';
    const bool sealed = m % 2 == 1;
    if (sealed) text = resealed(text);
    if (text == t) continue;
    spit(mutant_path(m), text);
    mutants.push_back({m, sealed, what});
  }
  std::vector<fs::path> paths;
  for (const Mutant& mu : mutants) paths.push_back(mutant_path(mu.m));
  const std::vector<Outcome> outcomes = resume_in_child(paths);
  int resumed = 0, refused = 0;
  for (size_t k = 0; k < mutants.size(); ++k) {
    const Mutant& mu = mutants[k];
    const Outcome& o = outcomes[k];
    SCOPED_TRACE("mutant " + std::to_string(mu.m) + (mu.sealed ? " (sealed again): " : ": ") + mu.what);
    EXPECT_TRUE(o.failure.empty()) << o.failure;
    if (o.resumed) {
      ++resumed;
      EXPECT_TRUE(mu.sealed) << "a damaged checkpoint resumed";
    } else if (o.failure.empty()) {
      ++refused;
      EXPECT_FALSE(raw(o.message)) << o.message;
      EXPECT_EQ(o.message.rfind(prefix(mu.m), 0), 0u) << o.message;  // names the file
      EXPECT_TRUE(o.untouched) << o.message;
    }
  }
  std::printf("checkpoint mutants: %d resumed, %d refused\n", resumed, refused);
  EXPECT_GT(refused, kMutants / 2);
}

}  // namespace
}  // namespace beltsim
