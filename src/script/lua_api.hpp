// The Lua API's global table `beltsim`: the bindings of the scene, its runs, the live simulation,
// the sweeps, help and beltsim.args put together (LÖVE's wrap_* pattern: the C++ classes know
// nothing of Lua; the bindings translate tables to SceneDef / RunSettings and back).
#pragma once

struct lua_State;

namespace beltsim::script {

struct Context;  // per-interpreter settings (overrides, default output folder, stop flag)

// registers the global table `beltsim` (with beltsim.args, the --set parameters)
void open_beltsim(lua_State* L, Context* ctx);

}  // namespace beltsim::script
