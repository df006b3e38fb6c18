// Lua bindings of the scene (see lua_scene.hpp). Tables in, SceneDef / RunSettings out; every
// key is checked (a misspelt key is an error naming the valid ones), every value's type too,
// and the scene is validated when it is built, so a bad scenario stops before simulating with
// "file:line: reason (got value unit)".
//
// Debian's liblua5.4-c++ is Lua compiled as C++: lua_error unwinds with a C++ exception, so the
// destructors of the C++ objects below run. C++ exceptions of our own are caught and turned into
// Lua errors only after their catch block has been left (as LÖVE does).
#include "script/lua_scene.hpp"

#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "integrate/stepper.hpp"
#include "io/suggest.hpp"
#include "render/recorder.hpp"
#include "scene/validate.hpp"
#include "script/context.hpp"
#include "script/lua_api.hpp"
#include "script/lua_law.hpp"
#include "script/lua_sim.hpp"
#include "script/progress.hpp"
#include "script/sandbox.hpp"

namespace beltsim::script {

namespace {
constexpr const char* kSceneMeta = "beltsim.Scene";
}  // namespace

const Scene* check_scene(lua_State* L, int idx, const char* method) {
  auto** box = static_cast<Scene**>(luaL_testudata(L, idx, kSceneMeta));
  if (!box) fail(L, std::string("scene:") + method + ": call it as scene:" + method + "(...) on a scene");
  if (!*box) fail(L, std::string("scene:") + method + ": this scene has been finalised");
  return *box;
}

void push_site(lua_State* L, const ElementSite& e) {
  lua_createtable(L, 0, 8);
  lua_pushinteger(L, e.index), lua_setfield(L, -2, "index");
  lua_pushnumber(L, e.centre.x()), lua_setfield(L, -2, "x");
  lua_pushnumber(L, e.centre.y()), lua_setfield(L, -2, "y");
  lua_pushnumber(L, e.s), lua_setfield(L, -2, "s");
  lua_pushnumber(L, e.length), lua_setfield(L, -2, "length");
  if (!e.pulley.empty()) lua_pushstring(L, e.pulley.c_str()), lua_setfield(L, -2, "pulley");
  for (const auto& [name, table] : {std::pair{"meets", &e.meets}, std::pair{"leaves", &e.leaves}}) {
    lua_createtable(L, 0, static_cast<int>(table->size()));
    for (const auto& [k, v] : *table) lua_pushnumber(L, v), lua_setfield(L, -2, k.c_str());
    lua_setfield(L, -2, name);
  }
}


namespace {

PulleyDef to_pulley(lua_State* L, int idx, const std::string& what, Context* ctx) {
  idx = lua_absindex(L, idx);
  require_table(L, idx, what);
  check_keys(L, idx, what, {"name", "centre", "center", "radius", "inertia", "wrap", "torque", "speed"});
  PulleyDef p;
  const auto name = opt_string(L, idx, "name", what);
  if (!name) fail(L, what + ": a name is required");
  p.name = *name;
  const std::string w = "pulley '" + p.name + "'";
  bool centred = false;
  if (has(L, idx, "centre") && has(L, idx, "center")) fail(L, w + ": give centre or center, not both");
  for (const char* key : {"centre", "center"})
    if (field(L, idx, key)) {
      p.centre = to_vec2(L, -1, w + " " + key);
      lua_pop(L, 1);
      centred = true;
    }
  if (!centred) fail(L, w + ": a centre {x, y} [m] is required");
  if (auto v = opt_number(L, idx, "radius", w)) p.radius = *v;
  if (auto v = opt_number(L, idx, "inertia", w)) p.inertia = *v;
  if (auto v = opt_string(L, idx, "wrap", w)) {
    if (*v == "inside")
      p.wrap = WrapSide::inside;
    else if (*v == "back")
      p.wrap = WrapSide::back;
    else
      fail(L, w + ".wrap: 'inside' or 'back' expected, got '" + *v + "'");
  }
  if (field(L, idx, "torque")) {
    p.torque = to_law(L, -1, w + ".torque", false, ctx);
    lua_pop(L, 1);
  }
  if (field(L, idx, "speed")) {
    p.speed = to_law(L, -1, w + ".speed", true, ctx);
    p.kinematic = true;
    lua_pop(L, 1);
  }
  return p;
}

// a Lua function kept alive in the registry while the scene is built
void read_belt(lua_State* L, int idx, BeltDef& b, std::unique_ptr<LuaRef>& mu_fn) {
  const std::string w = "belt";
  require_table(L, idx, w);
  check_keys(L, idx, w,
             {"elements", "pretension", "rest_length", "strain", "direction", "route", "EA", "EI", "axial_damping",
              "bending_damping", "bending_viscosity", "sde", "e_tra", "e_tor", "mass_per_length", "mu"});
  if (field(L, idx, "elements")) {
    b.elements = to_integer(L, -1, "belt.elements");
    lua_pop(L, 1);
  }
  {  // the tension at rest: exactly one of three ways (the paper's 500 N pretension when none)
    const int ways = has(L, idx, "pretension") + has(L, idx, "rest_length") + has(L, idx, "strain");
    if (ways > 1) fail(L, "belt: give one of pretension [N], rest_length [m] or strain, not " + std::to_string(ways));
  }
  if (auto v = opt_number(L, idx, "pretension", w)) b.pretension = *v;
  if (auto v = opt_number(L, idx, "rest_length", w)) b.rest_length = *v, b.tensioning = Tensioning::rest_length;
  if (auto v = opt_number(L, idx, "strain", w)) b.strain = *v, b.tensioning = Tensioning::strain;
  if (auto v = opt_string(L, idx, "direction", w)) {
    if (*v == "cw")
      b.loop_sense = -1;
    else if (*v == "ccw")
      b.loop_sense = 1;
    else
      fail(L, "belt.direction: 'cw' or 'ccw' expected, got '" + *v + "'");
  }
  if (field(L, idx, "route")) {
    const int r = lua_gettop(L);
    require_table(L, r, "belt.route");
    check_sequence(L, r, "belt.route");
    if (lua_rawlen(L, r) < 2) fail(L, "belt.route: at least two pulley names expected (leave route out for the order of pulleys)");
    for (lua_Integer k = 1; k <= static_cast<lua_Integer>(lua_rawlen(L, r)); ++k) {
      lua_rawgeti(L, r, k);
      if (lua_type(L, -1) != LUA_TSTRING) fail(L, "belt.route: pulley names expected, got " + std::string(type_name(L, -1)));
      b.route.push_back(lua_tostring(L, -1));
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
  }
  const bool rigidities = has(L, idx, "EA") || has(L, idx, "EI") || has(L, idx, "axial_damping") ||
                          has(L, idx, "bending_damping") || has(L, idx, "bending_viscosity");
  if (has(L, idx, "bending_damping") && has(L, idx, "bending_viscosity"))
    fail(L, "belt: give bending_damping [N·m·s/rad per SDE] or bending_viscosity [N·m²·s per length], not both");
  if (auto v = opt_number(L, idx, "EA", w)) b.EA = *v;
  if (auto v = opt_number(L, idx, "EI", w)) b.EI = *v;
  if (auto v = opt_number(L, idx, "axial_damping", w)) b.axial_damping = *v;
  if (auto v = opt_number(L, idx, "bending_damping", w)) b.bending_damping = *v;
  if (auto v = opt_number(L, idx, "bending_viscosity", w)) b.bending_viscosity = *v;
  if (field(L, idx, "sde")) {
    if (rigidities) fail(L, "belt: give either rigidities (EA, EI, axial_damping, bending_damping or bending_viscosity) or per-SDE values (sde), not both");
    const int s = lua_gettop(L);
    require_table(L, s, "belt.sde");
    check_keys(L, s, "belt.sde", {"k", "c", "kt", "ct"});
    b.reading = StiffnessReading::per_sde;
    for (auto [key, dst] : {std::pair{"k", &b.k}, std::pair{"c", &b.c}, std::pair{"kt", &b.kt}, std::pair{"ct", &b.ct}}) {
      const auto v = opt_number(L, s, key, "belt.sde");
      if (!v) fail(L, std::string("belt.sde: all of k, c, kt, ct are required (") + key + " is missing)");
      *dst = *v;
    }
    lua_pop(L, 1);
  }
  if (auto v = opt_number(L, idx, "e_tra", w)) b.e_tra = *v;
  if (auto v = opt_number(L, idx, "e_tor", w)) b.e_tor = *v;
  if (auto v = opt_number(L, idx, "mass_per_length", w)) b.mass_per_length = *v;
  if (field(L, idx, "mu")) {
    const int m = lua_gettop(L);
    if (lua_type(L, m) == LUA_TNUMBER) {
      b.mu = lua_tonumber(L, m);
    } else if (lua_isfunction(L, m)) {
      mu_fn = std::make_unique<LuaRef>(L, m);
      LuaRef* ref = mu_fn.get();
      b.mu_at = [ref](const ElementSite& site) {
        lua_State* S = ref->L;
        lua_rawgeti(S, LUA_REGISTRYINDEX, ref->ref);
        push_site(S, site);
        lua_call(S, 1, 1);
        if (lua_type(S, -1) != LUA_TNUMBER)
          luaL_error(S, "belt.mu function: number expected for element %d, got %s", site.index, luaL_typename(S, -1));
        const double mu = lua_tonumber(S, -1);
        lua_pop(S, 1);
        return mu;
      };
    } else if (lua_istable(L, m)) {
      check_sequence(L, m, "belt.mu");
      if (lua_rawlen(L, m) == 0) fail(L, "belt.mu: an empty list; give a number, one μ per element, or a function(site)");
      for (lua_Integer k = 1; k <= static_cast<lua_Integer>(lua_rawlen(L, m)); ++k) {
        lua_rawgeti(L, m, k);
        b.mu_per_element.push_back(to_number(L, -1, "belt.mu entry " + std::to_string(k)));
        lua_pop(L, 1);
      }
    } else {
      fail(L, std::string("belt.mu: number, list or function expected, got ") + type_name(L, m));
    }
    lua_pop(L, 1);
  }
}


// the string keys of the table at idx, as prefix..key, into `given` (SceneDef::given)
void note_given(lua_State* L, int idx, const std::string& prefix, std::set<std::string>& given) {
  idx = lua_absindex(L, idx);
  lua_pushnil(L);
  while (lua_next(L, idx)) {
    lua_pop(L, 1);
    if (lua_type(L, -1) == LUA_TSTRING) given.insert(prefix + lua_tostring(L, -1));
  }
}

// the run's first lines: the defaults a scene took, and the tension a given rest length gives
void report_scene(const Scene& sc, Tensioning tensioning) {
  std::string taken;
  for (const SceneInput& in : sc.inputs) {
    if (in.given) continue;
    std::ostringstream v;
    v << in.name << " = ";
    if (in.text.empty())
      v << in.value << (in.unit.empty() ? "" : " ") << in.unit;
    else
      v << in.text;
    taken += (taken.empty() ? "" : ", ") + v.str();
  }
  if (!taken.empty())
    std::fprintf(stderr, "beltsim: scene defaults (not given; parameters.csv says where each comes from): %s\n",
                 taken.c_str());
  if (tensioning != Tensioning::pretension) {
    const Belt& b = sc.model.belt;
    std::fprintf(stderr, "beltsim: belt: rest length %.6g m on a %.6g m route (strain %.4g %%): static span tension %.6g N\n",
                 b.rigid_length * b.n, sc.route.length, 100 * (b.pitch / b.rigid_length - 1), sc.static_tension);
  }
}

// beltsim.scene{ pulleys = {...}, belt = {...}, contact = {...}, friction = {...}, gravity = g, energy = bool }
int l_scene(lua_State* L) {
  check_args(L, "beltsim.scene", {{"{pulleys, belt, ...}", kTable}});
  check_keys(L, 1, "scene", {"pulleys", "belt", "contact", "friction", "gravity", "energy", "allow_large"});
  auto* ctx = static_cast<Context*>(lua_touserdata(L, lua_upvalueindex(1)));
  SceneDef d;
  if (!field(L, 1, "pulleys")) fail(L, "scene: a list of pulleys is required");
  require_table(L, -1, "scene.pulleys");
  const int pl = lua_gettop(L);
  for (lua_Integer k = 1; k <= static_cast<lua_Integer>(lua_rawlen(L, pl)); ++k) {
    lua_rawgeti(L, pl, k);
    d.pulleys.push_back(to_pulley(L, -1, "pulley " + std::to_string(k), ctx));
    note_given(L, -1, "pulley." + d.pulleys.back().name + ".", d.given);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  std::unique_ptr<LuaRef> mu_fn;
  if (field(L, 1, "belt")) {
    read_belt(L, lua_gettop(L), d.belt, mu_fn);
    note_given(L, -1, "belt.", d.given);
    if (field(L, -1, "sde")) note_given(L, -1, "belt.sde.", d.given), lua_pop(L, 1);
    lua_pop(L, 1);
  }
  if (field(L, 1, "contact")) {
    const int c = lua_gettop(L);
    require_table(L, c, "contact");
    check_keys(L, c, "contact",
               {"c1", "c2", "damping", "p_max", "c1_per_length", "c2_per_length", "damping_per_length"});
    // each constant per element (the paper's) or per metre of pitch, not both
    for (const char* k : {"c1", "c2", "damping"})
      if (has(L, c, k) && has(L, c, (std::string(k) + "_per_length").c_str()))
        fail(L, std::string("contact: give ") + k + " (per element) or " + k + "_per_length (per metre of belt), not both");
    if (auto v = opt_number(L, c, "c1", "contact")) d.contact.c1 = *v;
    if (auto v = opt_number(L, c, "c2", "contact")) d.contact.c2 = *v;
    if (auto v = opt_number(L, c, "damping", "contact")) d.contact.b = *v;
    if (auto v = opt_number(L, c, "p_max", "contact")) d.contact.p_max = *v;
    if (auto v = opt_number(L, c, "c1_per_length", "contact")) d.contact_per_length.c1 = *v;
    if (auto v = opt_number(L, c, "c2_per_length", "contact")) d.contact_per_length.c2 = *v;
    if (auto v = opt_number(L, c, "damping_per_length", "contact")) d.contact_per_length.b = *v;
    note_given(L, c, "contact.", d.given);
    lua_pop(L, 1);
  }
  if (field(L, 1, "friction")) {
    const int f = lua_gettop(L);
    require_table(L, f, "friction");
    check_keys(L, f, "friction", {"dv"});
    if (auto v = opt_number(L, f, "dv", "friction")) d.friction.dv = *v;
    note_given(L, f, "friction.", d.given);
    lua_pop(L, 1);
  }
  note_given(L, 1, "", d.given);
  if (auto v = opt_number(L, 1, "gravity", "scene")) d.gravity = *v;
  if (auto v = opt_bool(L, 1, "energy", "scene")) d.track_energy = *v;
  if (auto v = opt_bool(L, 1, "allow_large", "scene")) d.allow_large = *v;

  auto** box = static_cast<Scene**>(lua_newuserdatauv(L, sizeof(Scene*), 0));
  *box = nullptr;
  luaL_setmetatable(L, kSceneMeta);
  std::string error;
  try {
    *box = new Scene(build_scene(d, ctx ? ctx->stop : nullptr));
  } catch (const ParameterError& e) {
    error = e.what();
  } catch (const BuildInterrupted& e) {
    ctx->interrupted = true;
    error = e.what();
  } catch (const std::exception& e) {  // a Lua law that failed while the static state was sought
    error = e.what();
  }
  if (!error.empty()) fail(L, error);
  report_scene(**box, d.belt.tensioning);
  return 1;
}

int l_scene_gc(lua_State* L) {
  auto** box = static_cast<Scene**>(luaL_checkudata(L, 1, kSceneMeta));
  delete *box;
  *box = nullptr;
  return 0;
}

// scene:info() -> table of the derived model parameters
int l_scene_info(lua_State* L) {
  const Scene* sc = check_scene(L, 1, "info");
  check_args(L, "scene:info", {}, 2);
  const Belt& b = sc->model.belt;
  lua_newtable(L);
  auto num = [&](const char* k, double v) { lua_pushnumber(L, v), lua_setfield(L, -2, k); };
  lua_pushinteger(L, b.n), lua_setfield(L, -2, "elements");
  num("pitch", b.pitch);
  num("rigid_length", b.rigid_length);
  num("rest_length", b.rigid_length * b.n);
  num("strain", b.pitch / b.rigid_length - 1);
  num("mass", b.mass);
  num("k", b.k);
  num("c", b.c);
  num("kt", b.kt);
  num("ct", b.ct);
  num("route_length", sc->route.length);
  num("static_tension", sc->static_tension);
  num("static_residual", sc->static_residual);
  lua_newtable(L);
  for (size_t k = 0; k < sc->route_names.size(); ++k)
    lua_pushnumber(L, sc->route.arcs[k].angle * 180 / M_PI), lua_setfield(L, -2, sc->route_names[k].c_str());
  lua_setfield(L, -2, "wrap_deg");
  return 1;
}

// scene:element_near{x, y} -> number of the element whose centre starts nearest the point
int l_scene_element_near(lua_State* L) {
  const Scene* sc = check_scene(L, 1, "element_near");
  check_args(L, "scene:element_near", {{"{x, y}", kTable}}, 2);
  const Vec2 p = to_vec2(L, 2, "element_near");
  lua_pushinteger(L, sc->element_nearest(p));
  return 1;
}

// run.events: { {t = 0.5, mu = 0.2, from = 0.3, to = 0.6}, {t = 0.8, mu = function(site) ... end} }
// Each event sets μ at time t on the elements whose start position s (belt coordinate, m, as in
// belt.mu functions) lies in [from, to] (wrapping round when from > to; the whole belt without
// them); mu is a number or a function of the element's site.
}  // namespace

std::vector<double> mu_over(lua_State* L, int mu_idx, const Scene& sc, std::optional<double> from,
                            std::optional<double> to, const std::string& what) {
  mu_idx = lua_absindex(L, mu_idx);
  const double length = sc.sites.empty() ? 0 : sc.sites[0].length;
  if (from.has_value() != to.has_value()) fail(L, what + ": give both from and to (m along the belt), or neither");
  for (const auto& [v, name] : {std::pair{from, "from"}, std::pair{to, "to"}})
    if (v && !(*v >= 0 && *v <= length)) {
      std::ostringstream m;
      m << what << "." << name << ": must be in [0, " << length << "] m, the belt's length (got " << *v << " m)";
      fail(L, m.str());
    }
  if (lua_type(L, mu_idx) != LUA_TNUMBER && !lua_isfunction(L, mu_idx))
    fail(L, what + ".mu: number or function(site) expected, got " + type_name(L, mu_idx));
  std::vector<double> out(sc.sites.size(), std::nan(""));
  for (const ElementSite& site : sc.sites) {
    if (from) {
      const bool in = *from <= *to ? (site.s >= *from && site.s <= *to) : (site.s >= *from || site.s <= *to);
      if (!in) continue;
    }
    double mu = 0;
    if (lua_isfunction(L, mu_idx)) {
      lua_pushvalue(L, mu_idx);
      push_site(L, site);
      lua_call(L, 1, 1);
      mu = to_number(L, -1, what + ".mu(site) for element " + std::to_string(site.index));
      lua_pop(L, 1);
    } else {
      mu = lua_tonumber(L, mu_idx);
    }
    if (!(mu >= 0 && std::isfinite(mu))) {
      std::ostringstream m;
      m << what << ".mu: must be >= 0 and finite (got " << mu << " for element " << site.index << ")";
      fail(L, m.str());
    }
    out[site.index] = mu;
  }
  return out;
}

// run.events: { {t = 0.5, mu = 0.2, from = 0.3, to = 0.6}, {t = 0.8, mu = function(site) ... end} }
// Each event sets μ at time t on the elements whose start position s (belt coordinate, m, as in
// belt.mu functions) lies in [from, to] (wrapping round when from > to; the whole belt without
// them); mu is a number or a function of the element's site.
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
    check_keys(L, e, what, {"t", "mu", "from", "to"});
    MuEvent ev;
    const auto t = opt_number(L, e, "t", what);
    if (!t) fail(L, what + ".t: the event's time is missing");
    if (!(*t > 0 && std::isfinite(*t))) fail(L, what + ".t: must be > 0 and finite (got " + std::to_string(*t) + " s)");
    ev.t = *t;
    const auto from = opt_number(L, e, "from", what), to = opt_number(L, e, "to", what);
    if (!field(L, e, "mu")) fail(L, what + ".mu: the new friction coefficient is missing");
    ev.mu = mu_over(L, lua_gettop(L), sc, from, to, what);
    std::ostringstream text;
    text << "scheduled: mu = ";
    if (lua_type(L, -1) == LUA_TNUMBER)
      text << lua_tonumber(L, -1);
    else
      text << "function";
    if (from) text << " on s in [" << *from << ", " << *to << "] m";
    ev.what = "event";
    ev.text = text.str();
    lua_pop(L, 2);  // mu, the event table
    out.push_back(std::move(ev));
  }
  return out;
}

FrameSettings to_frames(lua_State* L, int idx, const std::string& w, const std::vector<std::string>& extra) {
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
    if (!lua_istable(L, -1) || lua_rawlen(L, -1) != 2) fail(L, w + "." + key + ": " + what + " expected, got " + type_name(L, -1));
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
      std::ostringstream m;
      m << w << ".size: whole numbers of pixels in 16..8192 expected (got {" << s->first << ", " << s->second << "})";
      fail(L, m.str());
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
    if (!found) fail(L, w + ".quantity: unknown quantity '" + *q + "'" + did_you_mean(*q, names) + "; one of: " + join(names));
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
      fail(L, w + "." + key + ": true, false or a path expected, got " + type_name(L, -1));
    lua_pop(L, 1);
    return r;
  };
  f.png_dir = output("png", "frames");
  if (!extra.empty()) f.png_dir = ".";  // sim:show: one picture, written by its caller
  f.video_path = output("video", "frames.mp4");
  std::string error;
  try {
    validate(f);
  } catch (const std::invalid_argument& e) {
    error = w.substr(0, w.rfind('.') == std::string::npos ? 0 : w.rfind('.') + 1) + e.what();
  }
  if (!error.empty()) fail(L, error);
  return f;
}

// scene:run{ t_end=, integrator=, rtol=, atol=, sample=, out=, probe=, progress=, events=, frames= } -> result

namespace {

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
  if (n == 0) fail(L, w + ": an element number, a point {x, y} or a list of them expected, got an empty table");
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
        fail(L, wk + ": element " + std::to_string(i) + " is probed already (entry " + std::to_string(j + 1) +
                    "); a point is written with decimals, e.g. {0.0, 0.1}");
    out.push_back(i);
  }
  return out;
}

// the keys of scene:run{} and scene:start{} with their readers (one table: the key check and
// the reading cannot drift apart)
struct RunKey {
  const char* key;
  bool batch_only;
  void (*read)(lua_State* L, int v, const Scene& sc, RunSettings& rs, bool& progress, const std::string& w);
};
const RunKey kRunKeys[] = {
    {"t_end", true, [](lua_State* L, int v, const Scene&, RunSettings& rs, bool&, const std::string& w) {
       rs.t_end = to_number(L, v, w + ".t_end");
     }},
    {"integrator", false, [](lua_State* L, int v, const Scene&, RunSettings& rs, bool&, const std::string& w) {
       rs.integrator = to_string(L, v, w + ".integrator");
     }},
    {"rtol", false, [](lua_State* L, int v, const Scene&, RunSettings& rs, bool&, const std::string& w) {
       rs.rtol = to_number(L, v, w + ".rtol");
     }},
    {"atol", false, [](lua_State* L, int v, const Scene&, RunSettings& rs, bool&, const std::string& w) {
       rs.atol = to_number(L, v, w + ".atol");
       if (!(rs.atol > 0 && std::isfinite(rs.atol)))
         fail(L, w + ".atol: must be > 0 and finite (leave it out to mean rtol) (got " + std::to_string(rs.atol) + ")");
     }},
    {"sample", false, [](lua_State* L, int v, const Scene&, RunSettings& rs, bool&, const std::string& w) {
       rs.sample_dt = to_number(L, v, w + ".sample");
     }},
    {"out", false, [](lua_State* L, int v, const Scene&, RunSettings& rs, bool&, const std::string& w) {
       rs.out_dir = to_string(L, v, w + ".out");
     }},
    {"probe", false, [](lua_State* L, int v, const Scene& sc, RunSettings& rs, bool&, const std::string& w) {
       rs.probes = read_probes(L, v, sc, w + ".probe");
     }},
    {"snapshots", false, [](lua_State* L, int v, const Scene&, RunSettings& rs, bool&, const std::string& w) {
       const std::string ww = w + ".snapshots";
       require_table(L, v, ww);
       check_keys(L, v, ww, {"times", "every"});
       if (field(L, v, "every")) {
         rs.snapshot_every = to_number(L, -1, ww + ".every");
         if (!(rs.snapshot_every > 0 && std::isfinite(rs.snapshot_every)))
           fail(L, ww + ".every: must be > 0 s and finite (got " + std::to_string(rs.snapshot_every) + " s)");
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
         fail(L, ww + ": give times = {t1, t2, ...} [s] and/or every = dt [s]");
     }},
    {"progress", false, [](lua_State* L, int v, const Scene&, RunSettings&, bool& progress, const std::string& w) {
       if (lua_type(L, v) != LUA_TBOOLEAN) fail(L, w + ".progress: boolean expected, got " + type_name(L, v));
       progress = lua_toboolean(L, v);
     }},
    {"events", true, [](lua_State* L, int v, const Scene& sc, RunSettings& rs, bool&, const std::string&) {
       rs.mu_events = read_events(L, v, sc);
     }},
    {"max_wall", false, [](lua_State* L, int v, const Scene&, RunSettings& rs, bool&, const std::string& w) {
       rs.wall_limit = to_number(L, v, w + ".max_wall");
       if (!(rs.wall_limit > 0 && std::isfinite(rs.wall_limit)))
         fail(L, w + ".max_wall: must be > 0 s and finite (got " + std::to_string(rs.wall_limit) + ")");
     }},
    {"allow_large", false, [](lua_State* L, int v, const Scene&, RunSettings& rs, bool&, const std::string& w) {
       if (lua_type(L, v) != LUA_TBOOLEAN) fail(L, w + ".allow_large: boolean expected, got " + type_name(L, v));
       rs.allow_large = lua_toboolean(L, v);
     }},
    {"frames", false, [](lua_State* L, int v, const Scene&, RunSettings& rs, bool&, const std::string& w) {
       if (!(lua_type(L, v) == LUA_TBOOLEAN && !lua_toboolean(L, v))) rs.frames = to_frames(L, v, w + ".frames");
     }},
};

}  // namespace

RunSettings read_run_settings(lua_State* L, int idx, const Scene& sc, Context* ctx, bool batch, bool* progress) {
  const std::string w = batch ? "run" : "start";
  RunSettings rs;
  rs.out_dir = ctx->default_out;
  bool pr = true;
  if (!lua_isnoneornil(L, idx)) {
    idx = lua_absindex(L, idx);
    require_table(L, idx, w);
    std::vector<std::string> keys;
    for (const RunKey& k : kRunKeys)
      if (batch || !k.batch_only) keys.push_back(k.key);
    check_keys(L, idx, w, keys);
    for (const RunKey& k : kRunKeys) {
      if ((!batch && k.batch_only) || !field(L, idx, k.key)) continue;
      k.read(L, lua_gettop(L), sc, rs, pr, w);
      lua_pop(L, 1);
    }
  }
  const Overrides& o = ctx->overrides;
  if (o.no_frames) rs.frames.reset();
  rs.frame_factory = render::make_frame_recorder;
  if (o.out) rs.out_dir = *o.out;
  if (o.t_end) rs.t_end = *o.t_end;
  if (o.integrator) rs.integrator = *o.integrator;
  if (o.rtol) rs.rtol = *o.rtol;
  if (o.max_wall) rs.wall_limit = *o.max_wall;
  // the files of the run lie where the sandbox lets the script's own files lie
  if (const std::string r = run_paths_refusal(*ctx, w, rs); !r.empty()) fail(L, r);
  if (progress) *progress = pr;
  return rs;
}

namespace {

// scene:run{ t_end=, integrator=, rtol=, atol=, sample=, out=, probe=, progress=, events=, frames= } -> result
// = scene:start{...}, sim:run_to(t_end), sim:close()
int l_scene_run(lua_State* L) {
  const Scene* sc = check_scene(L, 1, "run");
  check_args(L, "scene:run", {{"{t_end, integrator, ...}", kTable, true}}, 2);
  auto* ctx = static_cast<Context*>(lua_touserdata(L, lua_upvalueindex(1)));
  bool progress = true;
  const RunSettings rs = read_run_settings(L, 2, *sc, ctx, true, &progress);
  warn_unread_args(*ctx);
  if (ctx->capture) {
    ctx->capture->scene = *sc;
    ctx->capture->settings = rs;
    ctx->captured = true;
    lua_pushliteral(L, "scene captured");
    return lua_error(L);
  }

  std::string error;
  RunResult res;
  try {
    ProgressLine line(progress);
    res = run(*sc, rs, ctx->stop, line.callback());
  } catch (const DivergenceError& e) {
    error = std::string(e.what()) + " (the samples up to then are in " + rs.out_dir + "/timeseries.csv)";
  } catch (const std::invalid_argument& e) {
    error = std::string("run.") + e.what();  // names the key: run.sample, run.frames.t_start, ...
  } catch (const std::exception& e) {
    error = e.what();
  }
  if (res.over_wall_limit) {
    // not silent: the outputs are finalised (run() closed them) and the script stops here
    std::ostringstream m;
    m.precision(10);
    m << "run.max_wall: the run passed its wall-time limit of " << rs.wall_limit << " s and stopped at t = "
      << res.t_reached << " s of t_end = " << rs.t_end << " s (the samples up to then are in " << res.csv_path << ")";
    error = m.str();
  }
  if (!error.empty()) fail(L, error);
  if (res.interrupted) ctx->interrupted = true;
  if (!res.warning_summary.empty()) std::fprintf(stderr, "beltsim: %s\n", res.warning_summary.c_str());

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
    lua_pushnumber(L, res.omega[j]), lua_setfield(L, -2, sc->model.pulleys[j].name.c_str());
  lua_setfield(L, -2, "omega");
  return 1;
}

// scene:start{ integrator=, rtol=, atol=, sample=, out=, probe=, progress=, frames= } -> sim at t = 0
int l_scene_start(lua_State* L) {
  const Scene* sc = check_scene(L, 1, "start");
  check_args(L, "scene:start", {{"{integrator, rtol, ...}", kTable, true}}, 2);
  auto* ctx = static_cast<Context*>(lua_touserdata(L, lua_upvalueindex(1)));
  bool progress = true;
  const RunSettings rs = read_run_settings(L, 2, *sc, ctx, false, &progress);
  warn_unread_args(*ctx);
  std::unique_ptr<Simulation> sim;
  std::string error;
  try {
    sim = std::make_unique<Simulation>(*sc, rs);
  } catch (const std::invalid_argument& e) {  // "key: reason"
    error = std::string("start.") + e.what();
  } catch (const std::exception& e) {  // an output that cannot be written, a folder in use
    error = std::string("start: ") + e.what();
  }
  if (!error.empty()) fail(L, error);
  push_simulation(L, std::move(sim), ctx, progress);
  return 1;
}
int l_scene_tostring(lua_State* L) {
  const Scene* sc = *static_cast<Scene**>(luaL_checkudata(L, 1, kSceneMeta));
  if (!sc) return lua_pushliteral(L, "beltsim scene (finalised)"), 1;
  lua_pushfstring(L, "beltsim scene: %d pulleys, %d elements", sc->model.n_p(), sc->model.n_el());
  return 1;
}

// beltsim.rpm(n) -> rad/s
int l_rpm(lua_State* L) {
  check_args(L, "beltsim.rpm", {{"n", kNumber}});
  lua_pushnumber(L, lua_tonumber(L, 1) * 2 * M_PI / 60);
  return 1;
}

int l_integrators(lua_State* L) {
  check_args(L, "beltsim.integrators", {});
  lua_newtable(L);
  int k = 1;
  for (const auto& n : integrator_names()) lua_pushstring(L, n.c_str()), lua_rawseti(L, -2, k++);
  return 1;
}

}  // namespace

void open_scene(lua_State* L, Context* ctx) {
  luaL_newmetatable(L, kSceneMeta);
  lua_pushcfunction(L, l_scene_gc), lua_setfield(L, -2, "__gc");
  lua_pushcfunction(L, l_scene_tostring), lua_setfield(L, -2, "__tostring");
  lua_pushliteral(L, "beltsim.Scene"), lua_setfield(L, -2, "__metatable");  // scripts cannot reach __gc
  lua_newtable(L);
  lua_pushcfunction(L, l_scene_info), lua_setfield(L, -2, "info");
  lua_pushcfunction(L, l_scene_element_near), lua_setfield(L, -2, "element_near");
  lua_pushlightuserdata(L, ctx);
  lua_pushcclosure(L, l_scene_run, 1), lua_setfield(L, -2, "run");
  lua_pushlightuserdata(L, ctx);
  lua_pushcclosure(L, l_scene_start, 1), lua_setfield(L, -2, "start");
  lua_pushvalue(L, -1);
  lua_setfield(L, -3, "methods");  // for the console's completion (read raw)
  lua_pushstring(L, "scene");
  lua_pushcclosure(L, index_methods, 2), lua_setfield(L, -2, "__index");
  lua_pop(L, 1);

  lua_pushlightuserdata(L, ctx);
  lua_pushcclosure(L, l_scene, 1), lua_setfield(L, -2, "scene");
  lua_pushcfunction(L, l_rpm), lua_setfield(L, -2, "rpm");
  open_laws(L);
  lua_pushcfunction(L, l_integrators), lua_setfield(L, -2, "integrators");
}

}  // namespace beltsim::script
