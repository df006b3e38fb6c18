// scene:run{} and scene:start{}: the methods of a scene (lua_scene.hpp) that integrate it, a batch
// run or a live simulation (lua_sim.hpp), on the run settings of lua_run.hpp.
#pragma once

struct lua_State;

namespace beltsim::script {

struct Context;

// adds run and start to the scene's methods (open_scene first); each takes ctx as its upvalue
void open_scene_runs(lua_State* L, Context* ctx);

}  // namespace beltsim::script
