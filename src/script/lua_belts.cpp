// beltsim.belts: the belt presets (scene/belt_presets.hpp) as tables a scene's belt takes.
// beltsim.belts["6PK"] is a new table each time, { preset = "6PK", mass_per_length = ..., EI = ...,
// ... }, so that a script may change or add keys before it builds a scene (`belt =
// beltsim.belts["6PK"]`); its preset key names where the values came from (parameters.csv's
// belt.preset). pairs(beltsim.belts) lists them in order, 3PK … 8PK.
#include <string>

#include "io/suggest.hpp"
#include "scene/belt_presets.hpp"
#include "script/lua_scene.hpp"

namespace beltsim::script {

namespace {

void push_preset(lua_State* L, const BeltPreset& p) {
  lua_createtable(L, 0, static_cast<int>(p.values.size()) + 1);
  lua_pushstring(L, p.name.c_str()), lua_setfield(L, -2, "preset");
  for (const auto& [key, value] : p.values) lua_pushnumber(L, value), lua_setfield(L, -2, key.c_str());
}

int l_belts_index(lua_State* L) {
  const std::vector<std::string> names = belt_preset_names();
  if (lua_type(L, 2) != LUA_TSTRING)
    fail(L, std::string("beltsim.belts[name]: a preset's name expected (") + join(names) + "), got " +
                type_name(L, 2));
  const std::string name = lua_tostring(L, 2);
  const BeltPreset* p = find_belt_preset(name);
  if (!p) fail_on(L, "beltsim.belts", std::string("no preset '") + name + "'" + belt_preset_hint(name));
  push_preset(L, *p);
  return 1;
}

int l_belts_newindex(lua_State* L) {
  fail(L, "beltsim.belts is read-only: change the table beltsim.belts[name] returns (a new one each time)");
}

// pairs(beltsim.belts): each preset's name and a new table of its values
int l_belts_next(lua_State* L) {
  const std::vector<BeltPreset>& all = belt_presets();
  size_t k = 0;
  if (lua_type(L, 2) == LUA_TSTRING) {
    const std::string name = lua_tostring(L, 2);
    while (k < all.size() && all[k].name != name) ++k;
    ++k;
  }
  if (k >= all.size()) return lua_pushnil(L), 1;
  lua_pushstring(L, all[k].name.c_str());
  push_preset(L, all[k]);
  return 2;
}
int l_belts_pairs(lua_State* L) {
  lua_pushcfunction(L, l_belts_next);
  lua_pushvalue(L, 1);
  lua_pushnil(L);
  return 3;
}

}  // namespace

void open_belts(lua_State* L) {
  lua_newtable(L);
  lua_createtable(L, 0, 4);
  lua_pushcfunction(L, l_belts_index), lua_setfield(L, -2, "__index");
  lua_pushcfunction(L, l_belts_newindex), lua_setfield(L, -2, "__newindex");
  lua_pushcfunction(L, l_belts_pairs), lua_setfield(L, -2, "__pairs");
  lua_pushliteral(L, "beltsim.belts"), lua_setfield(L, -2, "__metatable");
  lua_setmetatable(L, -2);
  lua_setfield(L, -2, "belts");
}

}  // namespace beltsim::script
