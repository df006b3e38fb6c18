// Lua bindings of the scene: beltsim.scene{...} and the scene's methods (info, element_near; run
// and start are in lua_scene_run.hpp), the laws' helpers (beltsim.rpm, beltsim.ramp). The C++ classes
// know nothing of Lua.
#pragma once

#include "scene/scene.hpp"
#include "script/lua_check.hpp"

namespace beltsim::script {

struct Context;

// the scene at idx (method: for the message when it is not one)
const Scene* check_scene(lua_State* L, int idx, const char* method);

// adds the method `name` (f, with ctx as its upvalue) to the scene's (after open_scene)
void add_scene_method(lua_State* L, const char* name, lua_CFunction f, Context* ctx);
// adds `scene`, `rpm`, the laws' helpers (lua_law.hpp), `integrators`, `belts` to the table on the top of
// the stack
void open_scene(lua_State* L, Context* ctx);
// adds `belts`, the belt presets (lua_belts.cpp), to the table on the top of the stack
void open_belts(lua_State* L);

}  // namespace beltsim::script
