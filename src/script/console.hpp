// `beltsim console [SCRIPT] [-- ARGS]`: an interactive Lua prompt on the beltsim API, after
// Lua's own lua.c (an expression prints its value, `<eof>` in a syntax error means "read on",
// errors get a traceback and the session goes on) with readline's line editing, persistent
// history ($BELTSIM_HISTORY, default ~/.beltsim_history) and completion of globals, fields and
// methods. Pictures made by sim:show and sim:plot appear in the terminal (term/term_image.hpp).
//
// Ctrl-C at the prompt clears the line; during sim:run_to/advance it stops at the last finished
// step (outputs written) and the prompt returns; in other Lua code it raises "interrupted!".
// Ctrl-D closes every simulation's outputs and exits 0; SIGTERM does the same after stopping the
// run or Lua code under way, and exits 143. With standard input not a terminal the
// commands are read and run with no prompt or escape codes, and the exit status is 1 if any
// failed. The commands that ran without error are written to <out>/session.lua, a script that
// `beltsim run` replays (the scenario's text is copied into it, so the replay runs in the sandbox).
// Each command has its own instruction budget (Safety::max_instructions).
#pragma once

#include <atomic>
#include <optional>
#include <string>
#include <vector>

#include "script/interpreter.hpp"

namespace beltsim::script {

// returns the exit status: 0, or 1 when a command (or the script) failed in a non-interactive
// session, or 143 after SIGTERM
int run_console(const std::optional<std::string>& script, const std::vector<std::string>& args, const Overrides& o,
                const Safety& safety, std::atomic<bool>* stop);

// the value at idx as readable Lua (tables one entry a line, long lists shortened, a number under
// a key with a known unit followed by "-- unit"); for the console and its tests
std::string pretty(lua_State* L, int idx);

}  // namespace beltsim::script
