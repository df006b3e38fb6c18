#include "script/progress.hpp"

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdarg>
#include <cstdio>

#include "io/duration_text.hpp"
#include "io/number_text.hpp"

namespace beltsim::script {

namespace {

std::atomic<bool> g_open{false};  // a progress line is on the terminal without its end
std::atomic<long> g_ended{0};

// stdout is the terminal stderr is (a script's print lands on the progress line's terminal line)
bool same_terminal() {
  static const bool same = [] {
    struct stat out {
    }, err{};
    return isatty(STDOUT_FILENO) && isatty(STDERR_FILENO) && fstat(STDOUT_FILENO, &out) == 0 &&
           fstat(STDERR_FILENO, &err) == 0 && out.st_rdev == err.st_rdev;
  }();
  return same;
}

}  // namespace

void end_progress_line() {
  if (g_open.exchange(false)) {
    std::fputc('\n', stderr);
    std::fflush(stderr);
    ++g_ended;
  }
}

long progress_lines_ended() {
  return g_ended.load();
}

void say(const char* format, ...) {
  end_progress_line();
  va_list args;
  va_start(args, format);
  std::vfprintf(stderr, format, args);
  va_end(args);
  std::fflush(stderr);
}

void before_stdout() {
  if (g_open.load() && same_terminal()) end_progress_line();
}

void before_write(std::FILE* f) {
  if (f == stdout)
    before_stdout();
  else if (f == stderr)
    end_progress_line();
}

namespace {

// say_run_end's closing line, without "beltsim: "
std::string run_end_text(double t, double t_end, bool interrupted, long steps, double wall,
                         const std::string& out_dir) {
  // two digits of a short run's wall time (0.034 s, 5.2 s, 46 s), minutes as the progress line has them
  const std::string w = wall < 60 ? rounded_text(wall, 2) + " s" : duration_text(wall);
  std::string s = std::string(interrupted ? "run stopped" : "run ended") + " at t = " + rounded_text(t, 4) + " s" +
                  (interrupted ? " of " + rounded_text(t_end, 4) + " s" : "") + " (" + std::to_string(steps) +
                  " steps, " + w + ")";
  if (!out_dir.empty()) s += ": " + out_dir + (out_dir.back() == '/' ? "" : "/");
  return s;
}

}  // namespace

void say_run_end(const RunEnd& e) {
  if (!e.warning_summary.empty()) say("beltsim: %s\n", e.warning_summary.c_str());
  if (!e.check_line.empty()) say("beltsim: %s%s\n", e.check_warns ? "warning: " : "", e.check_line.c_str());
  if (!e.unapplied.empty()) say("beltsim: %s\n", e.unapplied.c_str());
  if (e.closing_line) say("beltsim: %s\n", run_end_text(e.t, e.t_end, e.stopped, e.steps, e.wall, e.out_dir).c_str());
}

ProgressLine::ProgressLine(bool enabled, long steps_before)
    : enabled_(enabled), tty_(isatty(STDERR_FILENO)), steps_before_(steps_before) {}

ProgressLine::~ProgressLine() {
  if (drawn_) draw(true);
}

void ProgressLine::finish(double t, long steps, double wall) {
  t_ = std::min(t, target_), steps_ = steps, wall_ = wall;
}

void ProgressLine::draw(bool last) {
  const double done = t_ - t0_, todo = target_ - t_;
  const double pct = target_ > t0_ ? 100 * done / (target_ - t0_) : 100;
  char text[256];
  int n = std::snprintf(text, sizeof text, "beltsim: t = %.4f s of %.4g s (%.0f %%), %s elapsed, ", t_, target_, pct,
                        duration_text(wall_).c_str());
  if (!last) {
    const double left = done > 0 ? std::max(0.0, wall_ * todo / done) : NAN;
    n += std::snprintf(text + n, sizeof text - n, "about %s left, ", duration_text(left).c_str());
  }
  std::snprintf(text + n, sizeof text - n, "%ld steps", steps_);
  const std::string line = text;
  if (!tty_) {
    std::fprintf(stderr, "%s\n", line.c_str());
  } else {
    // on the line it drew (blanking what a longer text left), or on a line of its own after a message
    const size_t blank = g_open.load() && width_ > line.size() ? width_ - line.size() : 0;
    std::fprintf(stderr, "\r%s%s%s", line.c_str(), std::string(blank, ' ').c_str(), last ? "\n" : "");
    width_ = line.size();
    if (last) {
      g_open = false;
      ++g_ended;
    } else {
      g_open = true;
    }
  }
  std::fflush(stderr);
}

RunProgress ProgressLine::callback() {
  if (!enabled_) return {};
  return [this](double t, double target, const WorkCounters& w, double wall) {
    if (t0_ < 0) t0_ = t;
    // the integrator's last step may end past the target (the samples and callbacks up to the
    // target are read from its dense output): the line shows the run's progress, at most all of it
    t_ = std::min(t, target), target_ = target, wall_ = wall, steps_ = w.steps - steps_before_;
    if (wall < 1.0 || wall - last_ < (tty_ ? 0.5 : 10.0)) return;
    last_ = wall;
    drawn_ = true;
    draw(false);
  };
}

}  // namespace beltsim::script
