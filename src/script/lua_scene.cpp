// Lua bindings of the scene (see lua_scene.hpp): tables in, a built Scene out; every
// key is checked (a misspelt key is an error naming the valid ones), every value's type too,
// and the scene is validated when it is built, so a bad scenario stops before simulating with
// "file:line: reason (got value unit)". The readers of its tables (its pulleys, belt, friction,
// spray zones) are lua_scene_parts.cpp.
//
// Debian's liblua5.4-c++ is Lua compiled as C++: lua_error unwinds with a C++ exception, so the
// destructors of the C++ objects below run. C++ exceptions of our own are caught and turned into
// Lua errors only after their catch block has been left (as LÖVE does).
#include "script/lua_scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "integrate/stepper.hpp"
#include "scene/bending_loss.hpp"
#include "scene/parameters.hpp"
#include "scene/validate.hpp"
#include "script/context.hpp"
#include "script/key_line.hpp"
#include "script/lua_clock.hpp"
#include "script/lua_law.hpp"
#include "script/lua_scene_parts.hpp"
#include "script/progress.hpp"

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

namespace {

// the run's first lines: the defaults a scene took, and the tension a given rest length, strain
// or tensioner preload gives
void report_scene(const Scene& sc) {
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
    say("beltsim: scene defaults (not given; parameters.csv says where each comes from): %s\n", taken.c_str());
  for (const std::string& w : scene_warnings(sc)) say("beltsim: warning: %s\n", w.c_str());
  // the tension at rest is an input (given or the default) unless the rest length, the strain or a
  // tensioner's preload sets it
  if (std::none_of(sc.inputs.begin(), sc.inputs.end(),
                   [](const SceneInput& in) { return in.name == "belt.pretension"; })) {
    const Belt& b = sc.model.belt;
    say("beltsim: belt: rest length %.6g m on a %.6g m route (strain %.4g %%): static span tension %.6g N\n",
        b.rigid_length * b.n, sc.route.length, 100 * (b.pitch / b.rigid_length - 1), sc.static_tension);
  }
}

// beltsim.scene{ pulleys = {...}, belt = {...}, contact = {...}, friction = {...}, gravity = g, energy = bool }
int l_scene(lua_State* L) {
  check_args(L, "beltsim.scene", {{"{pulleys, belt, ...}", kTable}});
  check_keys(L, 1, "scene", keys_of("scene"));
  auto* ctx = static_cast<Context*>(lua_touserdata(L, lua_upvalueindex(1)));
  SceneDef d;
  if (!field(L, 1, "pulleys")) fail_on(L, "scene", "a list of pulleys is required");
  require_table(L, -1, "scene.pulleys");
  const int pl = lua_gettop(L);
  for (lua_Integer k = 1; k <= static_cast<lua_Integer>(lua_rawlen(L, pl)); ++k) {
    lua_rawgeti(L, pl, k);
    d.pulleys.push_back(to_pulley(L, -1, "pulley " + std::to_string(k), d, ctx));
    note_given(L, -1, "pulley." + d.pulleys.back().name + ".", d.given);
    if (field(L, -1, "tensioner"))
      note_given(L, -1, "pulley." + d.pulleys.back().name + ".tensioner.", d.given), lua_pop(L, 1);
    if (field(L, -1, "coupling"))
      note_given(L, -1, "pulley." + d.pulleys.back().name + ".coupling.", d.given), lua_pop(L, 1);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  std::unique_ptr<LuaRef> mu_fn;
  if (field(L, 1, "belt")) {
    read_belt(L, lua_gettop(L), d, mu_fn);
    note_given(L, -1, "belt.", d.given);
    if (field(L, -1, "sde")) note_given(L, -1, "belt.sde.", d.given), lua_pop(L, 1);
    lua_pop(L, 1);
  }
  if (field(L, 1, "contact")) {
    const int c = lua_gettop(L);
    require_table(L, c, "contact");
    check_keys(L, c, "contact", keys_of("contact"));
    // each constant per element (the paper's) or per metre of pitch, not both
    for (const char* k : {"c1", "c2", "damping"})
      if (has(L, c, k) && has(L, c, (std::string(k) + "_per_length").c_str()))
        fail(L, std::string("contact: give ") + k + " (per element) or " + k +
                    "_per_length (per metre of belt), not both");
    PulleyDef none;
    read_numbers(L, c, "contact", "contact", d, none);
    note_given(L, c, "contact.", d.given);
    lua_pop(L, 1);
  }
  if (field(L, 1, "friction")) {
    const int f = lua_gettop(L);
    require_table(L, f, "friction");
    check_keys(L, f, "friction", keys_of("friction"));
    read_friction_law(L, f, "friction", d);
    note_given(L, f, "friction.", d.given);
    if (field(L, f, "segments")) {
      read_friction_segments(L, lua_gettop(L), d);
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
  }
  if (field(L, 1, "spray")) {
    read_spray(L, lua_gettop(L), d);
    lua_pop(L, 1);
  }
  note_given(L, 1, "", d.given);
  PulleyDef none;
  read_numbers(L, 1, "scene", "scene", d, none);
  if (auto v = opt_bool(L, 1, "energy", "scene")) d.track_energy = *v;
  if (auto v = opt_bool(L, 1, "allow_large", "scene")) d.allow_large = *v;

  if (ctx && ctx->capture && ctx->capture->definition_only) {  // Captured: the definition, nothing built
    if (!mu_fn) ctx->capture->definition = d;
    ctx->captured = true;
    lua_pushliteral(L, "scene captured");
    return lua_error(L);
  }
  auto** box = static_cast<Scene**>(lua_newuserdatauv(L, sizeof(Scene*), 0));
  *box = nullptr;
  luaL_setmetatable(L, kSceneMeta);
  std::string error;
  KeyPath about;  // the parameter an error is about: its line is the key's (lua_check.hpp, fail_at)
  try {
    const HostWork work;  // beltsim's own work, not Lua code (lua_clock.hpp); its laws are calls of their own
    // a build that takes more than a second (thousands of elements) shows its progress; a quick one nothing
    ProgressLine line(!(ctx && ctx->capture && ctx->capture->quiet));
    BuildWatch watch;
    watch.stop = ctx ? ctx->stop : nullptr;
    watch.progress = line.build_callback();
    *box = new Scene(build_scene(d, watch));
    line.built();
  } catch (const ParameterError& e) {
    error = e.what(), about = e.path;
  } catch (const BuildInterrupted& e) {
    ctx->interrupted = true;
    error = e.what();
  } catch (const std::exception& e) {               // a Lua law that failed while the static state was sought
    error = e.what(), about = message_path(error);  // ("pulley 'driven'.torque (function at ...)")
  }
  if (!error.empty()) fail_at(L, about, error);
  if (!(ctx && ctx->capture && ctx->capture->quiet)) report_scene(**box);
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
  lua_pushinteger(L, b.n), lua_setfield(L, -2, "elements");
  set_number(L, "pitch", b.pitch);
  set_number(L, "rigid_length", b.rigid_length);
  set_number(L, "rest_length", b.rigid_length * b.n);
  set_number(L, "strain", b.pitch / b.rigid_length - 1);
  set_number(L, "mass", b.mass);
  set_number(L, "k", b.k);
  set_number(L, "c", b.c);
  set_number(L, "kt", b.kt);
  set_number(L, "ct", b.ct);
  set_number(L, "route_length", sc->route.length);
  // the length the belt coordinate s runs over (the path the elements' centres were laid on,
  // pressed into the pulleys): what a wet stretch's from and to take, what belt.mu's functions read
  set_number(L, "s_length", sc->sites.empty() ? 0.0 : sc->sites[0].length);
  set_number(L, "static_tension", sc->static_tension);
  set_number(L, "static_residual", sc->static_residual);
  // the fields' units, which beltsim.print and the console print after them (docs/lua-api.md)
  for (const auto& [field, unit] :
       std::initializer_list<std::pair<const char*, const char*>>{{"pitch", "m"},
                                                                  {"rigid_length", "m"},
                                                                  {"rest_length", "m"},
                                                                  {"mass", "kg"},
                                                                  {"c", "N·s/m"},
                                                                  {"kt", "N·m/rad"},
                                                                  {"ct", "N·m·s/rad"},
                                                                  {"route_length", "m"},
                                                                  {"s_length", "m"},
                                                                  {"static_tension", "N"},
                                                                  {"static_residual", "m/s²"}})
    set_unit(L, -1, field, unit);
  if (b.e_tra == 1) set_unit(L, -1, "k", "N/m");  // (N/m^e for a law of exponent e)
  lua_newtable(L);
  for (size_t k = 0; k < sc->route_names.size(); ++k)
    lua_pushnumber(L, sc->route.arcs[k].angle * 180 / M_PI), lua_setfield(L, -2, sc->route_names[k].c_str());
  lua_setfield(L, -2, "wrap_deg");
  lua_newtable(L);
  for (size_t k = 0; k < sc->route_names.size(); ++k)
    lua_pushnumber(L, sc->wrap_elements(k)), lua_setfield(L, -2, sc->route_names[k].c_str());
  lua_setfield(L, -2, "wrap_elements");
  lua_newtable(L);
  const std::vector<std::string> coarse = scene_warnings(*sc);
  for (size_t k = 0; k < coarse.size(); ++k) lua_pushstring(L, coarse[k].c_str()), lua_rawseti(L, -2, k + 1);
  lua_setfield(L, -2, "warnings");
  // the bending dampers' estimated power at the laws' steady speeds (scene/bending_loss.hpp)
  if (const std::optional<BendingLoss> e = estimate_bending_loss(*sc)) {
    lua_createtable(L, 0, 4);
    set_number(L, "belt_speed", e->belt_speed);
    set_number(L, "transmitted", e->transmitted);
    set_number(L, "dissipated", e->dissipated);
    set_number(L, "share", e->share());
    set_unit(L, -1, "belt_speed", "m/s"), set_unit(L, -1, "transmitted", "W"), set_unit(L, -1, "dissipated", "W");
    lua_setfield(L, -2, "bending_loss");
  }
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

void add_scene_method(lua_State* L, const char* name, lua_CFunction f, Context* ctx) {
  luaL_getmetatable(L, kSceneMeta);
  lua_getfield(L, -1, "methods");
  lua_pushlightuserdata(L, ctx);
  lua_pushcclosure(L, f, 1), lua_setfield(L, -2, name);
  lua_pop(L, 2);
}

void open_scene(lua_State* L, Context* ctx) {
  luaL_newmetatable(L, kSceneMeta);
  lua_pushcfunction(L, l_scene_gc), lua_setfield(L, -2, "__gc");
  lua_pushcfunction(L, l_scene_tostring), lua_setfield(L, -2, "__tostring");
  lua_pushliteral(L, "beltsim.Scene"), lua_setfield(L, -2, "__metatable");  // scripts cannot reach __gc
  lua_newtable(L);
  lua_pushcfunction(L, l_scene_info), lua_setfield(L, -2, "info");
  lua_pushcfunction(L, l_scene_element_near), lua_setfield(L, -2, "element_near");
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
  open_belts(L);
}

}  // namespace beltsim::script