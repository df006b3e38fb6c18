// How the console shows values: readable Lua (tables one entry a line, long lists shortened, a
// number in a result of the API followed by "-- unit", the unit its result recorded: lua_check.hpp,
// kUnitsField), never running Lua code except a __tostring (print_values is called protected for
// that reason).
#pragma once

#include <string>

struct lua_State;

namespace beltsim::script {

// a lua_CFunction: prints its arguments as the console shows values, separated by tabs, on stdout
// (nothing for none); the console's results, and beltsim.print (session.lua replays with it what
// the prompt printed)
int print_values(lua_State* L);
// s as a Lua string literal ("..." with escapes)
std::string quoted(const char* s, size_t n);
// s is a Lua name (letters, digits and _, not starting with a digit; keywords included)
bool is_identifier(const std::string& s);

}  // namespace beltsim::script
