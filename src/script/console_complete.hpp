// Tab completion at the console prompt: globals and Lua's keywords, the fields of a table named by
// a dotted path (`beltsim.ra` -> `beltsim.ramp(`), a simulation's methods (`sim:adv` ->
// `sim:advance(`); inside a string argument, the names the call takes there (`sim:pulley("dr` ->
// `sim:pulley("driver"`, `sim:plot{ "driver.om` -> `"driver.omega"`, `sim:elements{ pulley = "`,
// `sim:show{ quantity = "`, `help("`). Completing reads tables raw and never runs Lua code (an
// __index could fail or loop).
#pragma once

struct lua_State;

namespace beltsim::script {

// readline's completion from now on looks up names in L (nullptr: completes nothing)
void complete_from(lua_State* L);

}  // namespace beltsim::script
