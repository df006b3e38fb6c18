// Checking helpers of the Lua bindings: every value a script passes is checked for its type
// and range, every table for unknown keys (with a suggestion when one valid key is close), and a
// failure is a Lua error prefixed with the script's "file:line:".
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "model/model.hpp"

// not lua.hpp: its extern "C" would not match the C++-compiled library
#include "lauxlib.h"
#include "lua.h"

namespace beltsim::script {

[[noreturn]] void fail(lua_State* L, const std::string& msg);
bool has(lua_State* L, int idx, const char* key);
size_t edit_distance(const std::string& a, const std::string& b);
// the valid name closest to `name` (edit distance <= 2), or ""
std::string closest(const std::string& name, const std::vector<std::string>& valid);
// every key of the table at idx must be one of `allowed`
void check_keys(lua_State* L, int idx, const std::string& where, const std::vector<std::string>& allowed);
const char* type_name(lua_State* L, int idx);
// value of t[key] pushed; returns false (and pushes nothing) when nil
bool field(lua_State* L, int idx, const char* key);
double to_number(lua_State* L, int idx, const std::string& what);
std::optional<double> opt_number(lua_State* L, int t, const char* key, const std::string& where);
std::string to_string(lua_State* L, int idx, const std::string& what);  // a string without NUL
std::optional<std::string> opt_string(lua_State* L, int t, const char* key, const std::string& where);
std::optional<bool> opt_bool(lua_State* L, int t, const char* key, const std::string& where);
int to_integer(lua_State* L, int idx, const std::string& what);
void require_table(lua_State* L, int idx, const std::string& what);
Vec2 to_vec2(lua_State* L, int idx, const std::string& what);  // finite
// the table at idx must be a list 1..n without holes or named keys
std::vector<lua_Integer> check_sequence(lua_State* L, int idx, const std::string& what);
// a function's arguments: exactly `min`..`max` of them, or "NAME: expected ..., got N arguments"
void check_arg_count(lua_State* L, const char* name, int min, int max);

// a Lua value kept alive in the registry (released through the main thread: the coroutine that
// made the reference may be gone by then)
struct LuaRef {
  lua_State* L;
  int ref;
  LuaRef(lua_State* l, int idx) {
    lua_rawgeti(l, LUA_REGISTRYINDEX, LUA_RIDX_MAINTHREAD);
    L = lua_tothread(l, -1);
    lua_pop(l, 1);
    lua_pushvalue(l, idx);
    ref = luaL_ref(l, LUA_REGISTRYINDEX);
  }
  ~LuaRef() { luaL_unref(L, LUA_REGISTRYINDEX, ref); }
  LuaRef(const LuaRef&) = delete;
  LuaRef& operator=(const LuaRef&) = delete;
  void push(lua_State* S) const { lua_rawgeti(S, LUA_REGISTRYINDEX, ref); }
};

}  // namespace beltsim::script
