// The progress line on stderr and every other line written while it may be on screen.
//
// One progress line for integrations that take more than a second: simulated time reached of the
// target, wall time, an estimate of what is left, the steps of this integration (as the call
// returns them: a simulation's steps before it, steps_before, are not counted); the same line for
// a scene build that takes more than a second (a belt of thousands of elements): its stage, wall
// time and Newton iterations (build_callback). Redrawn in place
// on a terminal (every 0.5 s), a line every 10 s otherwise (no carriage returns in a pipe or a
// log). When the integration ends, the line shows where it ended (t_end and 100 % when it got
// there, where it stopped when it did not) with its total wall time, and is closed.
//
// On a terminal the line is written without its end while the run goes on: this file is the one
// place that knows whether such a line is open. Whatever else is written while it may be (a warning
// from the run, a note, an error, a script's print or io.write when stdout is the same terminal, its
// io.stderr:write) goes through say() or end_progress_line() first, so that it starts on a line of
// its own; the progress line is drawn again below it at its next update. Not part of the engine: the engine reports
// progress through a callback (sim/simulation.hpp RunProgress) and this prints it.
//
// While the line is drawn on a terminal, the terminal on stdin does not echo what is typed (the
// keys typed would land on the line: "... 57997 stepsbcllo there"). What is typed is kept by the
// terminal for whoever reads it next (the console's next prompt, or the shell after `beltsim
// run`), as a shell keeps it; a Ctrl-C, which the terminal answers by discarding its input, drops
// it. The echo is restored when the line ends (the run's end, an error or Ctrl-C unwinding through
// it) and, by restore_echo(), on the ways the process ends without unwinding.
#pragma once

#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <functional>
#include <string>
#include <utility>

#include "scene/scene_types.hpp"
#include "sim/simulation.hpp"

namespace beltsim::script {

// a progress line's parts (fit_progress_text, below)
struct ProgressParts {
  std::string head, elapsed, left, steps;
};

class ProgressLine {
 public:
  // origin: [s] where the simulation started (0, or the checkpoint's time of a resumed one), from
  // which the line's percentage counts: "t = 0.18 s of 0.4 s (46 %)" whether this call started at 0
  // or at 0.15 (a live simulation's second run_to); NaN: where this call started
  explicit ProgressLine(bool enabled, long steps_before = 0, double origin = NAN);
  ~ProgressLine();  // shows the end (finish, else the last state reported) and closes the line, if one was drawn
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;
  RunProgress callback();
  // where the integration ended, as the call returns it: t, its steps (all of them, as
  // RunProgress counts them), its wall time; shown by the last drawing of the line
  void finish(double t, long steps, double wall);
  // a scene build's instead (scene_types.hpp BuildWatch::progress), timed from this call: "beltsim:
  // building the scene (19000 elements): static state, 12 s elapsed, Newton iteration 14: 320 m/s²
  // from equilibrium"; built() when the build has made its scene, which the last drawing says
  // ("beltsim: scene built (19000 elements), 21 s elapsed, 38 Newton iterations")
  std::function<void(const BuildWatch&)> build_callback();
  void built();

 private:
  // the line is due to be drawn after `wall` seconds (from a second on, every 0.5 s on a
  // terminal, every 10 s in a log); when it is, it will be
  bool due(double wall);
  ProgressParts run_parts(bool last) const;
  ProgressParts build_parts(bool last) const;
  void draw(bool last);
  bool enabled_, tty_, drawn_ = false;
  bool echo_off_ = false;  // this line turned the terminal's echo off (restored with the line's end)
  double last_ = 0, t0_ = -1, origin_;
  long steps_before_ = 0;
  // the last state reported (or finish's): what the line shows
  double t_ = 0, target_ = 0, wall_ = 0;
  long steps_ = 0;
  // the time and steps at the last drawing, and the mean step from there to the drawing after it
  double drawn_t_ = 0, h_recent_ = NAN;
  long drawn_steps_ = 0;
  size_t width_ = 0;  // of the text drawn last on the terminal, blanked by a shorter one
  std::deque<std::pair<double, double>> seen_;  // (wall, t) of the line's drawings
  // a build's (build_callback): the last state it told, and whether it made its scene
  bool build_ = false, built_ = false;
  std::chrono::steady_clock::time_point start_;
  int elements_ = 0, newton_ = 0;
  std::string stage_;
  double residual_ = -1;
};

// The progress line's parts, and the line a terminal of `columns` columns shows (0: any length):
// the head always, then as many of the estimate, the elapsed time and the steps as fit, in that
// order of precedence, each in its place ("beltsim: t = 1.2 s of 30 s (4 %), 10 s elapsed, about
// 4 min 10 s left, 12000 steps")
std::string fit_progress_text(const ProgressParts& parts, int columns);
// the line's head, "beltsim: t = 0.1834 s of 0.4 s (46 %)": the percentage of the span from
// `origin` (the simulation's start) to `target` that t has covered (a user read "(13 %)", the share of
// the last run_to from 0.15 s, beside "of 0.4 s")
std::string progress_head(double t, double target, double origin);
// [s] the progress line's estimate of the wall time left (NaN: no basis yet) of a run from t0 to
// target now at t after `wall` seconds, from the (wall, t) pairs seen so far: at the rate of the
// last third of the wall time (from the last pair at or before two thirds of it), else of all of it
double wall_left(const std::deque<std::pair<double, double>>& seen, double t0, double t, double target, double wall);

// ends the progress line open on the terminal, if one is: what is written next starts on a line of its own
void end_progress_line();
// how many open progress lines have been ended so far (by a message or by their run's end): the
// console reads it round a command to know whether the line the terminal echoed ^C on was ended
long progress_lines_ended();
// the terminal's echo as it was before a progress line turned it off, if one did: for the ways the
// process ends without unwinding (a second stop signal, the watchdog, a time limit's end; they call it
// before their _exit or signal). Async-signal-safe. Only the echo is changed back, and only from the
// terminal's foreground (from the background it would stop the process with SIGTTOU; the shell
// that holds the terminal then has set it as it wants it)
void restore_echo();
// a message on stderr (printf's format, its own line end included), on a line of its own
[[gnu::format(printf, 1, 2)]] void say(const char* format, ...);
// a print to stdout (Lua's print, a picture's path): the progress line is ended first when stdout
// is the terminal stderr is
void before_stdout();
// a script's write to the file f (io.write, file:write): to stdout as before_stdout(); to stderr,
// the progress line's own, the line is ended first; to any other file nothing
void before_write(std::FILE* f);

// How a run ended, as it says so: a scene:run{} as it returns (lua_scene_run.cpp), a live
// simulation as sim:close() closes it (lua_sim.cpp)
struct RunEnd {
  std::string warning_summary;  // Simulation::warning_summary
  std::string check_line;       // Simulation::check_line
  bool check_warns = false;     // the check's estimate is past the contract's bounds
  std::string unapplied;        // Simulation::unapplied_warnings
  bool closing_line = true;     // the line below is said (progress on, and it ran)
  double t = 0, t_end = 0;      // [s] where it ended, and the time it was to reach
  bool stopped = false;         // stopped short of t_end (Ctrl-C, SIGTERM, the live view, max_wall)
  long steps = 0;
  double wall = 0;  // [s]
  std::string out_dir;
};
// says, each on stderr on a line of its own, the run's fallbacks, its check, the start's warnings
// that did not apply (each when there is one) and last its closing line: "beltsim: run ended at t =
// 0.1 s (1234 steps, 0.8 s): out/my/", "beltsim: run stopped at t = 0.4 s of 1 s (...)" for a run
// stopped short
void say_run_end(const RunEnd& end);

}  // namespace beltsim::script
