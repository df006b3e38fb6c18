// What a live simulation writes to files and reads back: sim:show (a frame of the belt now),
// sim:plot (time histories so far), sim:save (a checkpoint) and beltsim.resume (sim_box.hpp).
#include <algorithm>
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

// ---- a replay of a console session that resumed checkpoints (Context::replay_of) -------------

// the folder this script's runs write by default: --out, else out/<script name>; a replay of a
// session's session.lua writes there (its replay line gives --out <session folder>/replay)
std::string replay_folder(const Context& ctx) {
  return ctx.overrides.has("out") ? ctx.overrides.run.out_dir : ctx.default_out;
}

// true when path is the folder dir or lies under it (absolute and normalised, as run_dir_key)
bool lies_in(const std::string& path, const std::string& dir) {
  const std::filesystem::path p(run_dir_key(path)), d(run_dir_key(dir));
  return std::mismatch(d.begin(), d.end(), p.begin(), p.end()).first == d.end();
}

// true when path belongs to the session this script replays: it lies in the session's folder,
// and not in the replay's own folder inside it (out/x/replay, which the replay line gives)
bool of_the_session(const Context& ctx, const std::string& path) {
  if (!ctx.replay_of || !lies_in(path, *ctx.replay_of)) return false;
  const std::string mine = replay_folder(ctx);
  const bool mine_inside = lies_in(mine, *ctx.replay_of) && run_dir_key(mine) != run_dir_key(*ctx.replay_of);
  return !(mine_inside && lies_in(path, mine));
}

// the path in the replay's own folder that stands where path stands in the session's folder:
// out/x/ck/t.ckpt -> out/x/replay/ck/t.ckpt (where the replay's sim:save("ck/t.ckpt") wrote)
std::string in_replay_folder(const Context& ctx, const std::string& path) {
  const std::filesystem::path rel =
      std::filesystem::path(run_dir_key(path)).lexically_relative(run_dir_key(*ctx.replay_of));
  const std::string mine = replay_folder(ctx);
  return rel == "." ? mine : (std::filesystem::path(mine) / rel).string();
}

}  // namespace

// beltsim.replay_of(dir): the console's session.lua names at its start the session's folder
// when the session called beltsim.resume, so that its replay continues its own checkpoints and
// never the session's (which would write the replay's runs into the session's folder)
int l_replay_of(lua_State* L) {
  check_args(L, "beltsim.replay_of", {{"dir", kString}});
  auto* ctx = static_cast<Context*>(lua_touserdata(L, lua_upvalueindex(1)));
  const std::string dir = lua_tostring(L, 1);
  if (dir.empty())
    fail(L,
         "beltsim.replay_of: an empty folder name (give the folder of the session this script replays, where "
         "its session.lua lies)");
  const std::string mine = replay_folder(*ctx);
  if (run_dir_key(mine) == run_dir_key(dir))
    fail(L, "beltsim.replay_of: this replay's outputs would go into " + mine +
                ", the folder of the session it replays, and overwrite the record it is checked against; give "
                "the replay a folder of its own, as session.lua's replay line does: --out " +
                (std::filesystem::path(dir) / "replay").string());
  ctx->replay_of = dir;
  return 0;
}

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
    for (const std::string& w : plot::left_out_warnings(plot::plot_csv(s.csv_path(), columns, from, file)))
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
  ctx->resumed = true;  // session.lua names the session's folder for its replay (beltsim.replay_of)
  std::string path = lua_tostring(L, 1);
  // a replay of a console session (beltsim.replay_of): a checkpoint the session saved in its
  // folder, which continues the session's outputs, is read from the replay's own folder, where
  // the replay's sim:save wrote its copy, whose outputs are the replay's; one missing there is
  // refused (the session's would write the replay's run into the session's folder). A branch
  // (out) into the session's folder goes into the replay's folder the same way
  std::string session_copy;  // the session's checkpoint that path stands for ("": none)
  if (ctx->replay_of && of_the_session(*ctx, path)) {
    const std::string mine = in_replay_folder(*ctx, path);
    std::error_code ec;
    if (std::filesystem::symlink_status(mine, ec).type() == std::filesystem::file_type::not_found)
      fail(L, "beltsim.resume: " + path + " lies in " + *ctx->replay_of +
                  ", the folder of the session this script replays, and continues its outputs; a replay resumes "
                  "its own copy instead, " +
                  mine +
                  ", and that is not there (this replay's sim:save did not write it: an earlier session "
                  "saved the checkpoint, or this replay's simulations run in another folder than the session's "
                  "did): replay the session as session.lua's replay line says; nothing was written");
    session_copy = path, path = mine;
  }
  if (!out.empty() && of_the_session(*ctx, out)) {
    const std::string mine = in_replay_folder(*ctx, out);
    say("beltsim: beltsim.resume: the branch into %s, in the folder of the session this script replays, goes "
        "into %s, in the replay's own folder, instead\n",
        out.c_str(), mine.c_str());
    out = mine;
  } else if (!out.empty() && ctx->replay_of) {
    // a branch of the session's into a folder of its own (beside the session's): into the replay's
    // folder too, under its name, so that the replay writes nothing the session wrote (a user's
    // trial: the replay's sandbox refused the session's out/con2b, and under --trusted the replay
    // wrote over the session's branch)
    std::filesystem::path p = std::filesystem::path(out).lexically_normal();
    if (p.filename().empty()) p = p.parent_path();
    const std::string mine = (std::filesystem::path(replay_folder(*ctx)) / p.filename()).string();
    say("beltsim: beltsim.resume: the session's branch into %s goes into %s, in the replay's own folder, instead\n",
        out.c_str(), mine.c_str());
    out = mine;
  }
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
        "continues keeps its checkpoint's settings (%s)\n",
        options.c_str(), count == 1 ? "applies" : "apply",
        out.empty() ? "its folder, integrator, tolerances and frames"
                    : "its integrator, tolerances and frames; its folder is out's");
  }
  std::unique_ptr<Simulation> sim;
  int callbacks = 0;
  if (const std::string r = output_refusal(*ctx, "beltsim.resume", path, false); !r.empty()) fail(L, r);
  refuse_a_save_path(L, *ctx, path);
  // the checkpoint names the outputs it continues: they lie where the sandbox allows too; in a
  // replay, not in the session's folder (a checkpoint saved elsewhere whose run wrote there).
  // A branch's source (out given, another folder) is only read: it may be the session's
  const auto vet = [ctx, &out, &path](const RunSettings& rs) {
    if (const std::string r = run_paths_refusal(*ctx, "resume", rs); !r.empty()) throw std::invalid_argument(r);
    if (!ctx->replay_of || (!out.empty() && run_dir_key(rs.out_dir) != run_dir_key(out))) return;
    std::vector<std::string> written{rs.out_dir};
    if (rs.frames)
      for (const std::string* p : {&rs.frames->png_dir, &rs.frames->video_path})
        if (!p->empty()) written.push_back(output_path(rs, *p));
    for (const std::string& w : written)
      if (of_the_session(*ctx, w)) {
        const std::string& session = *ctx->replay_of;
        throw std::invalid_argument(
            path + ": its run would write into " +
            (run_dir_key(w) == run_dir_key(session) ? w : w + ", inside " + session) +
            ", the folder of the session this script replays, and change the record the replay is checked "
            "against; a replay resumes only checkpoints whose outputs are its own (one the session saved in its "
            "folder is read from the replay's own folder), or branches one into a folder of its own (out = ...); "
            "nothing was written");
      }
  };
  const auto warn = [](const std::string& m) { say("beltsim: warning: %s\n", m.c_str()); };
  guarded(L, "beltsim.resume",
          [&] { sim = Simulation::resume(path, render::make_frame_recorder, &callbacks, vet, rewind, warn, out); });
  sim->set_wall_limit(max_wall);
  const std::string copied = sim->branched_from().empty()
                                 ? ""
                                 : " (a copy of " + sim->branched_from() + "'s up to it; that folder is left as it is)";
  const std::string shown =
      session_copy.empty() ? path : path + " (this replay's copy of the session's " + session_copy + ")";
  say("beltsim: %s resumed at t = %s s; its outputs go on in %s%s\n", shown.c_str(), rounded_text(sim->now()).c_str(),
      sim->out_dir().c_str(), copied.c_str());
  if (callbacks > 0)
    say("beltsim: %s had %d callback(s) (every, when); register them again on the resumed simulation\n", path.c_str(),
        callbacks);
  push_simulation(L, std::move(sim), ctx, progress);
  return 1;
}

}  // namespace beltsim::script
