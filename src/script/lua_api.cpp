// Lua API of beltsim (documented in README.md, "Lua API"): the global table `beltsim` with the
// scene bindings (lua_scene.cpp) and the live simulation's (lua_sim.cpp).
#include "script/lua_api.hpp"

#include "script/lua_scene.hpp"
#include "script/lua_sim.hpp"

namespace beltsim::script {

void open_beltsim(lua_State* L, Context* ctx) {
  lua_newtable(L);
  open_scene(L, ctx);
  open_sim(L, ctx);
  lua_pushstring(L, "0.1.0"), lua_setfield(L, -2, "version");
  lua_setglobal(L, "beltsim");
}

}  // namespace beltsim::script
