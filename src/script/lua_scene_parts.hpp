// The readers of beltsim.scene{}'s tables into a SceneDef (lua_scene_parts.cpp), as l_scene
// (lua_scene.cpp) calls them, and the element's site as a belt.mu function gets it.
#pragma once

#include <memory>
#include <set>
#include <string>
#include <string_view>

#include "script/lua_check.hpp"

namespace beltsim {
struct ElementSite;
struct PulleyDef;
struct SceneDef;
}  // namespace beltsim

namespace beltsim::script {

struct Context;

// the element's site as the table belt.mu functions get (and a run's μ events' functions, lua_run.cpp)
void push_site(lua_State* L, const ElementSite& e);
// calls the μ function at idx (belt.mu, an event's or sim:wet's mu) with the element's site and
// returns its result; an error in it, or a result that is not a number, is a LawError naming the
// key (`key`: "belt.mu", "run.events[1].mu"), the function's place and the element, as a torque
// law's error names its law and time: "run.events[1].mu (function at s.lua:12) for element 48 at
// s = 0.252 m: s.lua:12: attempt to index a nil value (field 'nope')". The error's traceback is kept
// (docall.hpp, keep_traceback) for the error it is raised again as.
double call_mu(lua_State* L, int idx, const ElementSite& site, const std::string& key);

// every number of the parameter table's `table` that the Lua table at idx gives (scene/parameters.hpp),
// into d (a pulley's into p); `where` names the table in errors ("belt", "pulley 'driver'")
void read_numbers(lua_State* L, int idx, std::string_view table, const std::string& where, SceneDef& d, PulleyDef& p);
// a friction table's law and its numbers at idx into d.friction (w: "friction", "friction.segments[2]")
void read_friction_law(lua_State* L, int idx, const std::string& w, SceneDef& d);
// friction.segments at idx into d.friction_segments, the keys given into d.given
void read_friction_segments(lua_State* L, int idx, SceneDef& d);
// the scene's spray list at idx into d.spray, the keys given into d.given
void read_spray(lua_State* L, int idx, SceneDef& d);
// the pulley table at idx (`what` names it in errors: "pulley 2"), with its tensioner and coupling
PulleyDef to_pulley(lua_State* L, int idx, const std::string& what, SceneDef& d, Context* ctx);
// the belt table at idx into d.belt; a belt.mu function is kept alive in mu_fn while the scene is built
void read_belt(lua_State* L, int idx, SceneDef& d, std::unique_ptr<LuaRef>& mu_fn);
// the string keys of the table at idx, as prefix..key, into `given` (SceneDef::given)
void note_given(lua_State* L, int idx, const std::string& prefix, std::set<std::string>& given);

}  // namespace beltsim::script
