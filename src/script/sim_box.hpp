// The live simulation's userdata as the files of its methods share it (lua_sim.cpp: running,
// changes, callbacks; lua_sim_read.cpp: reading; lua_sim_files.cpp: pictures and checkpoints): the box, the check
// each method opens with, and the guard that turns C++ exceptions into Lua errors.
#pragma once

#include <cctype>
#include <initializer_list>
#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>

#include "integrate/integrator.hpp"
#include "live/live_server.hpp"
#include "script/context.hpp"
#include "script/docall.hpp"
#include "script/lua_check.hpp"
#include "script/lua_clock.hpp"
#include "sim/simulation.hpp"

namespace beltsim::script {

inline constexpr const char* kSimMeta = "beltsim.Simulation";

struct SimBox {
  std::unique_ptr<Simulation> sim;
  Context* ctx = nullptr;
  bool progress = true;
  lua_State* L = nullptr;  // the state whose running method has the simulation at index 1
  std::map<int, std::unique_ptr<LuaRef>> refs;  // callbacks by id (a when has two: -id for its condition)
  long shows = 0;
  // the paths of the pictures sim:show and sim:plot have written: a default name among them
  // (a second show_<t>.png at the same time) gives way to the next free one (show_<t>_2.png).
  // A Lua userdata is never destroyed: l_gc empties every member that holds memory
  std::set<std::string> pictures;
  bool running = false;  // inside run_to: its callbacks may run Lua code that calls this simulation
  // what sim:close() says of the simulation's runs here (script/progress.hpp, say_run_end): its
  // steps and integration wall time when it was handed to the script (from its checkpoint when
  // resumed), the target of its last run_to and whether that run was stopped short of it
  long steps_before = 0;
  double wall_before = 0;
  double t_start = 0;  // [s] its time when handed to the script: the progress line's percentages count from it
  double last_target = 0;
  bool last_stopped = false;
  std::shared_ptr<live::LiveServer> serve;  // sim:serve{}: stops when the simulation closes
};

inline SimBox* check_box(lua_State* L, const char* method) {
  auto* box = static_cast<SimBox*>(luaL_testudata(L, 1, kSimMeta));
  if (!box) fail(L, std::string("sim:") + method + ": call it as sim:" + method + "(...) on a simulation");
  if (!box->sim) fail(L, std::string("sim:") + method + ": this simulation has been finalised");
  box->L = L;
  return box;
}

// the simulation of a method call, its arguments checked (check_args)
inline Simulation& live(lua_State* L, const char* method, std::initializer_list<Arg> args) {
  SimBox* box = check_box(L, method);
  check_args(L, std::string("sim:") + method, args, 2);
  return *box->sim;
}

// "what: message", the call named once where the C++ message begins with the same name
// ("sim:run_to" and "run_to: -1 s is before now (0 s)" -> "sim:run_to: -1 s is before now (0 s)")
// (a message that begins with the whole name, "sim:when's condition ...", is left as it is)
inline std::string call_error(const char* what, const std::string& message) {
  const std::string w(what);
  if (message.compare(0, w.size(), w) == 0 && message.size() > w.size() &&
      !(std::isalnum(static_cast<unsigned char>(message[w.size()])) || message[w.size()] == '_'))
    return message;
  const std::string name = w.substr(w.rfind(':') == std::string::npos ? 0 : w.rfind(':') + 1);
  if (message.compare(0, name.size() + 2, name + ": ") == 0) return w + message.substr(name.size());
  return w + ": " + message;
}

// A callback's Lua code failed (sim:every's function, sim:when's condition or action, lua_sim.cpp):
// the message names the callback, its place and the simulated time before the error's own
// file:line, as a Lua law's error does (lua_law.cpp); the traceback is the error's, where it was
// raised in the callback. The simulation may go on (Simulation::run_to).
struct CallbackError : std::runtime_error {
  CallbackError(const std::string& message, std::string tb) : std::runtime_error(message), traceback(std::move(tb)) {}
  std::string traceback;
};

// a C++ call whose exceptions become Lua errors once the catch block is left
// (a divergence is noted in ctx, when given, for a sweep point's status: lua_sweep.hpp)
template <class F>
void guarded(lua_State* L, const char* what, F&& f, Context* ctx = nullptr) {
  std::string error;
  try {
    const HostWork work;  // beltsim's own work, not Lua code (lua_clock.hpp)
    f();
  } catch (const CallbackError& e) {  // raised again here, with the traceback of where it was raised
    error = call_error(what, e.what());
    if (!e.traceback.empty()) keep_traceback(L, error, e.traceback);
  } catch (const DivergenceError& e) {
    error = call_error(what, e.what());
    if (ctx) ctx->divergence = {e.t, e.what()};
  } catch (const std::exception& e) {
    error = call_error(what, e.what());
  }
  if (!error.empty()) fail(L, error);
}

// the number of the pulley named by the string at idx; an error naming `what`, with a suggestion,
// when there is none (lua_sim.cpp)
int pulley_index(lua_State* L, const Simulation& s, int idx, const char* what);

// lua_sim_changes.cpp: sim:set_torque, sim:set_speed, sim:set_arm, sim:set_rotor, sim:spray, sim:wet,
// sim:set_mu, sim:log
int l_set_torque(lua_State* L);
int l_set_speed(lua_State* L);
int l_set_arm(lua_State* L);
int l_set_rotor(lua_State* L);
int l_spray(lua_State* L);
int l_wet(lua_State* L);
int l_set_mu(lua_State* L);
int l_log(lua_State* L);

// lua_sim_read.cpp: sim:pulley, sim:element, sim:elements, sim:span, sim:energy, sim:stats
int l_pulley(lua_State* L);
int l_element(lua_State* L);
int l_elements(lua_State* L);
int l_span(lua_State* L);
int l_energy(lua_State* L);
int l_stats(lua_State* L);

// lua_sim_files.cpp: sim:show, sim:plot, sim:save, and beltsim.resume and beltsim.replay_of (upvalue 1:
// the Context)
int l_show(lua_State* L);
int l_plot(lua_State* L);
// lua_modes.cpp: sim:modes
int l_modes(lua_State* L);
int l_save(lua_State* L);
int l_resume(lua_State* L);
int l_replay_of(lua_State* L);

}  // namespace beltsim::script
