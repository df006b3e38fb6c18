// Settings an interpreter passes to the bindings (private to src/script).
#pragma once

#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "script/load_source.hpp"
#include "script/overrides.hpp"

struct lua_State;

namespace beltsim {
class Simulation;
}
namespace beltsim::live {
class LiveServer;
}

namespace beltsim::script {

// a change the live view's page made (script/live_feed.hpp), as the console's session.lua replays
// it: on the simulation with this userdata (null: a scene:run{}'s, which no statement names) at t,
// the method call after "NAME:" (set_torque("driven", -65)); "" for where the run stood at its end
struct PageChange {
  const void* sim = nullptr;
  double t = 0;
  std::string call;
};

// The state a Lua law calls into. The interpreter empties it once the state is closed: a law may
// outlive its interpreter in a captured scene (beltsim wp), and must then neither call nor unref.
struct LawHost {
  lua_State* L = nullptr;  // the main thread
};

// the registry field holding the result table of the last scene:run{} (a sweep point of the quick form)
inline constexpr const char* kLastRun = "beltsim.last_run";

struct Context {
  Overrides overrides;
  std::string default_out = "out";  // out/<script name> while a script runs
  // the output folders of the runs started so far in this command (absolute, normalised): a run
  // into one of them replaces an earlier run's outputs, and says so (read_run_settings)
  std::set<std::string> run_dirs;
  std::string script_dir;           // the running script's folder ("" in a console without one)
  std::string script;               // the running script's path ("" in a console without one)
  bool trusted = false;             // full libraries (Safety::trusted)
  const std::atomic<bool>* stop = nullptr;
  bool interrupted = false;
  Captured* capture = nullptr;  // capture mode (see Interpreter::set_capture)
  bool captured = false;        // the script was ended by a capture
  // a picture made by sim:show or sim:plot: the console shows it in the terminal; a script run
  // prints its path (empty: print the path)
  std::function<void(const std::string& png)> on_picture;
  // a console session: commands typed later may read --set keys, so a key unread at the first
  // run is a warning there, not the error it is in a script run (check_unread_args)
  bool interactive = false;
  // runs stopped by Ctrl-C: the simulation's userdata (null for a scene:run) and where it stopped
  // (the console writes sim:run_to(t), or beltsim.stop_at(t) before a scene:run, into session.lua,
  // so that the replay stops there too)
  std::vector<std::pair<const void*, double>> stopped_runs;
  // beltsim.stop_at(t): the next run that would pass t stops there as Ctrl-C stops a run (run_feed),
  // and stop_made is set: later runs are refused as after Ctrl-C, until beltsim.stop_at()
  std::optional<double> stop_at;
  bool stop_made = false;
  // the page's changes during the command running now, with the ends of that command's runs
  // while a page could change them (the console writes them into session.lua instead of the
  // command, as for Ctrl-C)
  std::vector<PageChange> page_changes;
  // the keys of beltsim.args the running script has read (given with --set or not), in order
  std::vector<std::string> args_read;
  // the last run that diverged: its time and message (a sweep point's status, lua_sweep.hpp)
  std::optional<std::pair<double, std::string>> divergence;
  // the script files loaded so far (the scenario, dofile, loadfile, require), for a sweep point's
  // record of what defines it
  std::vector<LoadedFile> loaded;
  bool args_warned = false;   // the unread --set keys were reported at a run's start
  bool t_end_warned = false;  // --t-end was said not to shorten scene:start's simulations
  bool resume_warned = false;  // the run options were said not to apply to beltsim.resume
  // the checkpoints sim:save wrote, by the path it was given (the last one for each): a relative
  // path is taken inside the simulation's output folder, where beltsim.resume, reading from the
  // folder beltsim runs in, does not find it by the same path (its refusal names the one written)
  std::map<std::string, std::string> saved;
  // beltsim.resume was called (even when it failed): the console's session.lua then names the
  // session's folder (beltsim.replay_of), so that its replay resumes its own checkpoints
  bool resumed = false;
  // beltsim.replay_of(dir): this script replays the console session whose folder is dir. A
  // beltsim.resume of a checkpoint in that folder reads the replay's own copy (the same path in the
  // replay's output folder, where its sim:save wrote it), and a resume whose run would write into
  // that folder is refused: a replay leaves the record it is checked against as it is
  std::optional<std::string> replay_of;
  // the live view of --serve (Interpreter::serve): every run of the session feeds it
  std::shared_ptr<live::LiveServer> serve;
  // the live simulation that page showed last (sim:run_to), and its userdata: the page's changes
  // made while the console waits at its prompt go to it (null once it is finalised or a
  // scene:run{} has run since)
  Simulation* page_sim = nullptr;
  const void* page_key = nullptr;
  // a run has fed that page (sim:run_to, scene:run{}): until then it shows the simulation started last
  bool page_ran = false;
  // the simulations served by sim:serve{} (each its own page), by their userdata: the console
  // applies their pages' changes at its prompt as it does --serve's
  std::map<const void*, std::pair<live::LiveServer*, Simulation*>> served;
  // the state Lua laws call into (emptied when the interpreter closes it)
  std::shared_ptr<LawHost> law_host = std::make_shared<LawHost>();
};

}  // namespace beltsim::script
