// The command line's options as typed (text) and their reading into the settings the commands
// take: every number through script::decimal (a finite decimal: no hex, inf or nan), every
// problem a UsageError (exit status 2 with the pointer to the command's --help).
#pragma once

#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "script/interpreter.hpp"
#include "sim/work_precision.hpp"

namespace beltsim::app {

// bad usage: the message goes to stderr and the exit status is 2
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// the options as typed: text, turned into numbers and checked by the readers below and the
// commands, so every number goes through decimal()
struct Raw {
  // run, console, wp: the run settings' options (sim/run_table.hpp), by the setting's key ("t_end"):
  // a number's or text's as typed, a flag's "1"
  std::map<std::string, std::optional<std::string>> run;
  std::map<std::string, bool> run_flags;
  bool no_frames = false;
  std::optional<std::string> out;                                               // plot, sweep
  std::optional<std::string> serve;  // run, console: --serve [PORT]
  std::optional<std::string> integrators, rtols, ref_integrator, ref_rtol, wall_limit, metric;  // wp
  std::optional<std::string> from;                                      // plot, summary
  std::optional<std::string> by;                                        // plot
  std::optional<std::string> to, csv_out, plot_out;                     // summary
  bool trusted = false;                                                 // run, wp, console, sweep
  std::optional<std::string> max_instructions, max_lua_memory, max_lua_wall, max_lua_cpu;
  std::vector<std::string> set;  // run, console, wp: --set KEY=VALUE; sweep: --set KEY=V1,V2,..
  std::optional<std::string> jobs, point, partition, time, max_parallel;  // sweep
  bool list = false, collect = false, slurm = false, submit = false, rerun = false;
  std::optional<std::string> at, fmin, fmax, shapes, campbell, rpm, orders, settle, check;  // modes
  bool video = false;                                                                 // modes
};

double number(const std::string& option, const std::string& text);
// a picture's path: its name ends in .png (any case), the only kind beltsim draws (x.jpg got PNG bytes)
void require_png(const std::string& option, const std::string& path);
// a whole number in [lo, 1e9]
int whole_number(const std::string& option, const std::string& text, int lo);
// the integrators' names, separated by commas (for the help)
std::string integrator_list();

script::Safety safety(const Raw& raw);
// the safety options given, as typed: words of a command line ("--max-instructions", "1e6", ...)
std::vector<std::string> safety_words(const Raw& raw);
// the options given that change what a run does, as typed: the run settings' bar --out, --no-frames
// and the safety options (what a console's replay line repeats: script/console_session.hpp)
std::vector<std::string> run_option_words(const Raw& raw);
// the run settings' options (--out, --t-end, ...: sim/run_table.hpp), --no-frames and --set of run, console and wp
// the keys of the run settings the command line overrides (sim/run_table.hpp, their option)
std::vector<std::string> run_option_keys();
// option_keys: the run settings the command's options override (Overrides::option_keys); every
// one of the table's by default (run, console)
script::Overrides overrides(const Raw& raw, std::vector<std::string> option_keys = run_option_keys());
// wp's --integrators, --rtols, --ref-rtol and --wall-limit
WpSettings wp_settings(const Raw& raw);

}  // namespace beltsim::app
