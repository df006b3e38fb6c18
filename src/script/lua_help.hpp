// The API's help: one entry per function of beltsim, a scene and a live simulation, with its
// call, units and what it does. The source of help() in scripts and at the console, of the
// console's completion of names and of the reference's check (tests/script/lua_api_docs_test.cpp).
#pragma once

#include <vector>

struct lua_State;

namespace beltsim::script {

// one line of help per API entry: name, call, what it does (with units)
struct HelpEntry {
  const char* name;
  const char* call;
  const char* text;
};
const std::vector<HelpEntry>& api_help();

// sets the global help([name]): the list, or one entry ("help: nothing is called 'x'; did you
// mean ...?" for a name not in it)
void open_help(lua_State* L);

}  // namespace beltsim::script
