// Shared by the checkpoint tests: the saved run they resume, and resuming checkpoints in a child process.
#pragma once

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "sim/simulation.hpp"
#include "support/files.hpp"
#include "support/presets.hpp"
#include "support/scratch.hpp"

namespace beltsim::checkpoint_test {

namespace fs = std::filesystem;

inline fs::path dir() {
  return test::scratch_dir("beltsim_checkpoint_test");
}

inline const char* const kOutputs[] = {"timeseries.csv", "events.csv", "snapshots.csv"};

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
    text = test::slurp(ck);
    for (const char* f : kOutputs) outputs[f] = test::slurp(out / f);
  }
  void restore() const {
    for (const auto& [f, bytes] : outputs) test::spit(out / f, bytes);
  }
  bool outputs_untouched() const {
    for (const auto& [f, bytes] : outputs)
      if (test::slurp(out / f) != bytes) return false;
    return true;
  }
};

// (inline: one Saved for the program, whichever test file asks first)
inline const Saved& saved() {
  static const Saved s;
  return s;
}

// The address space a child may add to what this process has mapped: room for a resumed 60-element
// run (a few MB) many times over, far below what an unbounded count would take.
inline constexpr long kHeadroom = 512L << 20;

struct Outcome {
  bool resumed = false;
  std::string message;    // why it was refused
  std::string failure;    // a crash, a hang, a refusal without words: what happened
  bool untouched = true;  // the outputs were as the run left them after the refusal
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
// mutants (checkpoint_damage_test.cpp) a minute of the sanitizer tests. A checkpoint that kills or hangs the child is
// that checkpoint's failure, and a new child takes the ones after it.
inline std::vector<Outcome> resume_in_child(const std::vector<fs::path>& paths) {
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

inline fs::path mutant_path(int m = -1) {
  return dir() / (m < 0 ? "mutant.txt" : "mutant_" + std::to_string(m) + ".txt");
}

inline Outcome resume_text(const std::string& text) {
  test::spit(mutant_path(), text);
  return resume_in_child({mutant_path()})[0];
}

}  // namespace beltsim::checkpoint_test
