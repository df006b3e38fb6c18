#include "sweep/driver.hpp"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>
#include <thread>

#include "io/duration_text.hpp"
#include "io/output_dir.hpp"
#include "sweep/results.hpp"

namespace beltsim::sweep {

namespace {

using Clock = std::chrono::steady_clock;

struct Running {
  const Point* point;
  Clock::time_point start;
  // its earlier folder, which held a point.csv, is kept aside (keep_earlier_folder) until this
  // run ends: its folder had no point.csv when it started, so one there is this run's
  bool kept;
};

// the last line of a point's log that is not blank ("" when none)
std::string last_log_line(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::string line, last;
  while (std::getline(f, line))
    if (line.find_first_not_of(" \t\r") != std::string::npos) last = line;
  if (!last.empty() && last.back() == '\r') last.pop_back();
  return last;
}

class Progress {
 public:
  Progress(const DriverSettings& s, int total) : s_(s), total_(total), tty_(isatty(2)) {}
  // standing: the results counted (summary.csv's, but of the points waiting or running); left:
  // time_left's estimate
  void show(const SummaryCounts& standing, std::size_t running, std::optional<double> left, bool final_line) {
    std::string line = "sweep " + s_.name + ": " + std::to_string(standing.ok) + "/" + std::to_string(total_) +
                       " done" + standing.over_text(true) + ", " + std::to_string(standing.failed) + " failed";
    if (running > 0) line += ", " + std::to_string(running) + " running";
    if (left) line += ", about " + duration_text(*left) + " left";
    if (tty_)
      std::fprintf(stderr, "\r%s\033[K%s", line.c_str(), final_line ? "\n" : "");
    else if (final_line || line != last_)
      std::fprintf(stderr, "%s\n", line.c_str());
    last_ = line;
  }
  // a message on a line of its own (the progress line redrawn after it on a terminal)
  void say(const std::string& m) { std::fprintf(stderr, tty_ ? "\r%s\033[K\n" : "%s\n", m.c_str()); }

 private:
  const DriverSettings& s_;
  int total_;
  bool tty_;
  std::string last_;
};

// summary.csv as the points stand, rewritten as they finish, so that a sweep killed outright
// (kill -9, a node lost) leaves it true to what finished; the writing kept to a tenth of the time
// or less (a sweep of very many points writes it less often)
struct LiveSummary {
  const std::vector<Point>& points;
  Results results;
  const OutputDir& top;
  Figures figures;
  Clock::time_point next{};
  std::optional<PointResult>& of(const Point& p) { return results[static_cast<std::size_t>(&p - points.data())]; }
  void write() {
    const Clock::time_point t0 = Clock::now();
    if (t0 < next) return;
    write_summary(top, points, results, figures);
    const Clock::time_point t1 = Clock::now();
    next = t1 + 9 * (t1 - t0);
  }
};

// the lines that say what this run does before it starts: the points that run again for a change
// of their inputs, with why; --rerun; the points done already
void say_plan(Progress& progress, const DriverSettings& s, std::size_t total, const DriverReport& report,
              const Reasons& reasons, std::size_t todo) {
  for (const std::string& line : reason_lines(s.name, reasons)) progress.say(line);
  if (s.rerun)
    progress.say("sweep " + s.name + ": --rerun: all " + std::to_string(total) + " points run again");
  else if (report.already_done > 0)
    progress.say("sweep " + s.name + ": " + std::to_string(report.already_done) + " of " + std::to_string(total) +
                 " points done already (" + s.dir + "), " + std::to_string(todo) + " to run");
}

// the points to run: every one with rerun, else those not done; the points done and those run
// again for a change of their inputs counted in the report
std::vector<const Point*> points_to_run(const std::vector<Point>& points, const Results& results, bool rerun,
                                        DriverReport& report) {
  std::vector<const Point*> todo;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const auto& r = results[k];
    if (!rerun && r && r->ok()) {
      ++report.already_done;
      continue;
    }
    todo.push_back(&points[k]);
    if (r && r->outdated()) ++report.outdated;
  }
  return todo;
}

}  // namespace

std::optional<double> time_left(const std::vector<double>& ran, const std::vector<double>& running, int waiting,
                                int jobs) {
  if (ran.empty()) return std::nullopt;
  double per = 0;
  for (double t : ran) per += t;
  per /= static_cast<double>(ran.size());
  // when each process comes free: the running points' rest, then the waiting points in turn on
  // the process free first
  std::vector<double> free(static_cast<std::size_t>(std::max(1, jobs)), 0.0);
  for (std::size_t k = 0; k < running.size(); ++k)
    free[k % free.size()] = std::max(free[k % free.size()], per - running[k]);
  for (int k = 0; k < waiting; ++k) *std::min_element(free.begin(), free.end()) += per;
  const double left = *std::max_element(free.begin(), free.end());
  if (left <= 0) return std::nullopt;
  return left;
}

DriverReport run_points(const std::vector<Point>& points, const DriverSettings& s, const OutputDir& top) {
  DriverReport report;
  Definition now = s.definition;
  LiveSummary summary{points, current_results(s.dir, points, now), top, s.quick ? Figures::kRunResult : Figures::kOwn};
  const Reasons reasons = rerun_reasons(summary.results);
  const std::vector<const Point*> todo = points_to_run(points, summary.results, s.rerun, report);
  const auto slot = [&](const Point& p) -> std::optional<PointResult>& { return summary.of(p); };
  const auto summary_now = [&] { summary.write(); };
  // the points to run whose run has not ended: the progress line counts their results when it has
  std::vector<bool> pending(points.size(), false);
  for (const Point* p : todo) pending[static_cast<std::size_t>(p - points.data())] = true;
  std::vector<double> ran;  // the times of the points that ran to their end (ok) in this run
  Progress progress(s, static_cast<int>(points.size()));
  say_plan(progress, s, points.size(), report, reasons, todo.size());
  if (const std::string line = moved_line(s.name, top, move_stale_folders(top, points)); !line.empty())
    progress.say(line);
  std::map<pid_t, Running> running;
  std::size_t next = 0;
  bool forwarded = false;
  bool said_no_figures = false;  // a point ok without figures: said once

  const auto show = [&](bool final_line) {
    SummaryCounts standing;
    for (std::size_t k = 0; k < points.size(); ++k)
      if (!pending[k]) standing.add(summary.results[k]);
    std::vector<double> elapsed;
    for (const auto& [pid, r] : running)
      elapsed.push_back(std::chrono::duration<double>(Clock::now() - r.start).count());
    // (no estimate once stopped: the running points are ending and no other starts)
    const std::optional<double> left =
        forwarded ? std::nullopt : time_left(ran, elapsed, static_cast<int>(todo.size() - next), s.jobs);
    progress.show(standing, running.size(), left, final_line);
  };

  // the sweep's end: the points stopped before their run ended count by the result they keep
  const auto close = [&] {
    SummaryCounts kept;
    for (std::size_t k = 0; k < points.size(); ++k)
      if (pending[k]) kept.add(summary.results[k]), pending[k] = false;
    if (const int n = kept.ok + kept.failed; n > 0)
      progress.say("sweep " + s.name + ": stopped before " + std::to_string(n) + (n == 1 ? " point" : " points") +
                   " ran again: " + (n == 1 ? "it keeps its" : "they keep their") + " earlier " +
                   (n == 1 ? "result" : "results") + " (" + std::to_string(kept.ok) + " ok, " +
                   std::to_string(kept.failed) + " failed)");
    show(true);
  };

  // p's process started, in its folder, its output into log.txt
  const auto start = [&](const Point& p, bool kept) {
    const OutputDir folder(top, p.id);
    const int log = folder.open_file("log.txt", false);
    std::vector<std::string> args{s.program};
    args.insert(args.end(), s.point_args.begin(), s.point_args.end());
    args.push_back("--point");
    args.push_back(std::to_string(p.index));
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    const pid_t parent = getpid();
    // the stop signals are blocked across the fork: one sent to the child before its exec stays
    // pending until the child has their default actions back, rather than being taken by this
    // process's handlers in the child and lost at the exec
    sigset_t stops, old;
    sigemptyset(&stops);
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&stops, sig);
    pthread_sigmask(SIG_BLOCK, &stops, &old);
    const pid_t pid = fork();
    if (pid != 0) pthread_sigmask(SIG_SETMASK, &old, nullptr);
    if (pid < 0) {
      const int e = errno;
      ::close(log);
      throw std::runtime_error("cannot start the process of point " + p.id + ": " + std::strerror(e));
    }
    if (pid == 0) {  // the child: only async-signal-safe calls until exec
      for (int sig : {SIGINT, SIGTERM, SIGHUP}) signal(sig, SIG_DFL);
      sigprocmask(SIG_SETMASK, &old, nullptr);
      setpgid(0, 0);
      // the sweep killed outright (kill -9): its points stop too, their outputs closed
      prctl(PR_SET_PDEATHSIG, SIGTERM);
      if (getppid() != parent) _exit(143);
      const int null = ::open("/dev/null", O_RDONLY);
      if (null >= 0) dup2(null, 0);
      dup2(log, 1);
      dup2(log, 2);
      execv(argv[0], argv.data());
      const char m[] = "beltsim sweep: cannot run the program for this point\n";
      (void)!::write(2, m, sizeof m - 1);
      _exit(127);
    }
    ::close(log);
    running[pid] = Running{&p, Clock::now(), kept};
  };

  // the earlier folder of a point whose run again has ended (with a result: removed) or been stopped
  // (put back); a failure is said and left for the next run of the sweep to settle
  const auto settle = [&](const Point& p, bool ended) {
    try {
      if (ended)
        drop_earlier_folder(top, p.id);
      else
        restore_earlier_folder(top, p.id);
    } catch (const std::exception& e) {
      progress.say(std::string("beltsim sweep: ") + e.what() + " (the next run of the sweep settles it)");
      mark_output_failure_shown(e.what());
    }
  };

  const auto launch = [&](const Point& p) {
    // its earlier folder aside, whole, while it runs in a new one (its files name their folder)
    const bool kept = keep_earlier_folder(top, p.id);
    try {
      start(p, kept);
    } catch (...) {
      if (kept) settle(p, false);
      throw;
    }
  };

  const auto finish = [&](pid_t pid, int status) {
    const Running r = running.at(pid);
    running.erase(pid);
    const Point& p = *r.point;
    const double seconds = std::chrono::duration<double>(Clock::now() - r.start).count();
    // (a point.csv there is this run's: an earlier one was moved aside with its folder)
    std::optional<PointResult> result = read_point_result(s.dir, p);
    if (!result && forwarded) {  // stopped before its end: it keeps its earlier folder and result, if any
      if (r.kept) settle(p, false);
      return;
    }
    if (!result) {
      const std::string log = (std::filesystem::path(s.dir) / p.id / "log.txt").string();
      std::string why = WIFSIGNALED(status) ? "its process was killed by signal " + std::to_string(WTERMSIG(status))
                                            : "its process ended with status " + std::to_string(WEXITSTATUS(status)) +
                                                  " without a result";
      const std::string last = last_log_line(log);
      why += last.empty() ? " (" + log + " is empty)" : " (" + log + ": " + last + ")";
      result = PointResult{error_status(why), {}, ""};
      try {
        write_point_result(s.dir, p, *result);
      } catch (const std::exception& e) {
        progress.say(std::string("beltsim sweep: ") + e.what());
      }
    }
    if (r.kept) settle(p, true);  // a result of this run (a process that died has failed): the earlier one goes
    slot(p) = result;
    pending[static_cast<std::size_t>(&p - points.data())] = false;
    summary_now();
    if (result->ok()) {
      ran.push_back(seconds);
      if (result->figures.empty() && !said_no_figures) {
        said_no_figures = true;
        progress.say("sweep " + s.name + ": warning: point " + p.id + " (" + params_text(p) +
                     ") is ok with no figures: " +
                     (s.quick ? "the script made no scene:run{}" : "run(p) returned an empty table") +
                     " (said of the first such point only)");
      }
    } else {
      progress.say("sweep " + s.name + ": point " + p.id + " (" + params_text(p) + "): " + result->status);
    }
  };

  try {
    bool changed = true;
    while ((next < todo.size() && !forwarded) || !running.empty()) {
      if (s.stop && s.stop->load() && !forwarded) {
        forwarded = true;
        report.stopped = true;
        const int sig = s.stop_signal ? s.stop_signal() : SIGINT;
        for (const auto& [pid, r] : running) kill(pid, sig == 0 ? SIGINT : sig);
      }
      while (!forwarded && running.size() < static_cast<std::size_t>(std::max(1, s.jobs)) && next < todo.size())
        launch(*todo[next++]);
      if (changed) show(false);
      changed = false;
      int status = 0;
      const pid_t pid = waitpid(-1, &status, WNOHANG);
      if (pid > 0 && running.count(pid)) {
        finish(pid, status);
        changed = true;
      } else if (pid <= 0) {
        if (pid < 0 && errno != EINTR && errno != ECHILD)
          throw std::runtime_error(std::string("waitpid: ") + std::strerror(errno));
        std::this_thread::sleep_for(std::chrono::milliseconds(20));  // the children's end is polled with the stop flag
      }
    }
  } catch (...) {
    // a point that cannot start, a failed wait: the points running are stopped as by a signal
    // and waited for (their outputs closed, their folders as a stop leaves them), then the error
    // goes on
    forwarded = true;
    for (const auto& [pid, r] : running) kill(pid, SIGTERM);
    while (!running.empty()) {
      int status = 0;
      const pid_t pid = waitpid(running.begin()->first, &status, 0);
      if (pid > 0)
        finish(pid, status);
      else if (errno != EINTR)
        running.erase(running.begin());  // not a child any more: nothing to wait for
    }
    close();
    throw;
  }
  close();
  return report;
}

}  // namespace beltsim::sweep
