#include "script/docall.hpp"

#include <sstream>
#include <string_view>

#include "lauxlib.h"
#include "lua.h"
#include "script/limits.hpp"
#include "script/lua_clock.hpp"

namespace beltsim::script {

namespace {

constexpr const char* kKeptTraceback = "beltsim.kept_traceback";  // registry: {message, traceback}

// the traceback keep_traceback left for the string error at index 1, pushed and taken away; false
// when there is none for it
bool push_kept_traceback(lua_State* L) {
  if (lua_getfield(L, LUA_REGISTRYINDEX, kKeptTraceback) != LUA_TTABLE) return lua_pop(L, 1), false;
  const int kept = lua_gettop(L);
  lua_rawgeti(L, kept, 1);
  size_t n = 0, m = 0;
  const char* text = lua_tolstring(L, 1, &n);
  const char* message = lua_tolstring(L, -1, &m);
  const bool ends = text && message && m <= n && std::string_view(text + n - m, m) == std::string_view(message, m);
  lua_pop(L, 1);
  if (!ends) return lua_pop(L, 1), false;
  lua_rawgeti(L, kept, 2);
  lua_remove(L, kept);
  lua_pushnil(L);
  lua_setfield(L, LUA_REGISTRYINDEX, kKeptTraceback);
  return true;
}

// the message handler: a string error keeps its "file:line:" (Lua adds it); any other error
// object gets the place it was raised at and its __tostring (or its type), so that error(42)
// still says where it came from; then Lua's traceback (or the one keep_traceback left for it)
int msghandler(lua_State* L) {
  if (lua_type(L, 1) != LUA_TSTRING) {
    luaL_where(L, 2);  // "file:line:" of the Lua function that called error (1 is error itself)
    if (luaL_callmeta(L, 1, "__tostring") && lua_type(L, -1) == LUA_TSTRING)
      lua_pushfstring(L, "%s%s", lua_tostring(L, -2), lua_tostring(L, -1));
    else if (lua_type(L, 1) == LUA_TNUMBER)
      lua_pushfstring(L, "%s%s", lua_tostring(L, 2), luaL_tolstring(L, 1, nullptr));
    else
      lua_pushfstring(L, "%s(an error object that is a %s value)", lua_tostring(L, 2), luaL_typename(L, 1));
    lua_replace(L, 1);
    lua_settop(L, 1);
  } else if (push_kept_traceback(L)) {
    lua_pushfstring(L, "%s\n%s", lua_tostring(L, 1), lua_tostring(L, -1));
    return 1;
  }
  luaL_traceback(L, L, lua_tostring(L, 1), 1);
  return 1;
}

constexpr const char* kTraceback = "\nstack traceback:\n";

}  // namespace

bool docall(lua_State* L, int nargs, int nresults, CallError* error, const std::string& where) {
  const int fn = lua_gettop(L) - nargs;
  lua_pushcfunction(L, msghandler);
  lua_insert(L, fn);
  int status = LUA_OK;
  {
    const InsideLua inside(L, where.c_str());  // the clock's and the watchdog's view (lua_clock.hpp)
    status = lua_pcall(L, nargs, nresults, fn);
  }
  if (status == LUA_OK) {
    lua_remove(L, fn);
    return true;
  }
  CallError e;
  if (status == -1) {
    // Lua compiled as C++ takes any other exception for an error of status -1, without running
    // the message handler or keeping the exception's text: a binding let a C++ exception out
    // instead of turning it into a Lua error (sim_box.hpp, guarded)
    e.message = where + ": an internal error of beltsim (a C++ exception left one of its Lua functions; please report it)";
  } else if (lua_gettop(L) >= fn && memory_message(L, status, where, e.message)) {
  } else if (lua_gettop(L) > fn && lua_type(L, -1) == LUA_TSTRING) {
    const std::string text = lua_tostring(L, -1);
    const size_t tb = text.rfind(kTraceback);  // the handler's; a message may quote another's
    e.message = text.substr(0, tb);
    if (tb != std::string::npos) e.traceback = text.substr(tb + 1);
  } else {
    e.message = where + ": an error without a message (status " + std::to_string(status) + ")";
  }
  lua_settop(L, fn - 1);
  if (error) *error = std::move(e);
  return false;
}

void keep_traceback(lua_State* L, const std::string& message, const std::string& traceback) {
  lua_createtable(L, 2, 0);
  lua_pushstring(L, message.c_str()), lua_rawseti(L, -2, 1);
  lua_pushstring(L, traceback.c_str()), lua_rawseti(L, -2, 2);
  lua_setfield(L, LUA_REGISTRYINDEX, kKeptTraceback);
}

int call_original(lua_State* L, const char* what) {
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  CallError e;
  if (docall(L, lua_gettop(L) - 1, LUA_MULTRET, &e, what)) return lua_gettop(L);
  luaL_where(L, 1);
  lua_pushstring(L, e.message.c_str());
  lua_concat(L, 2);
  return lua_error(L);
}

std::string function_place(lua_State* L, int idx) {
  lua_Debug ar;
  lua_pushvalue(L, idx);
  lua_getinfo(L, ">S", &ar);  // (pops the function)
  return std::string(ar.short_src) + ":" + std::to_string(ar.linedefined);
}

std::string shown_traceback(const std::string& traceback, int frames) {
  std::istringstream in(traceback);
  std::string line, out;
  int kept = 0, in_lua = 0;
  while (std::getline(in, line)) {
    if (line.rfind('\t', 0) != 0) continue;                     // "stack traceback:"
    if (line.find("[C]: in ?") != std::string::npos) continue;  // the host's own frame
    if (line.rfind("\t[C]:", 0) != 0) ++in_lua;
    if (++kept > frames) continue;
    out += line + "\n";
  }
  // an error in the script's top level, or in a beltsim function it called there (a scene's key):
  // the message's file:line is the whole story
  if (in_lua <= 1) return "";
  if (kept > frames) out += "\t(" + std::to_string(kept - frames) + " more)\n";
  return "stack traceback:\n" + out;
}

}  // namespace beltsim::script
