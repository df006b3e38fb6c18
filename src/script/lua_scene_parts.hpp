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
