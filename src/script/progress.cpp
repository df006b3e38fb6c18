#include "script/progress.hpp"

#include <sys/ioctl.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>

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

// the terminal on stdin while a progress line holds its echo off: its echo flags before (restore_echo)
tcflag_t g_echo_flags = 0;
std::atomic<bool> g_echo_off{false};
constexpr tcflag_t kEchoFlags = ECHO | ECHONL;

// stdin is a terminal whose foreground this process is in (a background process that sets its
// modes is stopped with SIGTTOU)
bool terminal_in_foreground() {
  return isatty(STDIN_FILENO) && tcgetpgrp(STDIN_FILENO) == getpgrp();
}

// turns the terminal's echo off; true when this call did (false: no terminal in the foreground,
// its echo already off, or another line holds it off)
bool echo_off() {
  termios t{};
  if (g_echo_off.load() || !terminal_in_foreground() || tcgetattr(STDIN_FILENO, &t) != 0 || !(t.c_lflag & ECHO))
    return false;
  static const bool at_exit = std::atexit(restore_echo) == 0;  // exit() from a run (os.exit with --trusted)
  (void)at_exit;
  g_echo_flags = t.c_lflag & kEchoFlags;
  g_echo_off.store(true);  // before the change: a signal that ends the process from here on restores it
  t.c_lflag &= ~kEchoFlags;
  if (tcsetattr(STDIN_FILENO, TCSANOW, &t) == 0) return true;  // TCSANOW: what was typed stays
  g_echo_off.store(false);
  return false;
}

}  // namespace

void restore_echo() {
  if (!g_echo_off.exchange(false)) return;
  termios t{};  // (only async-signal-safe calls: stdin was a terminal when the echo was turned off)
  if (tcgetpgrp(STDIN_FILENO) != getpgrp() || tcgetattr(STDIN_FILENO, &t) != 0) return;
  t.c_lflag = (t.c_lflag & ~kEchoFlags) | g_echo_flags;
  tcsetattr(STDIN_FILENO, TCSANOW, &t);
}

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
                  (steps == 1 ? " step, " : " steps, ") + w + ")";
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

ProgressLine::ProgressLine(bool enabled, long steps_before, double origin)
    : enabled_(enabled), tty_(isatty(STDERR_FILENO)), origin_(origin), steps_before_(steps_before) {}

ProgressLine::~ProgressLine() {
  if (drawn_) draw(true);
  if (echo_off_) restore_echo();
}

void ProgressLine::finish(double t, long steps, double wall) {
  t_ = std::min(t, target_), steps_ = steps, wall_ = wall;
}

// the terminal's width in columns (0: unknown)
static int terminal_columns() {
  winsize ws{};
  return ioctl(STDERR_FILENO, TIOCGWINSZ, &ws) == 0 ? ws.ws_col : 0;
}

std::string fit_progress_text(const ProgressParts& p, int columns) {
  // the parts a narrow terminal drops first come last here: the steps, then the elapsed time, then
  // the estimate (a line longer than the terminal wraps, and each redraw then leaves a line behind)
  for (int keep = 3; keep >= 0; --keep) {
    std::string line = p.head;
    if (keep > 1 && !p.elapsed.empty()) line += ", " + p.elapsed;
    if (keep > 0 && !p.left.empty()) line += ", " + p.left;
    if (keep > 2 && !p.steps.empty()) line += ", " + p.steps;
    if (columns <= 0 || static_cast<int>(line.size()) < columns) return line;
  }
  return columns > 1 ? p.head.substr(0, columns - 1) : p.head;
}

double wall_left(const std::deque<std::pair<double, double>>& seen, double t0, double t, double target, double wall) {
  // at the rate of the last third of the wall time so far (a run's cost per simulated second
  // changes as it goes: a start-up ramp is cheaper than the drive at speed), else of all of it
  double t_ref = t0, w_ref = 0;
  for (const auto& [w, ts] : seen)
    if (w <= 2 * wall / 3 && ts < t) t_ref = ts, w_ref = w;
  const double done = t - t_ref;
  return done > 0 ? std::max(0.0, (wall - w_ref) * (target - t) / done) : NAN;
}

std::string progress_head(double t, double target, double origin) {
  const double pct = target > origin ? std::clamp(100 * (t - origin) / (target - origin), 0.0, 100.0) : 100;
  char text[256];
  std::snprintf(text, sizeof text, "beltsim: t = %.4f s of %.4g s (%.0f %%)", t, target, pct);
  return text;
}

ProgressParts ProgressLine::run_parts(bool last) const {
  ProgressParts parts;
  // from the simulation's start (a state restored to before it: from where this call started);
  // the estimate of the time left is this call's rate over what is left of it
  const double origin = std::isnan(origin_) ? t0_ : std::min(origin_, t0_);
  parts.head = progress_head(t_, target_, origin);
  parts.elapsed = duration_text(wall_) + " elapsed";
  if (!last) parts.left = "about " + duration_text(wall_left(seen_, t0_, t_, target_, wall_)) + " left";
  parts.steps = std::to_string(steps_) + " steps";
  if (!last && h_recent_ > 0) parts.steps += " (lately " + rounded_text(h_recent_, 2) + " s each)";
  return parts;
}

ProgressParts ProgressLine::build_parts(bool last) const {
  // no estimate: how many Newton iterations the static state will take is not known before
  ProgressParts parts;
  const std::string belt = "(" + std::to_string(elements_) + " elements)";
  parts.head = built_ ? "beltsim: scene built " + belt : "beltsim: building the scene " + belt + ": " + stage_;
  parts.elapsed = duration_text(wall_) + " elapsed";
  if (newton_ > 0 && (built_ || last))
    parts.steps = std::to_string(newton_) + " Newton iteration" + (newton_ == 1 ? "" : "s");
  else if (newton_ > 0)
    parts.steps = "Newton iteration " + std::to_string(newton_) +
                  (residual_ >= 0 ? ": " + rounded_text(residual_, 2) + " m/s² from equilibrium" : "");
  return parts;
}

bool ProgressLine::due(double wall) {
  if (wall < 1.0 || wall - last_ < (tty_ ? 0.5 : 10.0)) return false;
  last_ = wall;
  drawn_ = true;
  return true;
}

void ProgressLine::draw(bool last) {
  const ProgressParts parts = build_ ? build_parts(last) : run_parts(last);
  const std::string line = fit_progress_text(parts, tty_ ? terminal_columns() : 0);
  if (!tty_) {
    std::fprintf(stderr, "%s\n", line.c_str());
  } else {
    // the keys typed from now on would be echoed onto the line: no echo until the line's end (the destructor)
    if (!last && !echo_off_) echo_off_ = echo_off();
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
    if (t0_ < 0) t0_ = drawn_t_ = t;
    // the integrator's last step may end past the target (the samples and callbacks up to the
    // target are read from its dense output): the line shows the run's progress, at most all of it
    t_ = std::min(t, target), target_ = target, wall_ = wall, steps_ = w.steps - steps_before_;
    if (!due(wall)) return;
    // the times drawn, for the estimate's recent rate: the last two thirds of the run's wall time,
    // and the one before them
    seen_.emplace_back(wall, t_);
    while (seen_.size() > 2 && seen_[1].first <= wall / 3) seen_.pop_front();
    // the mean step since the last drawing: a run held to tiny steps (rkf45 in the friction band,
    // a stiff transient) shows why its estimate is hours (a user's trial: "about 5 h 44 min left",
    // the steps 7 ns, nothing on the line said so)
    h_recent_ = steps_ > drawn_steps_ ? (t_ - drawn_t_) / static_cast<double>(steps_ - drawn_steps_) : NAN;
    drawn_t_ = t_, drawn_steps_ = steps_;
    draw(false);
  };
}

std::function<void(const BuildWatch&)> ProgressLine::build_callback() {
  if (!enabled_) return {};
  build_ = true;
  start_ = std::chrono::steady_clock::now();
  return [this](const BuildWatch& w) {
    elements_ = w.elements, newton_ = w.newton, stage_ = w.stage, residual_ = w.residual;
    wall_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (due(wall_)) draw(false);
  };
}

void ProgressLine::built() {
  if (!build_) return;
  built_ = true;
  wall_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

}  // namespace beltsim::script
