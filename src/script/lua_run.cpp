// The run settings of scene:run{} and scene:start{} (see lua_run.hpp) read from their tables
// (every key checked, as in lua_scene.cpp), the μ events and frames among them, and the readers
// the live simulation's methods share.
#include "script/lua_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "integrate/integrator.hpp"
#include "io/number_text.hpp"
#include "io/suggest.hpp"
#include "io/units.hpp"
#include "model/laws.hpp"
#include "render/draw_list.hpp"
#include "render/recorder.hpp"
#include "scene/validate.hpp"
#include "script/context.hpp"
#include "script/lua_check.hpp"
#include "script/lua_scene_parts.hpp"
#include "script/progress.hpp"
#include "script/sandbox.hpp"
#include "sim/run_table.hpp"

namespace beltsim::script {

std::string range_problem(const Scene& sc, std::optional<double> from, std::optional<double> to,
                          const std::string& what, std::string* key) {
  const double length = sc.sites.empty() ? 0 : sc.sites[0].length;
  if (key) *key = what;
  if (from.has_value() != to.has_value()) return "give both from and to (m along the belt), or neither";
  for (const auto& [v, name] : {std::pair{from, "from"}, std::pair{to, "to"}})
    if (v && !(*v >= 0 && *v <= length)) {
      if (key) *key = what + "." + name;
      return "must be in [0, " + rounded_text(length) +
             "] m, the length the belt coordinate s runs over (scene:info()'s "
             "s_length) (got " +
             rounded_text(*v) + " m)";
    }
  return "";
}

void check_range(lua_State* L, const Scene& sc, std::optional<double> from, std::optional<double> to,
                 const std::string& what) {
  std::string key;
  if (const std::string bad = range_problem(sc, from, to, what, &key); !bad.empty()) fail_on(L, key, bad);
}

bool in_stretch(const ElementSite& site, double from, double to) {
  return from <= to ? (site.s >= from && site.s <= to) : (site.s >= from || site.s <= to);
}

std::string wet_text(std::optional<double> mu, std::optional<double> from, std::optional<double> to,
                     std::optional<double> transition) {
  // (six significant digits: a text to read, in a plot's event line among others)
  std::ostringstream text;
  text << "mu = ";
  if (mu)
    text << *mu;
  else
    text << "function";
  if (from) text << " on s in [" << *from << ", " << *to << "] m";
  if (transition && *transition > 0) text << ", transition " << *transition << " m";
  return text.str();
}

std::vector<double> mu_over(lua_State* L, int mu_idx, const Scene& sc, std::optional<double> from,
                            std::optional<double> to, const std::string& what) {
  mu_idx = lua_absindex(L, mu_idx);
  check_range(L, sc, from, to, what);
  if (lua_type(L, mu_idx) != LUA_TNUMBER && !lua_isfunction(L, mu_idx))
    fail_on(L, what + ".mu", std::string("number or function(site) expected, got ") + type_name(L, mu_idx));
  std::vector<double> out(sc.sites.size(), std::nan(""));
  for (const ElementSite& site : sc.sites) {
    if (from && !in_stretch(site, *from, *to)) continue;
    double mu = 0;
    if (lua_isfunction(L, mu_idx)) {
      std::string error;  // (raised after the call's C++ frame is left)
      try {
        mu = call_mu(L, mu_idx, site, what + ".mu");
      } catch (const LawError& e) {
        error = e.what();
      }
      if (!error.empty()) fail(L, error);  // (at the line of the key it names)
    } else {
      mu = lua_tonumber(L, mu_idx);
    }
    if (const std::string bad = mu_problem(mu, site.index); !bad.empty()) fail_on(L, what + ".mu", bad);
    out[site.index] = mu;
  }
  return out;
}

FrameSettings to_frames(lua_State* L, int idx, const std::string& w, const std::vector<std::string>& extra,
                        bool times_only) {
  idx = lua_absindex(L, idx);
  require_table(L, idx, w);
  std::vector<std::string> keys{"fps", "slowdown", "size", "quantity", "range", "levels", "magnify", "view", "png",
                                "png_every", "video", "t_start"};
  if (!extra.empty()) keys = extra;  // sim:show: its own list
  check_keys(L, idx, w, keys);
  FrameSettings f;
  if (auto v = opt_number(L, idx, "fps", w)) f.fps = *v;
  if (auto v = opt_number(L, idx, "slowdown", w)) f.slowdown = *v;
  if (auto v = opt_number(L, idx, "magnify", w)) f.magnify = *v;
  if (auto v = opt_number(L, idx, "t_start", w)) f.t_start = *v;
  if (field(L, idx, "levels")) f.levels = to_integer(L, -1, w + ".levels"), lua_pop(L, 1);
  if (field(L, idx, "png_every")) f.png_every = to_integer(L, -1, w + ".png_every"), lua_pop(L, 1);
  auto pair = [&](const char* key, const char* what) -> std::optional<std::pair<double, double>> {
    if (!field(L, idx, key)) return std::nullopt;
    if (!lua_istable(L, -1) || lua_rawlen(L, -1) != 2)
      fail_on(L, w + "." + key, std::string(what) + " expected, got " + type_name(L, -1));
    double a[2];
    for (int k = 0; k < 2; ++k) {
      lua_rawgeti(L, -1, k + 1);
      a[k] = to_number(L, -1, w + "." + key);
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
    return std::make_pair(a[0], a[1]);
  };
  if (auto s = pair("size", "{width, height} in pixels")) {
    // checked before the cast to int (a huge value would not fit)
    if (s->first != std::floor(s->first) || s->second != std::floor(s->second) || !(s->first >= 16 && s->first <= 8192) ||
        !(s->second >= 16 && s->second <= 8192)) {
      fail_on(L, w + ".size",
              std::string("whole numbers of pixels in 16..8192 expected (got {") + rounded_text(s->first) + ", " +
                  rounded_text(s->second) + "})");
    }
    f.width = static_cast<int>(s->first), f.height = static_cast<int>(s->second);
  }
  if (auto r = pair("range", "{lo, hi} in the quantity's unit")) f.range_lo = r->first, f.range_hi = r->second;
  if (auto q = opt_string(L, idx, "quantity", w)) {
    std::vector<std::string> names;
    bool found = false;
    for (const auto& i : frame_quantities()) {
      names.push_back(i.key);
      if (*q == i.key) f.quantity = i.q, found = true;
    }
    if (!found)
      fail_on(L, w + ".quantity",
              std::string("unknown quantity '") + *q + "'" + did_you_mean(*q, names) + "; one of: " + join(names));
  }
  if (field(L, idx, "view")) {
    require_table(L, -1, w + ".view");
    check_keys(L, -1, w + ".view", {"centre", "center", "width"});
    for (const char* k : {"centre", "center"})
      if (field(L, -1, k)) f.view_centre = to_vec2(L, -1, w + ".view." + k), lua_pop(L, 1);
    if (auto v = opt_number(L, lua_gettop(L), "width", w + ".view")) f.view_width = *v;
    lua_pop(L, 1);
  }
  // png = true: <out>/frames/; a string: that folder; video = true: <out>/frames.mp4
  auto output = [&](const char* key, const char* dflt) -> std::string {
    if (!field(L, idx, key)) return "";
    std::string r;
    if (lua_type(L, -1) == LUA_TBOOLEAN)
      r = lua_toboolean(L, -1) ? dflt : "";
    else if (lua_type(L, -1) == LUA_TSTRING)
      r = lua_tostring(L, -1);
    else
      fail_on(L, w + "." + key, std::string("true, false or a path expected, got ") + type_name(L, -1));
    // "" would be no output, or the output folder itself: refused rather than guessed (it read
    // "neither png nor video asked for", naming png for an empty video)
    if (lua_type(L, -1) == LUA_TSTRING && r.empty()) {
      fail_on(L, w + "." + key,
              std::string(key) == "png"
                  ? "an empty folder name (true for the folder frames, false or leave it out for no PNGs)"
                  : "an empty file name (true for frames.mp4, false or leave it out for no video)");
    }
    lua_pop(L, 1);
    return r;
  };
  f.png_dir = output("png", "frames");
  if (!extra.empty()) f.png_dir = ".";  // sim:show: one picture, written by its caller
  f.video_path = output("video", "frames.mp4");
  std::string error;
  KeyPath about;
  try {
    validate(f, times_only);
  } catch (const ParameterError& e) {
    // e names frames.<key>: its key under the table that holds these frames (run.frames.size,
    // start.frames.size; sim:show.size, which is no frames table)
    KeyPath key = e.path;
    if (!key.chain.empty()) key.chain.erase(key.chain.begin());
    const std::string name = w + "." + path_text(key);
    about = parse_path(name);
    error = parameter_message(name, e.reason, e.value, e.unit);
  }
  if (!error.empty()) fail_at(L, about, error);
  return f;
}

double wet_share(double s, double from, double to, double len, double tau) {
  const double span = from <= to ? to - from : len - from + to;
  if (span >= len) return 1.0;  // the whole loop: its two ends meet, no edge to ramp across
  double u = std::fmod(s - from, len);
  if (u < 0) u += len;
  const bool inside = u <= span;
  if (tau == 0) return inside ? 1.0 : 0.0;
  const double d = inside ? std::min(u, span - u) : -std::min(u - span, len - u);  // > 0 inside
  return std::clamp(0.5 + d / tau, 0.0, 1.0);
}

std::vector<double> wet_shares(const Scene& sc, double from, double to, double tau) {
  const double len = sc.sites.empty() ? 0 : sc.sites[0].length;
  std::vector<double> share(sc.sites.size(), 0.0);
  for (const ElementSite& site : sc.sites) share[site.index] = wet_share(site.s, from, to, len, tau);
  return share;
}

void check_transition(lua_State* L, const Scene& sc, double from, double to, double tau, const std::string& what) {
  const double len = sc.sites.empty() ? 0 : sc.sites[0].length;
  const double stretch = to >= from ? to - from : len - from + to;
  if (tau > stretch)
    fail_on(L, what + ".transition",
            "must be at most the stretch's length, " + rounded_text(stretch, 6) +
                " m, for its elements to reach the new mu (it ramps across the transition about each end) (got " +
                rounded_text(tau) + " m)");
}

std::optional<double> read_transition(lua_State* L, int idx, bool has_range, const std::string& what) {
  const auto transition = opt_number(L, idx, "transition", what);
  if (!transition) return transition;
  if (!has_range) fail_on(L, what + ".transition", "a transition needs the wet stretch's from and to [m]");
  if (!(*transition >= 0 && std::isfinite(*transition))) {
    fail_on(L, what + ".transition", std::string("must be >= 0 and finite (got ") + rounded_text(*transition) + " m)");
  }
  return transition;
}

namespace {

// run.events: { {t = 0.5, mu = 0.2, from = 0.3, to = 0.6, transition = 0.02}, {t = 0.8, mu = function(site) ... end} }
// Each event sets μ at time t on the elements whose start position s (belt coordinate, m, as in
// belt.mu functions) lies in [from, to] (wrapping round when from > to; the whole belt without
// them); mu is a number or a function of the element's site; with a transition [m] μ ramps from
// the belt's μ at time t to the new one across that length about each end (as sim:wet's).
std::vector<MuEvent> read_events(lua_State* L, int idx, const Scene& sc) {
  std::vector<MuEvent> out;
  require_table(L, idx, "run.events");
  check_sequence(L, idx, "run.events");
  const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, idx));
  for (lua_Integer k = 1; k <= n; ++k) {
    lua_geti(L, idx, k);
    const int e = lua_gettop(L);
    const std::string what = "run.events[" + std::to_string(k) + "]";
    require_table(L, e, what);
    check_keys(L, e, what, {"t", "mu", "from", "to", "transition"});
    MuEvent ev;
    const auto t = opt_number(L, e, "t", what);
    if (!t) fail_on(L, what + ".t", "the event's time is missing");
    if (const std::string bad = event_time_problem(*t); !bad.empty()) fail_on(L, what + ".t", bad);
    ev.t = *t;
    const auto from = opt_number(L, e, "from", what), to = opt_number(L, e, "to", what);
    const auto transition = read_transition(L, e, from.has_value(), what);
    if (!field(L, e, "mu")) fail_on(L, what + ".mu", "the new friction coefficient is missing");
    if (transition && *transition > 0) {
      // the new μ on every element the ramps reach, each with its share (wet_share)
      check_range(L, sc, from, to, what);
      check_transition(L, sc, *from, *to, *transition, what);
      ev.mu = mu_over(L, lua_gettop(L), sc, std::nullopt, std::nullopt, what);
      ev.share = wet_shares(sc, *from, *to, *transition);
      for (size_t i = 0; i < ev.mu.size(); ++i)
        if (ev.share[i] == 0) ev.mu[i] = std::nan("");
    } else {
      ev.mu = mu_over(L, lua_gettop(L), sc, from, to, what);
    }
    // a stretch that holds no element's start would change nothing, and events.csv would record a
    // wetting all the same (sim:wet answers "no element changed")
    if (std::all_of(ev.mu.begin(), ev.mu.end(), [](double mu) { return std::isnan(mu); }))
      fail_on(L, what,
              "the stretch [" + rounded_text(from.value_or(0)) + ", " + rounded_text(to.value_or(0)) +
                  "] m holds no element (an element is in it when its start s is): the event would change nothing; "
                  "widen it, or give from > to for a stretch across s = 0");
    // recorded as sim:wet and sim:set_mu record theirs (events.csv, the plots' event lines)
    ev.what = from ? "wet" : "set_mu";
    ev.text = wet_text(lua_type(L, -1) == LUA_TNUMBER ? std::optional<double>(lua_tonumber(L, -1)) : std::nullopt, from,
                       to, transition);
    lua_pop(L, 2);  // mu, the event table
    out.push_back(std::move(ev));
  }
  return out;
}

// probe = 12 (an element), {x, y} (a point in metres: the element that starts nearest it), or a
// list of these: { 12, 40, {0.29, 0.1} }. A table of two numbers is a point unless both are
// written as whole numbers without a decimal point (Lua integers): { 12, 40 } probes elements 12
// and 40, { 0.0, 0.1 } is a point.
std::vector<int> read_probes(lua_State* L, int v, const Scene& sc, const std::string& w) {
  if (!lua_istable(L, v)) return {to_integer(L, v, w)};
  auto is_int = [&](int k) {
    lua_rawgeti(L, v, k);
    const bool r = lua_isinteger(L, -1);
    lua_pop(L, 1);
    return r;
  };
  const size_t n = check_sequence(L, v, w).size();
  if (n == 0) fail_on(L, w, "an element number, a point {x, y} or a list of them expected, got an empty table");
  if (n == 2 && !(is_int(1) && is_int(2))) {
    bool numbers = true;
    for (int k = 1; k <= 2; ++k) {
      lua_rawgeti(L, v, k);
      numbers = numbers && lua_type(L, -1) == LUA_TNUMBER;
      lua_pop(L, 1);
    }
    if (numbers) return {sc.element_nearest(to_vec2(L, v, w))};
  }
  std::vector<int> out;
  for (size_t k = 1; k <= n; ++k) {
    lua_rawgeti(L, v, static_cast<lua_Integer>(k));
    const std::string wk = w + "[" + std::to_string(k) + "]";
    const int i = lua_istable(L, -1) ? sc.element_nearest(to_vec2(L, -1, wk)) : to_integer(L, -1, wk);
    lua_pop(L, 1);
    for (size_t j = 0; j < out.size(); ++j)
      if (out[j] == i)
        fail_on(L, wk,
                std::string("element ") + std::to_string(i) + " is probed already (entry " + std::to_string(j + 1) +
                    "); a point is written with decimals, e.g. {0.0, 0.1}");
    out.push_back(i);
  }
  return out;
}

// snapshots = { times = {t1, t2, ...}, every = dt } [s]
void read_snapshots(lua_State* L, int v, RunSettings& rs, const std::string& ww) {
  require_table(L, v, ww);
  check_keys(L, v, ww, {"times", "every"});
  if (field(L, v, "every")) {
    rs.snapshot_every = to_number(L, -1, ww + ".every");
    if (!(rs.snapshot_every > 0 && std::isfinite(rs.snapshot_every)))
      fail_on(L, ww + ".every",
              std::string("must be > 0 s and finite (got ") + rounded_text(rs.snapshot_every) + " s)");
    lua_pop(L, 1);
  }
  if (field(L, v, "times")) {
    const int tt = lua_gettop(L);
    require_table(L, tt, ww + ".times");
    const size_t n = check_sequence(L, tt, ww + ".times").size();
    for (size_t k = 1; k <= n; ++k) {
      lua_rawgeti(L, tt, static_cast<lua_Integer>(k));
      rs.snapshot_times.push_back(to_number(L, -1, ww + ".times[" + std::to_string(k) + "]"));
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
  }
  if (rs.snapshot_every == 0 && rs.snapshot_times.empty())
    fail_on(L, ww, "give times = {t1, t2, ...} [s] and/or every = dt [s]");
}

// the value at v of setting s (a key of scene:run{} or scene:start{}, sim/run_table.hpp), named
// w.<key>: a number, flag or text by its kind into its slot, checked at once by its rule; a list or
// table by its own reader
void read_setting(lua_State* L, int v, const Scene& sc, const RunSetting& s, RunSettings& rs, const std::string& w) {
  const std::string what = w + "." + std::string(s.key);
  const RunSlot slot = run_slot(s, rs);
  if (auto* x = std::get_if<double*>(&slot)) **x = to_number(L, v, what);
  if (auto* t = std::get_if<std::string*>(&slot)) **t = to_string(L, v, what);
  if (auto* f = std::get_if<bool*>(&slot)) {
    if (lua_type(L, v) != LUA_TBOOLEAN) fail_on(L, what, std::string("boolean expected, got ") + type_name(L, v));
    **f = lua_toboolean(L, v);
  }
  if (const std::string bad = run_problem(s, rs, true); !bad.empty())
    fail_at(L, KeyPath{"", {w, std::string(s.key)}}, what + ": " + bad);
  if (s.kind != RunKind::other) return;
  if (s.key == "probe")
    rs.probes = read_probes(L, v, sc, what);
  else if (s.key == "snapshots")
    read_snapshots(L, v, rs, what);
  else if (s.key == "events")
    rs.mu_events = read_events(L, v, sc);
  else if (s.key == "frames") {
    // (keep_states comes before frames in the table: with it, frames may give only the times)
    if (!(lua_type(L, v) == LUA_TBOOLEAN && !lua_toboolean(L, v)))
      rs.frames = to_frames(L, v, what, {}, rs.keep_states);
  } else {
    throw std::logic_error("scene:run: no reader for the run setting '" + std::string(s.key) + "'");
  }
}

}  // namespace

RunSettings read_run_settings(lua_State* L, int idx, const Scene& sc, Context* ctx, bool batch, bool* progress) {
  const std::string w = batch ? "run" : "start";
  RunSettings rs;
  rs.out_dir = ctx->default_out;
  if (!lua_isnoneornil(L, idx)) {
    idx = lua_absindex(L, idx);
    require_table(L, idx, w);
    check_keys(L, idx, w, run_keys(batch));
    for (const RunSetting& s : run_settings()) {
      if (!(s.where & (batch ? kRunKey : kStartKey)) || !field(L, idx, std::string(s.key).c_str())) continue;
      read_setting(L, lua_gettop(L), sc, s, rs, w);
      lua_pop(L, 1);
    }
  }
  const Overrides& o = ctx->overrides;
  // an event at or after the script's own t_end is a mistake in the script, as a snapshot time
  // after it is: refused with its line (one that --t-end shortens away is left out with a note,
  // drop_after_end)
  if (batch && !o.has("t_end"))
    for (size_t k = 0; k < rs.mu_events.size(); ++k)
      if (const std::string bad = event_time_problem(rs.mu_events[k].t, rs.t_end); !bad.empty())
        fail_on(L, w + ".events[" + std::to_string(k + 1) + "].t", bad);
  // --no-frames draws nothing; kept states stay at the frames' times
  if (o.no_frames && rs.keep_states && rs.frames) rs.frames->png_dir.clear(), rs.frames->video_path.clear();
  if (o.no_frames && !rs.keep_states) rs.frames.reset();
  // the frames' recorder, made as the run opens its outputs, said once there when the frames'
  // size is too small for their text
  rs.frame_factory = [](const Scene& scene, const FrameSettings& f) {
    if (const std::string small = render::frame_size_problem(scene, f); !small.empty())
      say("beltsim: warning: frames.size %s\n", small.c_str());
    return render::make_frame_recorder(scene, f);
  };
  // the command line's settings over the script's (checked when they were read, app/options.cpp)
  for (const std::string& key : o.given) copy_run_setting(*find_run_setting(key), o.run, rs);
  // the check's warning while the run goes on (sim/run_check.hpp)
  rs.on_warning = [](const std::string& m) { say("beltsim: warning: %s\n", m.c_str()); };
  // the files of the run lie where the sandbox lets the script's own files lie
  if (const std::string r = run_paths_refusal(*ctx, w, rs); !r.empty()) fail(L, r);
  // a second run into a folder this command has run into replaces the first one's outputs: said,
  // as the console's scenario's run, replaced by a simulation a dofile at the prompt started
  // without out, was not. (A folder holds one run's outputs, docs/outputs.md.) The folders are
  // those of runs whose outputs opened (record_run_dir), not of runs refused before; said once
  // the run holds the folder, so that a folder in use is refused alone
  if (ctx->run_dirs.count(run_dir_key(rs.out_dir)))
    rs.on_claimed = [warn = rs.on_warning,
                     m = w + ": the output folder " + rs.out_dir +
                         " holds the outputs of an earlier run of this command, which this one replaces (" +
                         (ctx->overrides.has("out")
                              ? std::string("--out puts every run of the script into that one folder: "
                                            "leave it out and give each run its own out = ...")
                              : std::string("give each run its own folder: out = ..., or --out")) +
                         ")"] { warn(m); };
  if (progress) *progress = rs.progress;
  return rs;
}

std::string run_dir_key(const std::string& out_dir) {
  std::error_code ec;
  std::filesystem::path dir = std::filesystem::absolute(out_dir, ec).lexically_normal();
  if (ec) return out_dir;
  if (!dir.has_filename()) dir = dir.parent_path();  // "out/two/" is "out/two"
  return dir.string();
}

void record_run_dir(Context* ctx, const std::string& out_dir) {
  ctx->run_dirs.insert(run_dir_key(out_dir));
}

void end_if_probing(lua_State* L, Context* ctx, const char* call) {
  if (!ctx || !ctx->capture || !ctx->capture->until_run) return;
  luaL_where(L, 1);
  ctx->capture->run_at = lua_tostring(L, -1) + std::string(call);
  ctx->captured = true;
  lua_pushliteral(L, "scene captured");
  lua_error(L);
}

void refuse_if_capturing(lua_State* L, Context* ctx, const char* call) {
  if (!ctx || !ctx->capture || ctx->capture->until_run) return;
  const std::string& cmd = ctx->capture->command;
  luaL_error(L,
             "%s: beltsim %s takes the scene and settings of a batch run, scene:run{}, and this script runs a live "
             "simulation here; nothing was run. To measure it, write its run as scene:run{ t_end = ..., events = "
             "{...} } (the changes at known times: docs/lua-api.md, scene:run's events)",
             call, cmd.c_str());
}

void end_if_stopped(lua_State* L, const Context* ctx, const char* call) {
  if (!ctx || !(ctx->stop_made || (ctx->stop && ctx->stop->load(std::memory_order_relaxed)))) return;
  luaL_error(L, "%s: not run: Ctrl-C (or SIGTERM) stopped a run earlier in this script or console command", call);
}

void push_check(lua_State* L, const CheckEstimate& c) {
  lua_createtable(L, 0, 10);
  lua_pushnumber(L, c.err_speed), lua_setfield(L, -2, "speed");
  lua_pushnumber(L, c.err_tension), lua_setfield(L, -2, "tension");
  lua_pushnumber(L, c.speed_limit()), lua_setfield(L, -2, "limit_speed");
  lua_pushnumber(L, c.tension_limit()), lua_setfield(L, -2, "limit_tension");
  lua_pushboolean(L, c.over()), lua_setfield(L, -2, "over");
  lua_pushboolean(L, c.near()), lua_setfield(L, -2, "near");
  lua_pushnumber(L, c.steps_ratio), lua_setfield(L, -2, "steps_ratio");
  lua_pushboolean(L, c.shared()), lua_setfield(L, -2, "shared");
  if (c.warned_t >= 0) lua_pushnumber(L, c.warned_t), lua_setfield(L, -2, "warned_t");
  if (!c.failed.empty()) lua_pushstring(L, c.failed.c_str()), lua_setfield(L, -2, "failed");
  // named, with the units of a run result's check (io/units.cpp kRunResult), which the console
  // prints (lua_check.hpp, kUnitsField): its tension is a relative error, not a force in N
  if (luaL_newmetatable(L, kCheckTable)) {
    lua_newtable(L);
    for (const auto& [field, unit] : run_result_units("check."))
      lua_pushstring(L, unit.c_str()), lua_setfield(L, -2, field.c_str());
    lua_setfield(L, -2, kUnitsField);
  }
  lua_setmetatable(L, -2);
}

std::string wall_limit_text(double limit, double t, double target, const std::string& outputs, bool option) {
  return "stopped at its wall-time limit (" + std::string(option ? "--max-wall " : "max_wall = ") +
         rounded_text(limit) + " s) at t = " + rounded_text(t) + " s of " + rounded_text(target) +
         " s; the outputs up to then are in " + outputs;
}

std::string samples_note(const std::string& out_dir) {
  return " (the samples up to then are in " + (std::filesystem::path(out_dir) / "timeseries.csv").string() + ")";
}

// beltsim.stop_at(t): the next run that would pass t stops there, as Ctrl-C stops it, and later
// runs are refused until beltsim.stop_at() (without t), which also drops a stop not reached
int l_stop_at(lua_State* L) {
  check_args(L, "beltsim.stop_at", {{"t", kNumber, true}});
  auto* ctx = static_cast<Context*>(lua_touserdata(L, lua_upvalueindex(1)));
  if (ctx->stop_made) ctx->interrupted = false;  // its own stop, not one that ends `beltsim run` with 130
  ctx->stop_made = false;
  ctx->stop_at.reset();
  if (!lua_isnoneornil(L, 1)) ctx->stop_at = lua_tonumber(L, 1);
  return 0;
}

namespace {
// "[lo, hi]" or "v" when lo == hi
std::string value_range(double lo, double hi) {
  return lo == hi ? rounded_text(lo, 6) : "[" + rounded_text(lo, 6) + ", " + rounded_text(hi, 6) + "]";
}
}  // namespace

bool changes_mu(const std::vector<double>& before, const std::vector<double>& mu) {
  for (size_t i = 0; i < mu.size(); ++i)
    if (!std::isnan(mu[i]) && mu[i] != before[i]) return true;
  return false;
}

std::string mu_change_text(Simulation& s, const std::vector<double>& before, const std::vector<double>& mu,
                           const std::string& what) {
  const Model& m = s.model();
  const int n = static_cast<int>(mu.size());
  int addressed = 0, changed = 0;
  std::vector<int> on(m.pulleys.size() + 1, 0);  // per pulley, last: free
  // μ before of the elements addressed (lo_a, hi_a) and of those that changed (lo0, hi0); after (lo1, hi1)
  double lo_a = INFINITY, hi_a = -INFINITY, lo0 = INFINITY, hi0 = -INFINITY, lo1 = INFINITY, hi1 = -INFINITY;
  for (int i = 0; i < n; ++i) {
    if (std::isnan(mu[i])) continue;
    ++addressed;
    lo_a = std::min(lo_a, before[i]), hi_a = std::max(hi_a, before[i]);
    if (mu[i] == before[i]) continue;
    ++changed;
    const int p = s.element(i).pulley;
    ++on[p >= 0 ? p : on.size() - 1];
    lo0 = std::min(lo0, before[i]), hi0 = std::max(hi0, before[i]);
    lo1 = std::min(lo1, mu[i]), hi1 = std::max(hi1, mu[i]);
  }
  std::string text;
  if (changed == 0) {
    text = what + ": no element changed";
    if (addressed > 0)
      text += " (the " + std::to_string(addressed) + " it sets already had mu " + value_range(lo_a, hi_a) + ")";
  } else {
    std::vector<std::string> where;
    for (size_t p = 0; p < on.size(); ++p)
      if (on[p] > 0)
        where.push_back(std::to_string(on[p]) + (p + 1 < on.size() ? " on " + m.pulleys[p].name : " free"));
    text = what + ": " + std::to_string(changed) + " of " + std::to_string(n) + " elements (" + join(where) + "), mu " +
           value_range(lo0, hi0) + " -> " + value_range(lo1, hi1);
  }
  return text;
}

}  // namespace beltsim::script
