// Pulley laws from Lua (docs/lua-api.md, "Laws"): numbers, law tables, lists of laws (their sum), and
// function(t, omega) laws; the helpers beltsim.ramp, beltsim.step and beltsim.sine. The terms and
// their formulas are in model/laws.hpp; this file only reads them, checks them (file:line) and
// writes them back as text.
#pragma once

#include <memory>
#include <string>

#include "model/laws.hpp"
#include "script/lua_check.hpp"

namespace beltsim::script {

struct Context;

// a torque law [N·m] (speed = false) or a prescribed speed [rad/s] from the value at idx,
// checked (validate_law) with errors naming `what` and the script's file:line
TimeSpeedLaw to_law(lua_State* L, int idx, const std::string& what, bool speed, Context* ctx);
// adds ramp, step and sine to the table on the top of the stack
void open_laws(lua_State* L);

}  // namespace beltsim::script
