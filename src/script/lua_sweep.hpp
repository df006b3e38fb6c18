// Lua side of sweeps (docs/sweeps.md): beltsim.sweep{ grid = {...} | samples = {...}, run = fn },
// the sweep a sweep file returns (its points run in an interpreter: sweep_run.hpp). The processes,
// the resumption and the summary are Lua-free (src/sweep/).
#pragma once

#include <string>
#include <vector>

#include "sweep/points.hpp"

struct lua_State;

namespace beltsim::script {

struct Context;

// the userdata beltsim.sweep{} returns: its points
inline constexpr const char* kSweepMeta = "beltsim.Sweep";
struct SweepBox {
  std::vector<sweep::Point> points;
};

// adds beltsim.sweep to the table on the top of the stack
void open_sweep(lua_State* L, Context* ctx);

}  // namespace beltsim::script
