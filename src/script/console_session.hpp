// The console's session.lua: the commands that ran without error, in order, as a script that
// `beltsim run` replays. Each command is written so that it is valid where it stands and does
// what it did at the prompt: a call is the statement it is; an expression that is not a call and
// a chunk's returned values, which the prompt printed, are printed as the prompt showed them, by
// beltsim.print, after a comment with the command as it was typed (`-- > r`, then
// `beltsim.print(r)`; `print(r)` prints a table's address); a chunk with locals keeps them to
// itself (`do ... end`), one that returns runs as a function; a run that Ctrl-C stopped becomes
// run_to(where it stopped), a scene:run (at the prompt or in the scenario) goes between
// beltsim.stop_at(where it stopped) and beltsim.stop_at(); Lua code it interrupted is kept as a
// comment. The scenario's text is copied in, so the replay needs no access to the scenario's
// folder (which the sandbox would refuse). The file is written again after each command.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "script/context.hpp"
#include "script/script_args.hpp"

struct lua_State;

namespace beltsim::script {

// runs stopped by Ctrl-C in one command: the simulation's userdata and the time it stopped at
using StoppedRuns = std::vector<std::pair<const void*, double>>;

// the command `chunk` (compiled as an expression when `expression`; `printed`: the prompt printed
// the values it gave) as session.lua replays it; the globals of L name the simulations in
// `stopped` and `page` (the live view's changes while the command ran, context.hpp). A stopped or
// changed run is replayed as its parts; an assignment of its result (r = sim:run_to(1)) is kept on
// the last part
std::string replayable(lua_State* L, const std::string& chunk, bool expression, bool printed,
                       const StoppedRuns& stopped, const std::vector<PageChange>& page);

// the live view's changes applied while the console waited at its prompt, as statements ("" for none)
std::string at_prompt(lua_State* L, const std::vector<PageChange>& page);
// a command that raised an error after it may have changed something (a run stopped by an error in
// its callback at t = 0.03 s stays there): replayed as it ran, inside pcall, so that the replay
// takes the same way and goes on; with its error as a comment. Stopped or page-changed runs are
// replayed as replayable() says.
std::string failed_replayable(lua_State* L, const std::string& chunk, bool expression, const std::string& error,
                              const StoppedRuns& stopped, const std::vector<PageChange>& page);

// what session.lua records besides the commands: the scenario (its path, its text when the session
// began and its arguments after --), the --set values and the command line's other options that
// change a run (ConsoleSettings::replay_options), all of which its replay line repeats
struct SessionStart {
  std::string dir;  // the console's output folder, where session.lua goes
  std::optional<std::string> script;
  std::string script_text;
  std::vector<std::string> args;
  std::vector<ScriptArg> sets;
  std::vector<std::string> options;
  // the scenario's run a stop signal stopped (where, and "Ctrl-C"), replayed to there (beltsim.stop_at),
  // and the scenario's error, which its replay goes on after
  std::optional<double> scenario_stop;
  std::string scenario_stopped_by;
  std::string scenario_error;
};

// <dir>/session.lua, or session_2.lua, ... when an earlier session's is there (the name chosen at
// its first write): written whole again after each command (a kill of the console loses only the
// command under way), nothing while no command has run
class SessionFile {
 public:
  explicit SessionFile(SessionStart start) : start_(std::move(start)) {}
  // writes the commands so far; false when it cannot be written, the reason said on stderr (once
  // while it stays the same). runs_in_dir: every run of the session wrote into dir (none named a
  // folder of its own), and its replay line gives --out <dir>/replay, so that the replay writes
  // beside the session rather than into out/session, where every session's replay went.
  // resumed: the session called beltsim.resume, and session.lua names the session's folder
  // (beltsim.replay_of), so that its replay continues the checkpoints its own sim:save wrote and
  // never writes into the session's folder
  bool write(const std::vector<std::string>& commands, bool runs_in_dir, bool resumed);
  // the path written ("" before the first write)
  std::string path() const;

 private:
  SessionStart start_;
  std::string name_;    // session.lua, session_2.lua, ...
  std::string failed_;  // the reason the last write failed, said once
};

}  // namespace beltsim::script
