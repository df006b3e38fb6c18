// Lua bindings of the live simulation (sim/simulation.hpp): the object scene:start{} returns,
// its methods (run_to, advance, reading, changes, callbacks, show, plot, save, close) and
// beltsim.resume. The method table is also the source of the console's completion.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "sim/simulation.hpp"

struct lua_State;

namespace beltsim::script {

struct Context;

void push_simulation(lua_State* L, std::unique_ptr<Simulation> sim, Context* ctx, bool progress);
// adds `resume` to the table on the top of the stack; registers the metatable
void open_sim(lua_State* L, Context* ctx);

// The names a string argument of `sim:<method>` takes, for the console's completion: for the live
// simulation at index idx (anything else: none), argument `arg` (1-based) of the call, or inside
// its table argument (`in_table`) the field `key` ("" for the list part). Pulley names for
// pulley, span, set_torque, set_speed, set_arm (pulleys on an arm), set_rotor (coupled pulleys) and
// elements{ pulley = }; timeseries.csv's columns for plot{ ... }; the quantities for show{ quantity = }.
// Runs no Lua code.
std::vector<std::string> argument_names(lua_State* L, int idx, const std::string& method, bool in_table, int arg,
                                        const std::string& key);

}  // namespace beltsim::script
