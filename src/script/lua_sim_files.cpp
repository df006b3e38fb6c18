// What a live simulation writes to files and reads back: sim:show (a frame of the belt now),
// sim:plot (time histories so far), sim:save (a checkpoint) and beltsim.resume (sim_box.hpp).
#include <cstdio>
#include <filesystem>

#include "io/number_text.hpp"
#include "io/output_dir.hpp"
#include "io/suggest.hpp"
#include "plot/plot.hpp"
#include "render/recorder.hpp"
#include "script/lua_run.hpp"
#include "script/lua_sim.hpp"
#include "script/progress.hpp"
#include "script/sandbox.hpp"
#include "script/sim_box.hpp"
#include "sim/outputs.hpp"
#include "sim/run_table.hpp"

namespace beltsim::script {

namespace {

void picture(lua_State* L, SimBox& box, const std::string& png) {
  before_stdout();  // drawn from a run's callback, on the progress line's terminal
  if (box.ctx->on_picture)
    box.ctx->on_picture(png);
  else
    std::printf("picture: %s\n", png.c_str()), std::fflush(stdout);
  (void)L;
}

// an empty file = "" (it was taken as no name given: the default one)
const char* const kEmptyPicture = "an empty file name (leave file out for the default name in the output folder)";

// the default path of a picture of kind `stem` at time t in the output folder: STEM_<t>.png, or
// when this simulation has written that one (a second picture at the same time) STEM_<t>_2.png, _3 ...
// (sim/outputs.hpp picture_name, whose names a later run in the folder names as an earlier run's)
std::string picture_path(const SimBox& box, const std::string& stem, double t) {
  std::string path = output_path(box.sim->settings(), picture_name(stem, t));
  for (int k = 2; box.pictures.count(path); ++k) path = output_path(box.sim->settings(), picture_name(stem, t, k));
  return path;
}

// A relative path that is not there but is one sim:save was given (sim:save("ck/t03.ckpt")) or lies
// so in the output folder: refused naming the checkpoint that is there. sim:save takes a relative
// path inside the simulation's output folder, beltsim.resume from the folder beltsim runs in, so the
// same path read back said only "No such file or directory"
void refuse_a_save_path(lua_State* L, const Context& ctx, const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (path.empty() || fs::path(path).is_absolute() || fs::symlink_status(path, ec).type() != fs::file_type::not_found)
    return;
  std::vector<std::pair<std::string, std::string>> candidates;  // the path, and what says where it is
  if (const auto it = ctx.saved.find(path); it != ctx.saved.end())
    candidates.emplace_back(it->second, "sim:save(\"" + path + "\") wrote " + it->second);
  const std::string out = ctx.overrides.has("out") ? ctx.overrides.run.out_dir : ctx.default_out;
  candidates.emplace_back(output_path(out, path), "the output folder " + out + " holds " + output_path(out, path));
  for (const auto& [there, found] : candidates)
    if (fs::is_regular_file(there, ec))
      fail(L, "beltsim.resume: " + path + ": no such file in the folder beltsim runs in, where beltsim.resume reads; " +
                  found + " (sim:save takes a relative path inside the simulation's output folder): resume \"" + there +
                  "\", the path sim:save returned");
}

}  // namespace

// sim:show{ quantity, range, levels, magnify, view, size, file } -> path of the PNG
int l_show(lua_State* L) {
  Simulation& s = live(L, "show", {{"{quantity, range, ...}", kTable, true}});
  SimBox& box = *static_cast<SimBox*>(lua_touserdata(L, 1));
  FrameSettings fs;
  std::string file;
  if (!lua_isnoneornil(L, 2)) {
    require_table(L, 2, "sim:show");
    fs = to_frames(L, 2, "sim:show", {"quantity", "range", "levels", "magnify", "view", "size", "file"});
    if (auto f = opt_string(L, 2, "file", "sim:show")) {
      if (f->empty()) fail_on(L, "sim:show.file", kEmptyPicture);
      file = *f;
    }
    if (const std::string bad = png_name_problem(file); !file.empty() && !bad.empty())
      fail_on(L, "sim:show.file", "'" + file + "': " + bad);
  }
  file = file.empty() ? picture_path(box, "show", s.now()) : output_path(s.settings(), file);
  if (const std::string r = output_refusal(*box.ctx, "sim:show", file, true); !r.empty()) fail(L, r);
  guarded(L, "sim:show", [&] { render::render_snapshot(s.scene(), fs, s.now(), s.state().data(), s.drive(), file, &s.observation());
  });
  box.shows++;
  box.pictures.insert(file);
  picture(L, box, file);
  lua_pushstring(L, file.c_str());
  return 1;
}

// sim:plot{ "driver.omega", "driven.omega", from = t0 [s], file = "x.png" } -> path of the PNG
int l_plot(lua_State* L) {
  Simulation& s = live(L, "plot", {{"{columns..., from, file}", kTable, true}});
  SimBox& box = *static_cast<SimBox*>(lua_touserdata(L, 1));
  std::vector<std::string> columns;
  double from = 0;
  std::string file;
  if (!lua_isnoneornil(L, 2)) {
    require_table(L, 2, "sim:plot");
    lua_pushnil(L);
    while (lua_next(L, 2)) {
      lua_pop(L, 1);
      if (lua_type(L, -1) == LUA_TSTRING) {
        const std::string k = lua_tostring(L, -1);
        if (k != "from" && k != "file") {
          fail(L, "unknown key '" + k + "' in sim:plot" + did_you_mean(k, {"from", "file"}) +
                      "; valid keys: from, file, and column names as a list");
        }
      } else if (lua_type(L, -1) != LUA_TNUMBER) {
        fail(L, "sim:plot: column names as a list, from = t0 and file = path expected");
      }
    }
    const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, 2));
    for (lua_Integer k = 1; k <= n; ++k) {
      lua_rawgeti(L, 2, k);
      if (lua_type(L, -1) != LUA_TSTRING)
        fail(L, "sim:plot: column " + std::to_string(k) + ": a column name expected, got " + type_name(L, -1));
      columns.push_back(lua_tostring(L, -1));
      lua_pop(L, 1);
    }
    if (auto v = opt_number(L, 2, "from", "sim:plot")) from = *v;
    if (auto f = opt_string(L, 2, "file", "sim:plot")) {
      if (f->empty()) fail_on(L, "sim:plot.file", kEmptyPicture);
      file = *f;
    }
    if (const std::string bad = png_name_problem(file); !file.empty() && !bad.empty())
      fail_on(L, "sim:plot.file", "'" + file + "': " + bad);
  }
  const std::vector<std::string> valid = s.columns();
  for (const std::string& c : columns) {
    bool ok = false;
    for (const std::string& v : valid) ok = ok || v == c;
    if (!ok) {
      std::string list;
      for (const std::string& v : valid) list += (list.empty() ? "" : ", ") + v;
      fail(L, "sim:plot: no column '" + c + "'" + did_you_mean(c, valid) + "; columns: " + list);
    }
  }
  file = file.empty() ? picture_path(box, "plot", s.now()) : output_path(s.settings(), file);
  if (const std::string r = output_refusal(*box.ctx, "sim:plot", file, true); !r.empty()) fail(L, r);
  guarded(L, "sim:plot", [&] {
    if (const std::string w = plot::left_out_warning(plot::plot_csv(s.csv_path(), columns, from, file)); !w.empty())
      say("beltsim: warning: sim:plot: %s\n", w.c_str());
  });
  box.pictures.insert(file);
  picture(L, box, file);
  lua_pushstring(L, file.c_str());
  return 1;
}

// sim:save(path) -> path: a checkpoint (see sim/checkpoint.cpp)
int l_save(lua_State* L) {
  Simulation& s = live(L, "save", {{"path", kString}});
  if (lua_type(L, 2) != LUA_TSTRING) fail(L, std::string("sim:save: a file name expected, got ") + type_name(L, 2));
  std::string path = lua_tostring(L, 2);
  // (it was taken as the output folder: "cannot write out/x: it is a folder")
  if (path.empty()) fail(L, "sim:save: an empty file name (give the checkpoint's, e.g. sim:save(\"state.ckpt\"))");
  // inside the output folder as every path beltsim writes for a script (sim/run_settings.hpp): the
  // same in the console and in its session.lua's replay (a path with a folder was taken from the
  // folder beltsim ran in, which the replay's sandbox refused)
  const std::string given = path;
  path = output_path(s.settings(), path);
  Context& ctx = *static_cast<SimBox*>(lua_touserdata(L, 1))->ctx;
  if (const std::string r = output_refusal(ctx, "sim:save", path, true); !r.empty()) fail(L, r);
  guarded(L, "sim:save", [&] { s.save(path); });
  ctx.saved[given] = path;
  lua_pushstring(L, path.c_str());
  return 1;
}

// beltsim.resume(path [, { progress = bool, rewind = bool, max_wall = s, out = folder }]) -> the
// saved simulation, continuing (in its own folder, or with out in a branch of it: sim/simulation.hpp)
int l_resume(lua_State* L) {
  check_args(L, "beltsim.resume", {{"path", kString}, {"{progress, rewind, max_wall, out}", kTable, true}});
  auto* ctx = static_cast<Context*>(lua_touserdata(L, lua_upvalueindex(1)));
  end_if_probing(L, ctx, "beltsim.resume");
  refuse_if_capturing(L, ctx, "beltsim.resume");
  end_if_stopped(L, ctx, "beltsim.resume");
  bool progress = true, rewind = false;
  // the wall-time limit of each integration call, which a checkpoint does not keep (it is this
  // process's guard, not the run's): resume's own, checked as scene:start's max_wall; --max-wall over it
  double max_wall = 0;
  std::string out;  // "": the checkpoint's own folder
  if (!lua_isnoneornil(L, 2)) {
    require_table(L, 2, "beltsim.resume");
    check_keys(L, 2, "beltsim.resume", {"progress", "rewind", "max_wall", "out"});
    if (auto v = opt_bool(L, 2, "progress", "beltsim.resume")) progress = *v;
    if (auto v = opt_bool(L, 2, "rewind", "beltsim.resume")) rewind = *v;
    if (auto v = opt_number(L, 2, "max_wall", "beltsim.resume")) {
      RunSettings given;
      given.wall_limit = *v;
      if (const std::string bad = run_problem(*find_run_setting("max_wall"), given, true); !bad.empty())
        fail_on(L, "beltsim.resume.max_wall", bad);
      max_wall = *v;
    }
    if (auto v = opt_string(L, 2, "out", "beltsim.resume")) {
      if (v->empty())
        fail_on(L, "beltsim.resume.out",
                "an empty folder name (leave out out to go on in the checkpoint's own folder)");
      out = *v;
    }
  }
  if (ctx->overrides.has("max_wall")) max_wall = ctx->overrides.run.wall_limit;
  // the command line's other run options (--out, --rtol, --no-frames, ...) are scene:run's and
  // scene:start's: a resumed simulation keeps the checkpoint's settings. Said once, before it runs
  size_t count = ctx->overrides.no_frames ? 1 : 0;
  std::string options;
  for (const std::string& k : ctx->overrides.given)  // (the option each key comes from: sim/run_table.hpp)
    if (k != "max_wall") options += (options.empty() ? "" : ", ") + std::string(find_run_setting(k)->option), ++count;
  if (ctx->overrides.no_frames) options += options.empty() ? "--no-frames" : ", --no-frames";
  if (!ctx->resume_warned && count > 0) {
    ctx->resume_warned = true;
    say("beltsim: warning: %s %s to scene:run and scene:start only; the simulation beltsim.resume "
        "continues keeps its checkpoint's settings (its folder, integrator, tolerances and frames)\n",
        options.c_str(), count == 1 ? "applies" : "apply");
  }
  std::unique_ptr<Simulation> sim;
  int callbacks = 0;
  if (const std::string r = output_refusal(*ctx, "beltsim.resume", lua_tostring(L, 1), false); !r.empty()) fail(L, r);
  refuse_a_save_path(L, *ctx, lua_tostring(L, 1));
  // the checkpoint names the outputs it continues: they lie where the sandbox allows too
  const auto vet = [ctx](const RunSettings& rs) {
    if (const std::string r = run_paths_refusal(*ctx, "resume", rs); !r.empty()) throw std::invalid_argument(r);
  };
  const auto warn = [](const std::string& m) { say("beltsim: warning: %s\n", m.c_str()); };
  guarded(L, "beltsim.resume", [&] {
    sim = Simulation::resume(lua_tostring(L, 1), render::make_frame_recorder, &callbacks, vet, rewind, warn, out);
  });
  sim->set_wall_limit(max_wall);
  const std::string copied = sim->branched_from().empty()
                                 ? ""
                                 : " (a copy of " + sim->branched_from() + "'s up to it; that folder is left as it is)";
  say("beltsim: %s resumed at t = %s s; its outputs go on in %s%s\n", lua_tostring(L, 1),
      rounded_text(sim->now()).c_str(), sim->out_dir().c_str(), copied.c_str());
  if (callbacks > 0)
    say("beltsim: %s had %d callback(s) (every, when); register them again on the resumed simulation\n",
        lua_tostring(L, 1), callbacks);
  push_simulation(L, std::move(sim), ctx, progress);
  return 1;
}

}  // namespace beltsim::script
