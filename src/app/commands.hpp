// The commands that run scripts or read results: each takes its options as read by options.hpp and
// returns the exit status (0, 1 on an error whose message it printed, 130/143/129 after a signal);
// a UsageError (exit 2) escapes to main. `render` and `compare` are in render_cmd.hpp and compare.hpp.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "app/environment.hpp"
#include "app/options.hpp"

namespace beltsim::app {

int cmd_run(const std::string& script, const script::Overrides& o, const script::Safety& s);
// runs script in lua up to its first scene:run{}, which it captures (the script stops there):
// --set reaches the script, and --t-end too when t_end_to_script; a key the script reads after that
// point cannot be known and is a warning of `command` ("wp"). Throws when the script never calls
// scene:run{}. lua stays the caller's: a scene's Lua laws live in it.
script::Captured capture_first_run(script::Interpreter& lua, const std::string& script, const script::Overrides& o,
                                   const char* command, bool t_end_to_script);
int cmd_wp(const std::string& script, const script::Overrides& o, const script::Safety& s, WpSettings wps);
// replay_options: the options of the command line its session's replay repeats (run_option_words)
int cmd_console(const std::optional<std::string>& script, const std::vector<std::string>& args,
                const script::Overrides& o, const script::Safety& s, const Environment& env,
                const std::vector<std::string>& replay_options);
// A run's outputs given either way, as `summary` and `plot` take them: its folder (DIR or
// DIR/timeseries.csv given; "." for a bare timeseries.csv), and the CSV to draw (DIR/timeseries.csv
// for a folder, DIR/summary.csv for a sweep's folder; a file as given)
std::string run_folder(const std::string& given);
std::string run_csv(const std::string& given);
// `beltsim plot CSV|DIR [COLUMNS...] [--from T] [--to T] [--by PARAM]`
int cmd_plot(const std::string& csv, const std::vector<std::string>& columns, const Raw& raw,
             term::ImageMode images);
// `beltsim summary DIR [--from T0] [--to T1] [--csv FILE] [--plot PNG]` (plot/summary.hpp)
int cmd_summary(const std::string& dir, const Raw& raw);
// `beltsim modes SCRIPT [--at T] [--campbell PULLEY --rpm A:B:N]` (sim/modes.hpp, docs/modes.md)
int cmd_modes(const std::string& script, const script::Overrides& o, const script::Safety& s, const Raw& raw);
int cmd_sweep(const std::string& file, const Raw& raw, const script::Safety& s);

}  // namespace beltsim::app
