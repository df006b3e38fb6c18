// The embedded Lua 5.4 interpreter that runs scenario scripts (the engine never sees lua.h).
// Scripts get a global table `beltsim` (see lua_api.cpp and the README for the API).
#pragma once

#include <atomic>
#include <optional>
#include <stdexcept>
#include <string>

#include "sim/simulation.hpp"

struct lua_State;

namespace beltsim::script {

struct Context;  // script/context.hpp

// Command-line values that override what a script asks of scene:run{}.
struct Overrides {
  std::optional<std::string> out;
  std::optional<double> t_end;
  std::optional<std::string> integrator;
  std::optional<double> rtol;
  bool no_frames = false;  // ignore the scripts' frames = {...} (no rendering, no video)
};

// What a script asked of its first scene:run{} (for `beltsim wp`, which runs the scene itself).
struct Captured {
  std::optional<Scene> scene;
  RunSettings settings;
};

// A script error, already in "file:line: message" form.
struct ScriptError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class Interpreter {
 public:
  Interpreter();
  ~Interpreter();
  Interpreter(const Interpreter&) = delete;
  Interpreter& operator=(const Interpreter&) = delete;

  void set_overrides(const Overrides& o);
  void set_stop_flag(const std::atomic<bool>* stop);
  // capture mode: the first scene:run{} stores its scene and settings here and ends the script
  void set_capture(Captured* c);
  // runs a scenario script (loaded as text only); throws ScriptError
  void run_file(const std::string& path);
  // true when a run inside the last script was stopped by the stop flag
  bool interrupted() const;
  lua_State* state() { return L_; }
  Context& context();

 private:
  lua_State* L_;
};

}  // namespace beltsim::script
