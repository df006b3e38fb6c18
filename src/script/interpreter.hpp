// The embedded Lua 5.4 interpreter that runs scenario scripts (the engine never sees lua.h).
// Scripts get a global table `beltsim` (see lua_api.cpp and docs/lua-api.md for the API).
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "script/load_source.hpp"
#include "script/overrides.hpp"

struct lua_State;

namespace beltsim::script {

struct Context;  // script/context.hpp
struct Limits;   // script/limits.hpp

// What a script may reach and take (docs/limits-and-safety.md). The defaults are the sandbox
// and limits that no sensible scenario meets.
struct Safety {
  // every standard Lua library (os.execute, io anywhere, debug, C modules); the main file is
  // still loaded as text only
  bool trusted = false;
  // Lua instructions per call from the host (a script run, a console command, with the every/when
  // callbacks it runs); 0: no limit
  std::uint64_t max_instructions = 10'000'000'000;
  // bytes of Lua heap; 0: no limit
  std::size_t max_lua_memory = std::size_t(4) << 30;
  // [s] wall time and CPU time of each call into Lua (a script run, a console command, a sweep
  // point, a callback, a law), beltsim's own work in it not counted; 0: no limit
  double max_lua_wall = 600;
  double max_lua_cpu = 120;
};

// A script error, already in "file:line: message" form, with Lua's traceback of where it was
// raised ("" when there is none to give).
struct ScriptError : std::runtime_error {
  explicit ScriptError(const std::string& message, std::string traceback_ = "")
      : std::runtime_error(message), traceback(std::move(traceback_)) {}
  std::string traceback;
};

// the folder a script's outputs go to unless told otherwise: out/<the script's name without .lua>
// (a run's, a console session's, a sweep's; wp and modes use a folder inside it)
std::string default_out_dir(const std::string& script);

class Interpreter {
 public:
  explicit Interpreter(const Safety& safety = {});
  ~Interpreter();
  Interpreter(const Interpreter&) = delete;
  Interpreter& operator=(const Interpreter&) = delete;

  void set_overrides(const Overrides& o);
  void set_stop_flag(const std::atomic<bool>* stop);
  // starts the live view (live/live_server.hpp) that every run of this interpreter feeds, until
  // it ends; prints its address on stderr and returns it. Throws std::runtime_error when it cannot.
  std::string serve(int port);
  // capture mode: the first scene:run{} stores its scene and settings here and ends the script
  void set_capture(Captured* c);
  // runs a scenario script (loaded as text only); throws ScriptError. With nresults > 0 the first
  // nresults values the script returns are left on the stack (a sweep file's sweep).
  void run_file(const std::string& path, int nresults = 0);
  // true when a run inside the last script was stopped by the stop flag
  bool interrupted() const;
  // the --set keys the last script never read (beltsim.args.KEY), one message each:
  // "--set elemnts=120 was never read by S.lua (did you mean 'elements'?); keys it read: elements, mu"
  std::vector<std::string> unread_args(const std::string& script) const;
  // Ctrl-C for Lua code: raises "interrupted!" at the next slice of instructions (async-signal-safe:
  // one atomic store)
  void interrupt();
  // the script files loaded so far (script/load_source.hpp), in the order loaded
  const std::vector<LoadedFile>& loaded_files() const;
  lua_State* state() { return L_; }
  Context& context();

 private:
  std::unique_ptr<Limits> limits_;  // the allocator's: outlives the state
  std::unique_ptr<Context> ctx_;    // outlives the state too: finalisers may use it
  lua_State* L_;
};

}  // namespace beltsim::script
