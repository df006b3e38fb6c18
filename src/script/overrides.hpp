// What the command line gives an interpreter over its scripts' own requests (Overrides), and what
// capture mode takes from a script's first scene:run{} (Captured): the interpreter (interpreter.hpp)
// and the bindings (context.hpp) read both.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene.hpp"
#include "script/script_args.hpp"
#include "sim/run_settings.hpp"

namespace beltsim::script {

// Command-line values that override what a script asks of scene:run{}.
struct Overrides {
  // the run settings given on the command line (the table's options, sim/run_table.hpp: --out,
  // --t-end, --integrator, --rtol, --max-wall, --check), each over every run's own: their keys in
  // `given`, their values in `run`
  std::vector<std::string> given;
  RunSettings run;
  bool has(std::string_view key) const {
    for (const std::string& k : given)
      if (k == key) return true;
    return false;
  }
  void give(std::string_view key) {
    if (!has(key)) given.emplace_back(key);
  }
  // the run settings the command's own options override (run, console: all the table's; wp: out,
  // t_end): a --set of one of them the script never reads is named as the option it may have meant
  std::vector<std::string> option_keys;
  bool no_frames = false;      // ignore the scripts' frames = {...} (no rendering, no video)
  std::vector<ScriptArg> set;  // --set KEY=VALUE: beltsim.args (not an override of run{})
  std::optional<int> serve;    // --serve [PORT]: the live view on 127.0.0.1 (0: a free port)
};

// What a script asked of its first scene:run{} (for `beltsim wp`, which runs the scene itself).
struct Captured {
  std::optional<Scene> scene;
  RunSettings settings;
  // with definition_only (set by the caller), the script ends at its first beltsim.scene{} instead,
  // nothing built: `definition` is what it read (what the tests build the scripts' scenes from),
  // left empty when its belt.mu is a Lua function, which cannot be called once the interpreter is gone
  bool definition_only = false;
  std::optional<SceneDef> definition;
  // with until_run (set by the caller), the script ends at its first scene:run{}, scene:start{} or
  // beltsim.resume instead, before anything is integrated or written: `run_at` is "FILE:LINE:
  // scene:run", left empty when it called none (what `beltsim sweep` learns of a file before it
  // runs its points); with quiet too, scenes are built without their report on stderr
  bool until_run = false;
  bool quiet = false;
  std::string run_at;
  // without until_run: the command capturing ("wp", "modes"), named where a script starts a live
  // simulation (scene:start, beltsim.resume), which it refuses at once (refuse_if_capturing)
  std::string command = "wp";
};

}  // namespace beltsim::script
