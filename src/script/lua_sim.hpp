// Lua bindings of the live simulation (sim/simulation.hpp): the object scene:start{} returns,
// its methods (run_to, advance, reading, changes, callbacks, show, plot, save, close) and
// beltsim.resume. The method table is also the source of help() and of the console's completion.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "sim/simulation.hpp"

struct lua_State;

namespace beltsim::script {

struct Context;

void push_simulation(lua_State* L, std::unique_ptr<Simulation> sim, Context* ctx, bool progress);
// adds `resume` and `help` to the table on the top of the stack; registers the metatable
void open_sim(lua_State* L, Context* ctx);

// one line of help per API entry: name, call, what it does (with units)
struct HelpEntry {
  const char* name;
  const char* call;
  const char* text;
};
const std::vector<HelpEntry>& api_help();

}  // namespace beltsim::script
