// Checking helpers of the Lua bindings: every value a script passes is checked for its type
// and range, every table for unknown keys (with a suggestion when one valid key is close), and a
// failure is a Lua error prefixed with the script's "file:line:".
#pragma once

#include <initializer_list>
#include <optional>
#include <string>
#include <vector>

#include "model/model.hpp"
#include "scene/key_path.hpp"

// not lua.hpp: its extern "C" would not match the C++-compiled library
#include "lauxlib.h"
#include "lua.h"

namespace beltsim::script {

// a Lua error "file:line: msg", the line the one of the calling script, or of the key `path` in the
// call's table constructor (key_line.hpp); fail finds the path at the start of msg (message_path)
[[noreturn]] void fail_at(lua_State* L, const KeyPath& path, const std::string& msg);
[[noreturn]] void fail(lua_State* L, const std::string& msg);
// "what: reason" about the key `what` names (a path: "run.sample", "pulley 'a'.radius"), its line the key's
[[noreturn]] void fail_on(lua_State* L, const std::string& what, const std::string& reason);
bool has(lua_State* L, int idx, const char* key);
// every key of the table at idx must be one of `allowed` (a misspelt one gets a suggestion,
// io/suggest.hpp)
void check_keys(lua_State* L, int idx, const std::string& where, const std::vector<std::string>& allowed);
// a value's type for an error, with the value when it is a number, a boolean or a string (its
// first 40 characters): "number 2.5", "string 'abc'", "table"
std::string type_name(lua_State* L, int idx);
// value of t[key] pushed; returns false (and pushes nothing) when nil
bool field(lua_State* L, int idx, const char* key);
double to_number(lua_State* L, int idx, const std::string& what);
std::optional<double> opt_number(lua_State* L, int t, const char* key, const std::string& where);
std::string to_string(lua_State* L, int idx, const std::string& what);  // a string without NUL
std::optional<std::string> opt_string(lua_State* L, int t, const char* key, const std::string& where);
std::optional<bool> opt_bool(lua_State* L, int t, const char* key, const std::string& where);
// the index in `choices` of the string t[key], nothing when nil; another string is an error on
// where.key: "'cw' or 'ccw' expected, got 'cc' (did you mean 'cw'?)" (io/suggest.hpp)
std::optional<size_t> opt_choice(lua_State* L, int t, const char* key, const std::string& where,
                                 const std::vector<std::string>& choices);
int to_integer(lua_State* L, int idx, const std::string& what);
void require_table(lua_State* L, int idx, const std::string& what);
Vec2 to_vec2(lua_State* L, int idx, const std::string& what);  // finite
// the table at idx must be a list 1..n without holes or named keys
std::vector<lua_Integer> check_sequence(lua_State* L, int idx, const std::string& what);
// The arguments of an API function, checked by one helper for every function and method:
//   check_args(L, "beltsim.step", {{"t", kNumber}, {"from", kNumber}, {"to", kNumber}});
// Too few or too many arguments, or one of the wrong type, is an error naming the call, e.g.
//   "beltsim.step(t, from, to): expected 3 arguments, got 4"
//   "beltsim.step(t, from, to): argument 2 (from): number expected, got string"
// A method's arguments start at 2 (`first`): the object is checked by its own helper.
enum ArgType : unsigned { kNumber = 1, kString = 2, kTable = 4, kFunction = 8, kBoolean = 16, kNil = 32 };
struct Arg {
  const char* name;
  unsigned types;         // ArgType bits
  bool optional = false;  // may be left out (or nil); only at the end
};
void check_args(lua_State* L, const std::string& function, std::initializer_list<Arg> args, int first = 1);

// t[key] = v for the table on the top of the stack (the results' tables)
void set_number(lua_State* L, const char* key, double v);

// Gives the table on the stack top a metatable (one per `kind`) under which reading a field not
// in `fields` is an error with a suggestion, "sim:pulley's table has no field 'omgea' (did you
// mean 'omega'?); its fields: ...", not a nil that fails later; a field of `fields` the table
// lacks (one only some have: a tensioner arm's arm_angle) reads nil. `kind` names the table
// ("sim:pulley's table"). The results' tables of sim:pulley, sim:element, sim:energy.
// The table's metatable also holds the units of its fields (set_units; kUnits' of io/units.hpp,
// whose table names these results' fields).
void strict_fields(lua_State* L, const char* kind, std::initializer_list<const char*> fields);

// The units of a result table's fields, which the console's printer shows after them
// (console_print.cpp): the table kUnitsField of the table's metatable, field name -> unit ("" for
// a dimensionless number). A field it does not name has no unit known, and prints none.
inline constexpr const char* kUnitsField = "__units";
// records unit as the unit of the field `name` of the table at idx, in its metatable (one of its
// own made when it has none: not a metatable tables share)
void set_unit(lua_State* L, int idx, const std::string& name, const std::string& unit);

// __index of an object whose methods are in the table of upvalue 1 (its kind, e.g. "sim", in
// upvalue 2): an unknown name is an error with a suggestion, not a nil to call
int index_methods(lua_State* L);

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
