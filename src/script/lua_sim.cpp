// Lua bindings of the live simulation (see lua_sim.hpp and docs/lua-api.md, "Live simulation").
// A simulation is a full userdata holding a SimBox (sim_box.hpp); its methods check their arguments
// ("sim:advance: expected 1 argument, got 2") and turn C++ errors into Lua errors after leaving
// the catch block. Callbacks (every, when) are Lua functions kept in the registry; they are
// called with the simulation as their argument, from inside run_to. Here: running,
// callbacks and the metatable; changes in lua_sim_changes.cpp, reading in lua_sim_read.cpp,
// pictures and checkpoints in lua_sim_files.cpp.
#include "script/lua_sim.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>

#include "integrate/stepper.hpp"
#include "io/number_text.hpp"
#include "io/suggest.hpp"
#include "io/units.hpp"
#include "scene/law_text.hpp"
#include "scene/scene.hpp"
#include "script/context.hpp"
#include "script/docall.hpp"
#include "script/limits.hpp"
#include "script/live_feed.hpp"
#include "script/lua_check.hpp"
#include "script/lua_clock.hpp"
#include "script/lua_law.hpp"
#include "script/lua_run.hpp"
#include "script/lua_summary.hpp"
#include "script/progress.hpp"
#include "script/sandbox.hpp"
#include "script/sim_box.hpp"

namespace beltsim::script {

int pulley_index(lua_State* L, const Simulation& s, int idx, const char* what) {
  if (lua_type(L, idx) != LUA_TSTRING) fail(L, std::string(what) + ": a pulley name expected, got " + type_name(L, idx));
  const std::string name = lua_tostring(L, idx);
  const int j = s.scene().find_pulley(name);
  if (j < 0) {
    std::vector<std::string> names;
    for (const Pulley& p : s.model().pulleys) names.push_back(p.name);
    fail(L, std::string(what) + ": " + no_such("pulley", name, names));
  }
  return j;
}

namespace {

// ---- running ---------------------------------------------------------------------------------

int run_to(lua_State* L, SimBox& box, double t, const char* what) {
  end_if_stopped(L, box.ctx, what);
  Simulation::Advance a;
  bool interrupted = false;
  guarded(
      L, what,
      [&] {
        ProgressLine line(box.progress, box.sim->stats().steps, box.t_start);
        box.running = true;
        struct Done {
          SimBox& b;
          ~Done() { b.running = false; }
        } done{box};
        LiveFeed feed(box.serve ? box.serve.get() : box.ctx->serve.get(), box.ctx->stop, &box.ctx->page_changes,
                      lua_topointer(L, 1));
        if (!box.serve && box.ctx->serve)
          box.ctx->page_sim = box.sim.get(), box.ctx->page_key = lua_topointer(L, 1), box.ctx->page_ran = true;
        try {
          a = run_feed(box.ctx, feed, *box.sim, t, line.callback(), "paused");
        } catch (const DivergenceError& e) {  // where its samples are, as scene:run says
          throw DivergenceError(e.t, e.what() + samples_note(box.sim->out_dir()));
        }
        line.finish(a.t, a.steps, a.wall);
        box.last_target = t, box.last_stopped = a.interrupted;
      },
      box.ctx);
  if (a.over_wall_limit) {
    // not silent: an error naming the limit and the time reached (outputs flushed; the
    // simulation can go on with another call)
    fail(L, std::string(what) + ": " +
                wall_limit_text(box.sim->settings().wall_limit, a.t, t, box.sim->out_dir(),
                                box.ctx->overrides.has("max_wall")));
  }
  if (a.interrupted) {
    interrupted = true;
    box.ctx->interrupted = true;
    box.ctx->stopped_runs.push_back({lua_topointer(L, 1), a.t});
    clear_interrupt(L);  // the stop was honoured here; no "interrupted!" after it
  }
  lua_createtable(L, 0, 4);
  set_number(L, "t", a.t);
  lua_pushinteger(L, a.steps), lua_setfield(L, -2, "steps");
  set_number(L, "wall", a.wall);
  lua_pushboolean(L, interrupted), lua_setfield(L, -2, "interrupted");
  for (const char* f : {"t", "steps", "wall"}) set_unit(L, -1, f, run_result_unit(f).value_or(""));
  return 1;
}

// sim:run_to(t) -> { t [s], steps, wall [s], interrupted }
int l_run_to(lua_State* L) {
  live(L, "run_to", {{"t", kNumber}});
  SimBox& box = *static_cast<SimBox*>(lua_touserdata(L, 1));
  return run_to(L, box, to_number(L, 2, "sim:run_to(t)"), "sim:run_to");
}

// sim:advance(dt) -> same as run_to(sim.t + dt)
int l_advance(lua_State* L) {
  Simulation& s = live(L, "advance", {{"dt", kNumber}});
  const double dt = to_number(L, 2, "sim:advance(dt)");
  if (!(dt >= 0 && std::isfinite(dt))) {
    std::ostringstream m;
    m << "sim:advance: dt must be >= 0 s and finite (got " << dt << " s)";
    fail(L, m.str());
  }
  return run_to(L, *static_cast<SimBox*>(lua_touserdata(L, 1)), s.now() + dt, "sim:advance");
}

// ---- callbacks -------------------------------------------------------------------------------

// a callback: its role for messages ("sim:every's function") and its function's place ("cb.lua:9")
struct Callback {
  std::string what, where;
  Callback(lua_State* L, int idx, std::string role) : what(std::move(role)), where(function_place(L, idx)) {}
  // "sim:every's function (function at cb.lua:9) at t = 0.005 s"
  std::string text(const SimBox& box) const {
    return what + " (function at " + where + ") at t = " + rounded_text(box.sim->now()) + " s";
  }
};

// calls the function in ref with the simulation; nret results left on the stack. Its error is a
// CallbackError, a limit that fired in it too (named with the callback, as any error of its own);
// its code interrupted by Ctrl-C, a StoppedInCode: the run stops there (Simulation::run_to). A
// limit or Ctrl-C were raised again as they were, a Lua error that the run recorded as "an error in
// a callback" (a user's trial)
void call_back(SimBox& box, const LuaRef& ref, int nret, const Callback& cb) {
  lua_State* L = box.L;
  ref.push(L);
  lua_pushvalue(L, 1);  // the simulation: index 1 of the running method
  CallError e;
  // (docall: back in Lua code, inside the run, a call of its own: lua_clock.hpp)
  if (docall(L, 1, nret, &e, cb.what)) return;
  if (take_interrupt(L)) throw StoppedInCode(cb.text(box) + ": " + e.message);
  throw CallbackError(cb.text(box) + ": " + e.message, e.traceback);
}

// sim:every(dt, function(sim) ... end) -> id: called at now + k·dt exactly
int l_every(lua_State* L) {
  Simulation& s = live(L, "every", {{"dt", kNumber}, {"fn", kFunction}});
  SimBox* box = static_cast<SimBox*>(lua_touserdata(L, 1));
  const double dt = to_number(L, 2, "sim:every(dt, fn)");
  if (!lua_isfunction(L, 3)) fail(L, std::string("sim:every: a function expected, got ") + type_name(L, 3));
  auto ref = std::make_unique<LuaRef>(L, 3);
  const LuaRef* r = ref.get();
  int id = 0;
  const Callback cb(L, 3, "sim:every's function");
  guarded(L, "sim:every", [&] { id = s.every(dt, [box, r, cb] { call_back(*box, *r, 0, cb); }); });
  box->refs[id] = std::move(ref);
  lua_pushinteger(L, id);
  return 1;
}

// sim:when(function(sim) return condition end, function(sim) ... end, { once = false }) -> id
int l_when(lua_State* L) {
  Simulation& s = live(L, "when", {{"condition", kFunction}, {"action", kFunction}, {"{once}", kTable, true}});
  SimBox* box = static_cast<SimBox*>(lua_touserdata(L, 1));
  if (!lua_isfunction(L, 2)) fail(L, std::string("sim:when: a condition function expected, got ") + type_name(L, 2));
  if (!lua_isfunction(L, 3)) fail(L, std::string("sim:when: an action function expected, got ") + type_name(L, 3));
  // once: the callback is removed after its first action, as sim:cancel(id) inside the action
  // would (a condition on a noisy quantity, a wrap's creep at its threshold, turns true again
  // within nanoseconds of the action)
  bool once = false;
  if (lua_istable(L, 4)) {
    check_keys(L, 4, "sim:when", {"once"});
    once = opt_bool(L, 4, "once", "sim:when").value_or(false);
  }
  auto cond = std::make_unique<LuaRef>(L, 2), action = std::make_unique<LuaRef>(L, 3);
  const LuaRef *c = cond.get(), *a = action.get();
  auto own_id = std::make_shared<int>(0);  // the callback's id, for the once-action to remove it
  int id = 0;
  const Callback cc(L, 2, "sim:when's condition"), ca(L, 3, "sim:when's action");
  guarded(L, "sim:when", [&] {
    id = s.when(
        [box, c, cc] {
          call_back(*box, *c, 1, cc);
          lua_State* K = box->L;
          if (!lua_isboolean(K, -1)) {
            // 0 is true in Lua: a condition returning 1 or 0 fired at once or never, without a word
            // (named as any callback's error, by the line of the running call)
            const std::string got = type_name(K, -1);
            lua_pop(K, 1);
            throw CallbackError(cc.text(*box) + ": it returned " + got + "; it must return true or false", "");
          }
          const bool v = lua_toboolean(K, -1);
          lua_pop(K, 1);
          return v;
        },
        [box, a, once, own_id, ca] {
          call_back(*box, *a, 0, ca);
          if (once && box->sim->cancel(*own_id)) box->refs.erase(*own_id), box->refs.erase(-*own_id);
        });
  });
  *own_id = id;
  box->refs[id] = std::move(action);
  box->refs[-id] = std::move(cond);
  lua_pushinteger(L, id);
  return 1;
}

// sim:cancel(id) -> true when a callback was removed
int l_cancel(lua_State* L) {
  Simulation& s = live(L, "cancel", {{"id", kNumber}});
  SimBox* box = static_cast<SimBox*>(lua_touserdata(L, 1));
  const int id = to_integer(L, 2, "sim:cancel(id)");
  const bool removed = s.cancel(id);
  box->refs.erase(id), box->refs.erase(-id);
  lua_pushboolean(L, removed);
  return 1;
}

// sim:serve{ port = 0, host = "127.0.0.1" } -> url: the live view of this simulation's runs
// (docs/live-view.md), until it closes. A host other than this machine's loopback needs --trusted.
int l_serve(lua_State* L) {
  SimBox* box = check_box(L, "serve");
  check_args(L, "sim:serve", {{"{port, host}", kTable, true}}, 2);
  live::ServeSettings ss;
  if (lua_istable(L, 2)) {
    check_keys(L, 2, "sim:serve", {"port", "host"});
    if (const auto port = opt_number(L, 2, "port", "sim:serve")) {
      if (!(*port >= 0 && *port <= 65535 && *port == std::floor(*port)))
        fail(L, "sim:serve: port must be an integer in 0..65535 (0: a free one), got " + rounded_text(*port));
      ss.port = static_cast<int>(*port);
    }
    if (field(L, 2, "host")) {
      if (lua_type(L, -1) != LUA_TSTRING) fail(L, std::string("sim:serve: host must be a string, got ") + type_name(L, -1));
      ss.host = lua_tostring(L, -1);
      lua_pop(L, 1);
    }
  }
  if (!box->ctx->trusted && ss.host != "127.0.0.1" && ss.host != "::1" && ss.host != "localhost")
    fail(L, "sim:serve: host '" + ss.host + "' opens the live view to other machines; only a --trusted script may");
  if (box->serve) fail(L, "sim:serve: this simulation is served already, at " + box->serve->url());
  guarded(L, "sim:serve", [&] { box->serve = std::make_shared<live::LiveServer>(ss); });
  say("beltsim: live view at %s\n", box->serve->url().c_str());
  // the page shows the simulation where it stands until it runs; a console applies the page's
  // changes at its prompt
  box->ctx->served[lua_topointer(L, 1)] = {box->serve.get(), box->sim.get()};
  guarded(L, "sim:serve", [&] { LiveFeed(box->serve.get(), box->ctx->stop).show(*box->sim); });
  lua_pushstring(L, box->serve->url().c_str());
  return 1;
}

// box's simulation is closed or being finalised (why: "closed", "finalised"): when --serve's page
// shows it, nothing more is fed to it (the console's prompt fed it a closed simulation's sample,
// picture and refusals) and the page's controls are refused at once, as after a scene:run{},
// until the next run or simulation
void leave_page(SimBox& box, const char* why) {
  if (!box.ctx || !box.sim || box.ctx->page_sim != box.sim.get()) return;
  box.ctx->page_sim = nullptr, box.ctx->page_key = nullptr;
  if (!box.ctx->serve) return;
  box.ctx->serve->set_status(std::string(why) + " at t = " + rounded_text(box.sim->now(), 6) + " s");
  box.ctx->serve->refuse_controls(std::string("no simulation to change (it is ") + why + ")");
}

// sim:close(): flush the CSV files, finalise the video, and say how the runs ended (as scene:run{} does)
int l_close(lua_State* L) {
  SimBox* box = check_box(L, "close");
  check_args(L, "sim:close", {}, 2);
  // its callbacks (this one among them) are in use by the run under way
  if (box->running)
    fail(L, "sim:close: this simulation is running (this is one of its callbacks); close it after sim:run_to or "
            "sim:advance returns");
  const bool was_open = !box->sim->closed();
  leave_page(*box, "closed");  // first: a close that fails (an output not written) has closed it too
  guarded(L, "sim:close", [&] { box->sim->close(); });
  box->ctx->served.erase(lua_topointer(L, 1));
  box->serve.reset();
  // what a batch run says as it ends; its closing line when the simulation ran here, with its
  // progress: where it stands, the steps and wall time of its runs
  if (was_open) {
    const Simulation& s = *box->sim;
    RunEnd end;
    end.warning_summary = s.warning_summary(), end.check_line = s.check_line();
    end.check_warns = s.check_estimate().warns(), end.unapplied = s.unapplied_warnings();
    end.steps = s.stats().steps - box->steps_before, end.wall = s.wall() - box->wall_before;
    end.closing_line = box->progress && end.steps > 0;
    end.t = s.now(), end.t_end = box->last_target, end.stopped = box->last_stopped, end.out_dir = s.out_dir();
    say_run_end(end);
  }
  box->refs.clear();
  return 0;
}

int l_gc(lua_State* L) {
  auto* box = static_cast<SimBox*>(luaL_testudata(L, 1, kSimMeta));
  if (!box) return 0;
  try {
    if (box->sim) box->sim->close();
  } catch (const std::exception& e) {
    say("beltsim: closing a simulation: %s\n", e.what());
  }
  // emptied rather than destroyed: a finaliser that runs later (another object's __gc) may still
  // reach this userdata, and must find "finalised" (sim == nullptr), not a dead object
  leave_page(*box, "finalised");
  if (box->ctx) box->ctx->served.erase(lua_topointer(L, 1));
  box->serve.reset();
  box->sim.reset();
  box->refs.clear();
  box->pictures.clear();  // (the userdata's members are emptied here, never destroyed: every one)
  return 0;
}

int l_tostring(lua_State* L) {
  auto* box = static_cast<SimBox*>(luaL_testudata(L, 1, kSimMeta));
  if (!box || !box->sim) return lua_pushliteral(L, "beltsim simulation (finalised)"), 1;
  const Simulation& s = *box->sim;
  lua_pushfstring(L, "beltsim simulation at t = %f s (%s, %d elements%s)", s.now(), s.integrator_name().c_str(),
                  s.model().n_el(), s.closed() ? ", closed" : "");
  return 1;
}

const luaL_Reg kMethods[] = {
    {"run_to", l_run_to},   {"advance", l_advance},       {"pulley", l_pulley},       {"element", l_element},
    {"elements", l_elements},
    {"span", l_span},       {"energy", l_energy},         {"stats", l_stats},         {"set_torque", l_set_torque},
    {"set_speed", l_set_speed}, {"set_arm", l_set_arm}, {"set_rotor", l_set_rotor}, {"wet", l_wet},           {"spray", l_spray},       {"set_mu", l_set_mu},       {"log", l_log},
    {"every", l_every},     {"when", l_when},             {"cancel", l_cancel},       {"show", l_show},
    {"plot", l_plot},       {"summary", l_sim_summary}, {"modes", l_modes}, {"save", l_save},             {"serve", l_serve},             {"close", l_close},           {nullptr, nullptr}};

// sim.t is the current time; sim.<method> the methods
int l_index(lua_State* L) {
  auto* box = static_cast<SimBox*>(luaL_checkudata(L, 1, kSimMeta));
  const char* key = lua_tostring(L, 2);
  if (key && std::string(key) == "t") {
    if (!box->sim) fail_on(L, "sim.t", "this simulation has been finalised");
    lua_pushnumber(L, box->sim->now());
    return 1;
  }
  lua_getmetatable(L, 1);
  lua_getfield(L, -1, "methods");
  lua_pushvalue(L, 2);
  if (lua_rawget(L, -2) != LUA_TNIL || !key) return 1;
  std::vector<std::string> names{"t"};
  for (const luaL_Reg* r = kMethods; r->name; ++r) names.push_back(r->name);
  fail(L, std::string("sim has no field or method '") + key + "'" + did_you_mean(key, names) +
              "; fields: t; methods: " + join(std::vector<std::string>(names.begin() + 1, names.end())));
}

// sim.KEY = value: nothing of a simulation is set by assignment; its time moves by running it
int l_newindex(lua_State* L) {
  luaL_checkudata(L, 1, kSimMeta);
  const char* key = lua_tostring(L, 2);
  if (key && std::string(key) == "t")
    fail(L, "sim.t is read-only: the simulation's time moves by running it (sim:run_to(t), sim:advance(dt))");
  fail(L, std::string("sim.") + (key ? key : luaL_typename(L, 2)) +
              " cannot be set: a simulation has no fields to set but through its methods (sim:set_torque, "
              "sim:wet, ...; help() lists them)");
}

}  // namespace

std::vector<std::string> argument_names(lua_State* L, int idx, const std::string& method, bool in_table, int arg,
                                        const std::string& key) {
  const auto* box = static_cast<const SimBox*>(luaL_testudata(L, idx, kSimMeta));
  if (!box || !box->sim) return {};
  const Simulation& s = *box->sim;
  std::vector<std::string> names;
  auto pulleys = [&](auto keep) {
    for (const Pulley& p : s.model().pulleys)
      if (keep(p)) names.push_back(p.name);
  };
  const auto any = [](const Pulley&) { return true; };
  if (in_table) {
    if (method == "elements" && key == "pulley") pulleys(any);
    if (method == "plot" && key.empty()) names = s.columns();
    if (method == "show" && key == "quantity")
      for (const FrameQuantityInfo& q : frame_quantities()) names.push_back(q.key);
    return names;
  }
  if (((method == "pulley" || method == "set_torque" || method == "set_speed") && arg == 1) ||
      (method == "span" && arg <= 2)) {
    pulleys(any);
  } else if (method == "set_arm" && arg == 1) {
    pulleys([](const Pulley& p) { return p.arm >= 0; });
  } else if (method == "set_rotor" && arg == 1) {
    pulleys([](const Pulley& p) { return p.coupling >= 0; });
  }
  return names;
}

void push_simulation(lua_State* L, std::unique_ptr<Simulation> sim, Context* ctx, bool progress) {
  auto* box = new (lua_newuserdatauv(L, sizeof(SimBox), 0)) SimBox();
  box->sim = std::move(sim);
  box->ctx = ctx;
  box->progress = progress;
  box->steps_before = box->sim->stats().steps, box->wall_before = box->sim->wall();
  box->t_start = box->sim->now();
  luaL_setmetatable(L, kSimMeta);
  // --serve's page, before a run has fed it, shows the simulation started last (a console's
  // prompt applies the page's changes to it)
  if (ctx && ctx->serve && !ctx->page_ran) {
    ctx->page_sim = box->sim.get(), ctx->page_key = lua_topointer(L, -1);
    try {
      LiveFeed(ctx->serve.get(), ctx->stop).show(*box->sim);
    } catch (const std::exception& e) {
      say("beltsim: live view: %s\n", e.what());
    }
  }
}

void open_sim(lua_State* L, Context* ctx) {
  luaL_newmetatable(L, kSimMeta);
  lua_pushcfunction(L, l_gc), lua_setfield(L, -2, "__gc");
  lua_pushcfunction(L, l_tostring), lua_setfield(L, -2, "__tostring");
  lua_pushcfunction(L, l_index), lua_setfield(L, -2, "__index");
  lua_pushcfunction(L, l_newindex), lua_setfield(L, -2, "__newindex");
  lua_pushliteral(L, "beltsim.Simulation"), lua_setfield(L, -2, "__metatable");
  luaL_newlib(L, kMethods);
  lua_setfield(L, -2, "methods");
  lua_pop(L, 1);
  lua_pushlightuserdata(L, ctx);
  lua_pushcclosure(L, l_resume, 1), lua_setfield(L, -2, "resume");
  lua_pushlightuserdata(L, ctx);
  lua_pushcclosure(L, l_replay_of, 1), lua_setfield(L, -2, "replay_of");
}

}  // namespace beltsim::script
