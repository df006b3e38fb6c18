// The readers of beltsim.scene{}'s tables into a SceneDef (lua_scene.cpp builds it): a pulley with
// its tensioner and coupling, the belt, friction and its segments, spray zones; every key checked.
#include "script/lua_scene_parts.hpp"

#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "io/number_text.hpp"
#include "model/laws.hpp"
#include "scene/belt_presets.hpp"
#include "scene/parameters.hpp"
#include "scene/scene_types.hpp"
#include "scene/validate.hpp"
#include "script/docall.hpp"
#include "script/lua_law.hpp"

namespace beltsim::script {

namespace {

// a pulley's tensioner table at idx into p.tensioner: its pivot {x, y}, then the numbers of the
// parameter table's "pulley.tensioner" (w names it in errors: "pulley 'idler'.tensioner")
void read_tensioner(lua_State* L, int idx, const std::string& w, SceneDef& d, PulleyDef& p) {
  require_table(L, idx, w);
  check_keys(L, idx, w, keys_of("pulley.tensioner"));
  TensionerDef& t = p.tensioner.emplace();
  if (!field(L, idx, "pivot")) fail_on(L, w, "a pivot {x, y} [m] is required");
  t.pivot = to_vec2(L, -1, w + ".pivot");
  lua_pop(L, 1);
  if (!has(L, idx, "inertia")) fail_on(L, w, "the arm's inertia about the pivot [kg·m²] is required");
  if (!has(L, idx, "stiffness")) fail_on(L, w, "the spring's stiffness [N·m/rad] is required");
  if (has(L, idx, "preload") && has(L, idx, "angle0")) fail_on(L, w, "give preload [N·m] or angle0 [rad], not both");
  read_numbers(L, idx, "pulley.tensioner", w, d, p);
}

// a pulley's coupling table at idx into p.coupling: one_way, then the numbers of the parameter
// table's "pulley.coupling" (w names it in errors: "pulley 'alternator'.coupling")
void read_coupling(lua_State* L, int idx, const std::string& w, SceneDef& d, PulleyDef& p) {
  require_table(L, idx, w);
  check_keys(L, idx, w, keys_of("pulley.coupling"));
  CouplingDef& c = p.coupling.emplace();
  if (!has(L, idx, "inertia")) fail_on(L, w, "the rotor's inertia [kg·m²] is required");
  if (!has(L, idx, "stiffness")) fail_on(L, w, "the decoupler spring's stiffness [N·m/rad] is required");
  if (auto v = opt_bool(L, idx, "one_way", w)) c.one_way = *v;
  read_numbers(L, idx, "pulley.coupling", w, d, p);
}

}  // namespace

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

double call_mu(lua_State* L, int idx, const ElementSite& site, const std::string& key) {
  idx = lua_absindex(L, idx);
  const std::string where = function_place(L, idx);
  const std::string about = key + " (function at " + where + ") for element " + std::to_string(site.index) +
                            " at s = " + rounded_text(site.s) + " m";
  const int top = lua_gettop(L);
  lua_pushvalue(L, idx);
  push_site(L, site);
  CallError e;
  if (!docall(L, 1, 1, &e, where)) {
    keep_traceback(L, about + ": " + e.message, e.traceback);
    throw LawError(about + ": " + e.message);
  }
  if (lua_type(L, -1) != LUA_TNUMBER) {
    const std::string got = type_name(L, -1);
    lua_settop(L, top);
    throw LawError(about + ": it returned " + got + ", a number expected");
  }
  const double mu = lua_tonumber(L, -1);
  lua_settop(L, top);
  return mu;
}

// every number of the parameter table's `table` that the Lua table at idx gives (scene/parameters.hpp),
// into d (a pulley's into p); `where` names the table in errors ("belt", "pulley 'driver'")
void read_numbers(lua_State* L, int idx, std::string_view table, const std::string& where, SceneDef& d, PulleyDef& p) {
  for (const Parameter* par : parameters_of(table)) {
    if (par->kind == Kind::other) continue;
    const std::string key(par->key);
    if (!field(L, idx, key.c_str())) continue;
    const Slot slot = par->slot(d, p);
    if (int* const* i = std::get_if<int*>(&slot))
      **i = to_integer(L, -1, where + "." + key);
    else if (double* const* x = std::get_if<double*>(&slot))
      **x = to_number(L, -1, where + "." + key);
    else if (std::optional<double>* const* o = std::get_if<std::optional<double>*>(&slot))
      **o = to_number(L, -1, where + "." + key);
    lua_pop(L, 1);
  }
}

// a friction table's law and its numbers at idx into d.friction (w: "friction", "friction.segments[2]")
void read_friction_law(lua_State* L, int idx, const std::string& w, SceneDef& d) {
  if (auto k = opt_choice(L, idx, "law", w, {"threlfall", "stribeck", "lugre"}))
    d.friction.law = *k == 0 ? FrictionKind::threlfall : *k == 1 ? FrictionKind::stribeck : FrictionKind::lugre;
  // a law's own parameters with another law: a mistake the run would silently ignore
  for (const Parameter* par : parameters_of("friction"))
    if (par->applies && !par->applies(d) && has(L, idx, std::string(par->key).c_str()))
      fail_on(L, w + "." + std::string(par->key),
              std::string("a parameter of another law; this ") + (w == "friction" ? "scene's" : "segment's") +
                  " law is '" + friction_law_name(d.friction.law) + "'");
  PulleyDef none;
  read_numbers(L, idx, "friction", w, d, none);
}

// friction.segments at idx into d.friction_segments: each a stretch {from, to} [m] with the keys of
// the friction table (but dv and segments), starting from the scene's friction law; the keys given
// go to d.given as "friction.segments.<k>.<key>"
void read_friction_segments(lua_State* L, int idx, SceneDef& d) {
  require_table(L, idx, "friction.segments");
  const std::vector<lua_Integer> keys = check_sequence(L, idx, "friction.segments");
  std::vector<std::string> allowed{"from", "to"};
  for (const std::string& k : keys_of("friction"))
    if (k != "dv" && k != "segments") allowed.push_back(k);
  for (const lua_Integer k : keys) {
    lua_geti(L, idx, k);
    const int g = lua_gettop(L);
    const std::string w = "friction.segments[" + std::to_string(k) + "]";
    require_table(L, g, w);
    check_keys(L, g, w, allowed);
    FrictionSegment& seg = d.friction_segments.emplace_back();
    const auto from = opt_number(L, g, "from", w), to = opt_number(L, g, "to", w);
    if (!from || !to) fail_on(L, w, "from and to [m] (where the segment begins and ends along the belt) are required");
    seg.from = *from, seg.to = *to;
    SceneDef own;  // the segment's law, from the scene's
    own.friction = d.friction;
    read_friction_law(L, g, w, own);
    seg.law = own.friction;
    note_given(L, g, "friction.segments." + std::to_string(k) + ".", d.given);
    lua_pop(L, 1);
  }
}

// the scene's spray list at idx into d.spray: each zone's centre {x, y}, then the numbers of the
// parameter table's "spray" (their rules are checked by validate); the keys given go to d.given
// as "spray.<k>.<key>"
void read_spray(lua_State* L, int idx, SceneDef& d) {
  require_table(L, idx, "scene.spray");
  const std::vector<lua_Integer> keys = check_sequence(L, idx, "scene.spray");
  for (lua_Integer k = 1; k <= static_cast<lua_Integer>(keys.size()); ++k) {
    lua_rawgeti(L, idx, k);
    const int z = lua_gettop(L);
    const std::string w = "spray " + std::to_string(k);
    require_table(L, z, w);
    check_keys(L, z, w, keys_of("spray"));
    SprayZone& zone = d.spray.emplace_back();
    if (!field(L, z, "centre")) fail_on(L, w, "a centre {x, y} [m] is required");
    zone.centre = to_vec2(L, -1, w + ".centre");
    lua_pop(L, 1);
    zone.from = parameter_default("spray.from");
    zone.to = std::numeric_limits<double>::infinity();
    for (const Parameter* par : parameters_of("spray")) {
      if (par->kind != Kind::number) continue;
      const std::string key(par->key);
      double* slot = key == "radius" ? &zone.radius
                     : key == "mu"   ? &zone.mu
                     : key == "from" ? &zone.from
                     : key == "to"   ? &zone.to
                                     : &zone.drying_length;
      if (auto v = opt_number(L, z, key.c_str(), w)) {
        *slot = *v;
      } else if (!par->fallback && key != "to") {
        fail_on(L, w, key + (par->unit.empty() ? "" : " [" + std::string(par->unit) + "]") + " is required");
      }
    }
    note_given(L, z, "spray." + std::to_string(k) + ".", d.given);
    lua_pop(L, 1);
  }
}

PulleyDef to_pulley(lua_State* L, int idx, const std::string& what, SceneDef& d, Context* ctx) {
  idx = lua_absindex(L, idx);
  require_table(L, idx, what);
  // an unknown key named in the pulley it is in: by its name when it has a string one
  lua_getfield(L, idx, "name");
  const std::string known = lua_type(L, -1) == LUA_TSTRING ? "pulley '" + std::string(lua_tostring(L, -1)) + "'" : what;
  lua_pop(L, 1);
  check_keys(L, idx, known, keys_of("pulley"));
  PulleyDef p;
  const auto name = opt_string(L, idx, "name", what);
  // (the path pulley N.name: the line of its `name =`, or of the pulley's table when none is written)
  if (!name)
    fail_on(L, what + ".name",
            "a name is required, got nil (a string: name = \"idler\"; written without quotes, name = idler reads a "
            "variable, nil unless the script sets one)");
  p.name = *name;
  const std::string w = "pulley '" + p.name + "'";
  bool centred = false;
  if (has(L, idx, "centre") && has(L, idx, "center")) fail_on(L, w, "give centre or center, not both");
  for (const char* key : {"centre", "center"})
    if (field(L, idx, key)) {
      p.centre = to_vec2(L, -1, w + "." + key);
      lua_pop(L, 1);
      centred = true;
    }
  if (!centred) fail_on(L, w, "a centre {x, y} [m] is required");
  read_numbers(L, idx, "pulley", w, d, p);
  if (auto k = opt_choice(L, idx, "wrap", w, {"inside", "back"})) p.wrap = *k == 0 ? WrapSide::inside : WrapSide::back;
  if (field(L, idx, "torque")) {
    p.torque = to_law(L, -1, w + ".torque", false, ctx);
    lua_pop(L, 1);
  }
  if (field(L, idx, "speed")) {
    p.speed = to_law(L, -1, w + ".speed", true, ctx);
    p.kinematic = true;
    lua_pop(L, 1);
  }
  if (field(L, idx, "tensioner")) {
    read_tensioner(L, lua_gettop(L), w + ".tensioner", d, p);
    lua_pop(L, 1);
  }
  if (field(L, idx, "coupling")) {
    read_coupling(L, lua_gettop(L), w + ".coupling", d, p);
    lua_pop(L, 1);
  }
  return p;
}

// a Lua function kept alive in the registry while the scene is built
void read_belt(lua_State* L, int idx, SceneDef& d, std::unique_ptr<LuaRef>& mu_fn) {
  BeltDef& b = d.belt;
  require_table(L, idx, "belt");
  check_keys(L, idx, "belt", keys_of("belt"));
  {  // the tension at rest: exactly one of three ways (the paper's 500 N pretension when none)
    const int ways = has(L, idx, "pretension") + has(L, idx, "rest_length") + has(L, idx, "strain");
    if (ways > 1)
      fail_on(L, "belt",
              std::string("give one of pretension [N], rest_length [m] or strain, not ") + std::to_string(ways));
  }
  const bool rigidities = has(L, idx, "EA") || has(L, idx, "EI") || has(L, idx, "axial_damping") ||
                          has(L, idx, "bending_damping") || has(L, idx, "bending_viscosity");
  if (has(L, idx, "bending_damping") && has(L, idx, "bending_viscosity"))
    fail_on(L, "belt", "give bending_damping [N·m·s/rad per SDE] or bending_viscosity [N·m²·s per length], not both");
  if (auto name = opt_string(L, idx, "preset", "belt")) {  // its values first: the table's own override them
    const BeltPreset* p = find_belt_preset(*name);
    if (!p) fail_on(L, "belt.preset", std::string("no preset '") + *name + "'" + belt_preset_hint(*name));
    b.preset = *name;
    apply_belt_preset(*p, d, [&](const std::string& key) { return has(L, idx, key.c_str()); });
  }
  PulleyDef none;
  read_numbers(L, idx, "belt", "belt", d, none);
  if (has(L, idx, "rest_length")) b.tensioning = Tensioning::rest_length;
  if (has(L, idx, "strain")) b.tensioning = Tensioning::strain;
  if (auto k = opt_choice(L, idx, "direction", "belt", {"cw", "ccw"})) b.loop_sense = *k == 0 ? -1 : 1;
  if (field(L, idx, "route")) {
    const int r = lua_gettop(L);
    require_table(L, r, "belt.route");
    check_sequence(L, r, "belt.route");
    if (lua_rawlen(L, r) < 2)
      fail_on(L, "belt.route", "at least two pulley names expected (leave route out for the order of pulleys)");
    for (lua_Integer k = 1; k <= static_cast<lua_Integer>(lua_rawlen(L, r)); ++k) {
      lua_rawgeti(L, r, k);
      if (lua_type(L, -1) != LUA_TSTRING)
        fail_on(L, "belt.route", std::string("pulley names expected, got ") + std::string(type_name(L, -1)));
      b.route.push_back(lua_tostring(L, -1));
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
  }
  if (field(L, idx, "sde")) {
    if (rigidities)
      fail_on(L, "belt",
              "give either rigidities (EA, EI, axial_damping, bending_damping or bending_viscosity) or per-SDE values "
              "(sde), not both");
    const int s = lua_gettop(L);
    require_table(L, s, "belt.sde");
    check_keys(L, s, "belt.sde", keys_of("belt.sde"));
    b.reading = StiffnessReading::per_sde;
    read_numbers(L, s, "belt.sde", "belt.sde", d, none);
    for (const std::string& key : keys_of("belt.sde"))
      if (!has(L, s, key.c_str()))
        fail_on(L, "belt.sde", std::string("all of k, c, kt, ct are required (") + key + " is missing)");
    lua_pop(L, 1);
  }
  if (field(L, idx, "mu")) {
    const int m = lua_gettop(L);
    if (lua_type(L, m) == LUA_TNUMBER) {
      b.mu = lua_tonumber(L, m);
    } else if (lua_isfunction(L, m)) {
      mu_fn = std::make_unique<LuaRef>(L, m);
      LuaRef* ref = mu_fn.get();
      b.mu_at = [ref](const ElementSite& site) {  // (called by the build: its error is a LawError, call_mu)
        lua_State* S = ref->L;
        lua_rawgeti(S, LUA_REGISTRYINDEX, ref->ref);
        const double mu = call_mu(S, -1, site, "belt.mu");
        lua_pop(S, 1);
        return mu;
      };
    } else if (lua_istable(L, m)) {
      check_sequence(L, m, "belt.mu");
      if (lua_rawlen(L, m) == 0)
        fail_on(L, "belt.mu", "an empty list; give a number, one μ per element, or a function(site)");
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
  if (b.mu_flank) {  // the effective coefficient of the wedge from the flanks' (docs/model.md, The rib wedge)
    if (has(L, idx, "mu")) fail_on(L, "belt", "give mu (the effective coefficient) or mu_flank, not both");
    std::ostringstream m;
    if (!(b.rib_angle > 0 && b.rib_angle < 180))
      m << "belt.rib_angle: must be > 0 and < 180 (the ribs' included angle) (got " << b.rib_angle << " °)";
    else if (const std::string bad = mu_problem(*b.mu_flank); !bad.empty())
      m << "belt.mu_flank " << bad << " (got " << *b.mu_flank << ")";
    if (!m.str().empty()) fail(L, m.str());
    b.mu = *b.mu_flank / std::sin(b.rib_angle * M_PI / 360.0);
    d.given.insert("belt.mu");
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

}  // namespace beltsim::script
