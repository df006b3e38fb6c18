// Lua API of beltsim (documented in docs/lua-api.md): the global table `beltsim` with the
// scene bindings (lua_scene.cpp; its runs, lua_scene_run.cpp), the laws' helpers (lua_law.cpp), the
// live simulation's (lua_sim.cpp) and beltsim.args, the script parameters of the command line
// (--set KEY=VALUE, lua_args.cpp).
#include "script/lua_api.hpp"

#include "beltsim_version.hpp"
#include "script/console_print.hpp"
#include "script/lua_args.hpp"
#include "script/lua_check.hpp"
#include "script/lua_help.hpp"
#include "script/lua_run.hpp"
#include "script/lua_scene.hpp"
#include "script/lua_scene_run.hpp"
#include "script/lua_sim.hpp"
#include "script/lua_sweep.hpp"

namespace beltsim::script {

void open_beltsim(lua_State* L, Context* ctx) {
  lua_newtable(L);
  open_scene(L, ctx);
  open_scene_runs(L, ctx);
  open_sim(L, ctx);
  open_help(L);
  open_sweep(L, ctx);
  lua_pushstring(L, kBeltsimVersion), lua_setfield(L, -2, "version");
  lua_pushcfunction(L, print_values), lua_setfield(L, -2, "print");  // values as the console shows them
  lua_pushlightuserdata(L, ctx), lua_pushcclosure(L, l_stop_at, 1), lua_setfield(L, -2, "stop_at");
  push_args(L, ctx);
  lua_setfield(L, -2, "args");
  // beltsim.<misspelt>: an error with a suggestion, not a nil to call
  lua_createtable(L, 0, 2);
  lua_pushvalue(L, -2);
  lua_pushliteral(L, "beltsim");
  lua_pushcclosure(L, index_methods, 2);
  lua_setfield(L, -2, "__index");
  lua_setmetatable(L, -2);
  lua_setglobal(L, "beltsim");
}

}  // namespace beltsim::script
