// The one way the host calls into Lua (after lua.c's docall): a script run, a console command and
// the printing of its results, a Lua law called by the integrator, an io function the host wraps
// (the sandbox's files, io.write). The call is protected, with one message handler that names the
// error's place and appends Lua's traceback (luaL_traceback); a memory error names the limit
// (limits.hpp); a C++ exception that escaped a binding is an error too. While a call is under way
// the stop signals' watchdog knows the host is inside Lua (signals.hpp).
#pragma once

#include <string>

struct lua_State;

namespace beltsim::script {

struct CallError {
  std::string message;    // "file:line: reason" (a non-string error object named, with its place)
  std::string traceback;  // "stack traceback:\n\t..." ("" for a memory error)
};

// calls the function below the `nargs` values on the stack top. On success returns true and
// leaves `nresults` results (all of them for LUA_MULTRET) where the function was; on error
// returns false, leaves the stack as it was below the function and fills *error. `where` names
// the call for an error Lua gives without a place (a memory error: "stdin", the script's path).
bool docall(lua_State* L, int nargs, int nresults, CallError* error, const std::string& where);

// for a C function that wraps one of Lua's (its upvalue 1): calls that function with the values on
// the stack and returns its results; its error is raised again with the script's file:line (of the
// wrapper's caller) before it, as Lua's own function called from the script would have it. `what`
// names the call for docall
int call_original(lua_State* L, const char* what);

// The error about to be raised whose message ends with `message` was raised at another place
// first, with `traceback` ("stack traceback:\n\t..."): docall's message handler gives that
// traceback instead of the one where it is raised again (a callback's error, which the running
// method raises again naming the callback and the time: sim_box.hpp, guarded)
void keep_traceback(lua_State* L, const std::string& message, const std::string& traceback);

// where the Lua function at idx is defined, "file:line" (the place messages about a law, a callback
// or a μ function name: "function at cb.lua:9")
std::string function_place(lua_State* L, int idx);

// the traceback as a reader wants it: without the host's own frames ("[C]: in ?"), at most
// `frames` frames; "" when no more than one frame is left (the message already names that place)
std::string shown_traceback(const std::string& traceback, int frames = 8);

}  // namespace beltsim::script
