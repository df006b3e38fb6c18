// scene:run{} and scene:start{} (docs/lua-api.md): a scene's methods that integrate, on the run
// settings lua_run.cpp reads; scene:start hands back the live simulation of lua_sim.cpp.
#include "script/lua_scene_run.hpp"

#include <cstdio>
#include <memory>
#include <string>

#include "io/number_text.hpp"
#include "io/units.hpp"
#include "scene/validate.hpp"
#include "script/context.hpp"
#include "script/live_feed.hpp"
#include "script/lua_args.hpp"
#include "script/lua_check.hpp"
#include "script/lua_clock.hpp"
#include "script/lua_run.hpp"
#include "script/lua_scene.hpp"
#include "script/lua_sim.hpp"
#include "script/lua_summary.hpp"
#include "script/progress.hpp"
#include "sim/run_table.hpp"

namespace beltsim::script {

namespace {

// the message of an error about a run setting (sim/settings_check.hpp, check), its path set in
// `about` under the call's table (run.sample, start.frames.fps): made here, where it is reported
std::string setting_error(const char* table, const ParameterError& e, KeyPath& about) {
  about = e.path;
  about.chain.insert(about.chain.begin(), table);
  return parameter_message(path_text(about), e.reason, e.value, e.unit);
}

// scene:run{ t_end=, integrator=, rtol=, atol=, sample=, out=, probe=, progress=, events=, frames=, check= } -> result
// = scene:start{...}, sim:run_to(t_end), sim:close()
int l_scene_run(lua_State* L) {
  const Scene* sc = check_scene(L, 1, "run");
  check_args(L, "scene:run", {{"{t_end, integrator, ...}", kTable, true}}, 2);
  auto* ctx = static_cast<Context*>(lua_touserdata(L, lua_upvalueindex(1)));
  end_if_probing(L, ctx, "scene:run");
  end_if_stopped(L, ctx, "scene:run");
  bool progress = true;
  RunSettings rs = read_run_settings(L, 2, *sc, ctx, true, &progress);
  check_unread_args(L, *ctx, "run");
  for (const std::string& note : drop_after_end(rs, ctx->overrides.has("t_end") ? "--t-end" : nullptr))
    say("beltsim: %s\n", note.c_str());
  if (ctx->capture) {
    ctx->capture->scene = *sc;
    ctx->capture->settings = rs;
    ctx->captured = true;
    lua_pushliteral(L, "scene captured");
    return lua_error(L);
  }
  // (not for a captured scene: what is captured is not run here)
  if (const std::string w = sample_warning(rs, ctx->overrides.has("t_end") ? "--t-end" : nullptr); !w.empty())
    say("beltsim: warning: %s\n", w.c_str());

  std::string error;
  KeyPath about;  // the setting an error is about: its line is the key's (lua_check.hpp, fail_at)
  RunResult res;
  try {
    const HostWork work;  // beltsim's own work, not Lua code (lua_clock.hpp)
    ProgressLine line(progress);
    LiveFeed feed(ctx->serve.get(), ctx->stop, &ctx->page_changes);
    ctx->page_sim = nullptr;  // the page shows this run now, which ends with this call
    if (ctx->serve) ctx->page_ran = true;
    res = run(*sc, rs, ctx->stop, line.callback(), [&](Simulation& sim, double t) {
      record_run_dir(ctx, rs.out_dir);  // its outputs are open
      return run_feed(ctx, feed, sim, t, line.callback());
    });
    line.finish(res.t_reached, res.work.steps, res.wall_seconds);
  } catch (const DivergenceError& e) {
    error = e.what() + samples_note(rs.out_dir);
    ctx->divergence = {e.t, e.what()};
  } catch (const ParameterError& e) {
    error = setting_error("run", e, about);
  } catch (const std::exception& e) {
    error = e.what();
  }
  if (res.over_wall_limit) {
    // not silent: the outputs are finalised (run() closed them) and the script stops here
    // the limit named where it was given: the run's max_wall, or the command line's --max-wall
    const bool option = ctx->overrides.has("max_wall");
    about = option ? KeyPath{} : KeyPath{"", {"run", "max_wall"}};
    error = (option ? std::string() : path_text(about) + ": ") + "the run " +
            wall_limit_text(rs.wall_limit, res.t_reached, rs.t_end, res.csv_path, option);
  }
  // the page showed this run, which has ended: a change from it is refused at once (no simulation
  // is left to change; a console's prompt refused it only after it had been answered "queued")
  if (ctx->serve) ctx->serve->refuse_controls("no simulation to change (the run has ended)");
  // the run's last lines; its closing line said with its progress (progress = false leaves both
  // out). A run stopped by max_wall ran, as one Ctrl-C stopped did: its lines come before the error
  RunEnd end;
  end.warning_summary = res.warning_summary, end.check_line = res.check_line, end.check_warns = res.check.warns();
  end.unapplied = res.unapplied;
  end.closing_line = progress;
  end.t = res.t_reached, end.t_end = rs.t_end, end.stopped = res.interrupted || res.over_wall_limit;
  end.steps = res.work.steps, end.wall = res.wall_seconds, end.out_dir = rs.out_dir;
  if (res.over_wall_limit) say_run_end(end);
  if (!error.empty()) fail_at(L, about, error);
  if (res.interrupted) ctx->interrupted = true, ctx->stopped_runs.push_back({nullptr, res.t_reached});
  say_run_end(end);

  lua_newtable(L);
  lua_pushnumber(L, res.t_reached), lua_setfield(L, -2, "t");
  lua_pushboolean(L, res.interrupted), lua_setfield(L, -2, "interrupted");
  lua_pushnumber(L, res.wall_seconds), lua_setfield(L, -2, "wall");
  lua_pushinteger(L, res.work.steps), lua_setfield(L, -2, "steps");
  lua_pushinteger(L, res.work.rejected), lua_setfield(L, -2, "rejected");
  lua_pushinteger(L, res.work.rhs), lua_setfield(L, -2, "rhs");
  lua_pushinteger(L, res.work.jacobians), lua_setfield(L, -2, "jacobians");
  lua_pushinteger(L, res.work.factorizations), lua_setfield(L, -2, "factorizations");
  lua_pushstring(L, res.csv_path.c_str()), lua_setfield(L, -2, "csv");
  lua_pushstring(L, res.parameters_path.c_str()), lua_setfield(L, -2, "parameters");
  lua_pushinteger(L, res.frames), lua_setfield(L, -2, "frames");
  lua_newtable(L);
  for (int j = 0; j < sc->model.n_p(); ++j)
    lua_pushnumber(L, res.omega[j]), lua_setfield(L, -2, sc->model.pulleys[j].name.c_str()),
        set_unit(L, -1, sc->model.pulleys[j].name, run_result_unit("omega." + sc->model.pulleys[j].name).value_or(""));
  lua_setfield(L, -2, "omega");
  if (res.check.on) push_check(L, res.check), lua_setfield(L, -2, "check");
  set_results_methods(L, ctx);
  lua_pushvalue(L, -1);
  lua_setfield(L, LUA_REGISTRYINDEX, kLastRun);
  return 1;
}

// scene:start{ integrator=, rtol=, atol=, sample=, out=, probe=, progress=, frames= } -> sim at t = 0
int l_scene_start(lua_State* L) {
  const Scene* sc = check_scene(L, 1, "start");
  check_args(L, "scene:start", {{"{integrator, rtol, ...}", kTable, true}}, 2);
  auto* ctx = static_cast<Context*>(lua_touserdata(L, lua_upvalueindex(1)));
  end_if_probing(L, ctx, "scene:start");
  refuse_if_capturing(L, ctx, "scene:start");
  end_if_stopped(L, ctx, "scene:start");
  bool progress = true;
  const RunSettings rs = read_run_settings(L, 2, *sc, ctx, false, &progress);
  check_unread_args(L, *ctx, "start");
  // a live simulation runs to the times its script names: said once, before anything runs
  if (ctx->overrides.has("t_end") && !ctx->t_end_warned) {
    ctx->t_end_warned = true;
    say("beltsim: warning: --t-end %s s shortens scene:run only; %s's simulation (scene:start) runs to the "
        "times its sim:run_to and sim:advance name\n",
        rounded_text(ctx->overrides.run.t_end).c_str(), ctx->script.empty() ? "the console" : ctx->script.c_str());
  }
  std::unique_ptr<Simulation> sim;
  std::string error;
  KeyPath about;
  try {
    const HostWork work;  // beltsim's own work, not Lua code (lua_clock.hpp)
    sim = std::make_unique<Simulation>(*sc, rs);
    record_run_dir(ctx, rs.out_dir);
  } catch (const ParameterError& e) {
    error = setting_error("start", e, about);
  } catch (const std::exception& e) {  // an output that cannot be written, a folder in use
    error = std::string("start: ") + e.what();
  }
  if (!error.empty()) fail_at(L, about, error);
  // a Lua law, which no checkpoint can hold, is said where a state is saved (sim:save, the live
  // view's Save, keep_states), not here: most simulations with one are never saved
  push_simulation(L, std::move(sim), ctx, progress);
  return 1;
}

}  // namespace

void open_scene_runs(lua_State* L, Context* ctx) {
  add_scene_method(L, "run", l_scene_run, ctx);
  add_scene_method(L, "start", l_scene_start, ctx);
}

}  // namespace beltsim::script
