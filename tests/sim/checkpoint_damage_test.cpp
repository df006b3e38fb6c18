// A checkpoint that cannot hurt (sim/checkpoint.cpp, issue 31 §3): only a regular file of
// bounded size is read, every count is bounded by the text and the scene, the scene and settings
// are validated as a script's, the outputs are cut only at row ends past their headers and only
// after everything passed, a checksum catches the rest, and no message is a raw C++ text. The
// mutator at the end damages a saved checkpoint a few hundred ways (a fixed seed) and resumes each
// in a child process with bounded memory and time: each resumes or is refused with a message.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "checkpoint_support.hpp"
#include "io/number_text.hpp"
#include "scene/parameters.hpp"
#include "sim/simulation.hpp"
#include "support/checkpoint_edit.hpp"
#include "support/files.hpp"
#include "support/warning_guard.hpp"

namespace beltsim::checkpoint_test {
namespace {

using test::line_of;
using test::resealed;
using test::spit;
using test::with_line;

// the message of a refusal of `text` (a failure of the test when it resumes or crashes)
std::string refusal(const std::string& text) {
  const Outcome o = resume_text(text);
  EXPECT_TRUE(o.failure.empty()) << o.failure;
  EXPECT_FALSE(o.resumed);
  EXPECT_TRUE(o.untouched);
  return o.message;
}

std::string prefix(int m = -1) {
  return mutant_path(m).string() + ": ";
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
  { std::ofstream(big) << "beltsim-checkpoint"; }
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
                "line 1: a version 3 checkpoint; this beltsim reads versions 12 to 14 only: resume it with the "
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
                "announced, the file has " +
                std::to_string(std::count(t.begin(), t.end(), '\n') - line_of(t, "pending") - 1) + " lines left");
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
  refused("pulley.inertia", "pulley.inertia -0.025",
          "the scene: pulley 'driver'.inertia must be > 0 (got -0.025 kg·m²)");
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
  const char* const extremes[] = {"0",
                                  "-1",
                                  "1e308",
                                  "-1e308",
                                  "1000000000",
                                  "-0",
                                  "5e-324",
                                  "nan",
                                  "inf",
                                  "9223372036854775807",
                                  "-9223372036854775808",
                                  "2147483648",
                                  "1e-300",
                                  "3"};
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
      case 1:
        what = "line " + std::to_string(i + 1) + " deleted", l.erase(l.begin() + static_cast<long>(i));
        break;
      case 2:
        what = "line " + std::to_string(i + 1) + " duplicated", l.insert(l.begin() + static_cast<long>(i), l[i]);
        break;
      case 3:
        what = "lines " + std::to_string(i + 1) + " and " + std::to_string(i + 2) + " swapped";
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
}  // namespace beltsim::checkpoint_test
