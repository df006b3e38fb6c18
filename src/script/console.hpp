// `beltsim console [SCRIPT] [-- ARGS]`: an interactive Lua prompt on the beltsim API, after
// Lua's own lua.c (an expression prints its value, `<eof>` in a syntax error means "read on",
// errors get a traceback and the session goes on) with readline's line editing, persistent
// history and completion of globals, fields and methods (console_input.hpp, console_complete.hpp).
// Values are shown as readable Lua (console_print.hpp). Pictures made by sim:show and sim:plot
// appear in the terminal (term/term_image.hpp).
//
// Ctrl-C at the prompt clears the line; during sim:run_to/advance it stops at the last finished
// step (outputs written) and the prompt returns; in other Lua code it raises "interrupted!"; a
// second Ctrl-C in the same command ends the process (signals.hpp). Ctrl-D closes every
// simulation's outputs and exits 0; SIGTERM and SIGHUP do the same after stopping the run or Lua
// code under way, and exit 143 and 129. With standard input not a terminal the commands are read
// and run with no prompt or escape codes, and the exit status is 1 if any failed. The commands
// that ran without error are written to <out>/session.lua, a script that `beltsim run` replays
// (console_session.hpp). Each command has its own instruction budget (Safety::max_instructions).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "script/interpreter.hpp"
#include "term/term_image.hpp"

namespace beltsim::script {

// what the console takes from the program's environment (src/app reads it)
struct ConsoleSettings {
  std::string history = ".beltsim_history";             // the history file
  term::ImageMode images = term::ImageMode::automatic;  // how pictures are shown
  // the command line's options that change a run (--rtol 1e-3, --no-frames, ...), as typed: the
  // replay line of session.lua repeats them, so that the replay gives the same results
  std::vector<std::string> replay_options;
};

// returns the exit status: 0, or 1 when a command (or the script) failed in a non-interactive
// session or session.lua could not be written, or 128 + the signal after SIGTERM or SIGHUP.
// The stop signals must be installed (install_stop_signals).
int run_console(const std::optional<std::string>& script, const std::vector<std::string>& args, const Overrides& o,
                const Safety& safety, const ConsoleSettings& settings);

}  // namespace beltsim::script
