// Lua bindings of the scene builder and the runner (LÖVE's wrap_* pattern: the C++ classes know
// nothing of Lua; this file translates tables to SceneDef / RunSettings and back).
#pragma once

struct lua_State;

namespace beltsim::script {

struct Context;  // per-interpreter settings (overrides, default output folder, stop flag)

// registers the global table `beltsim`
void open_beltsim(lua_State* L, Context* ctx);

}  // namespace beltsim::script
