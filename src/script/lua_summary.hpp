// A run's review figures in Lua (plot/summary.hpp, docs/summary.md): `r:summary{ from, to, csv,
// plot }` on the table scene:run returns, and `sim:summary{...}` on a live simulation (its
// outputs so far). Each returns { from, to, rows, belt_speed, spans = {...}, pulleys = {...},
// wraps, hubs, arms, rotors (each rotor's `overrun` = { {from, to}, ... }), loss, table = the
// printed table, csv, plot = the paths written }.
#pragma once

#include "lua.h"

namespace beltsim::script {

struct Context;

// gives the results table on the top of the stack its `summary` method (a metatable's __index:
// pairs() and a sweep's figures do not see it)
void set_results_methods(lua_State* L, Context* ctx);
// sim:summary{...}
int l_sim_summary(lua_State* L);

}  // namespace beltsim::script
