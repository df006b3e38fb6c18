#include "script/lua_check.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string_view>
#include <utility>

#include "io/number_text.hpp"
#include "io/suggest.hpp"
#include "io/units.hpp"
#include "script/key_line.hpp"

namespace beltsim::script {

[[noreturn]] void fail(lua_State* L, const std::string& msg) {
  fail_at(L, message_path(msg), msg);
}

[[noreturn]] void fail_on(lua_State* L, const std::string& what, const std::string& reason) {
  fail_at(L, parse_path(what), what + ": " + reason);
}

[[noreturn]] void fail_at(lua_State* L, const KeyPath& path, const std::string& msg) {
  // "file:line:" of the calling script line, or of the line in the call's table constructor
  // where the key `path` was written (key_line.hpp)
  lua_Debug ar;
  std::optional<int> line;
  if (lua_getstack(L, 1, &ar) && lua_getinfo(L, "Sl", &ar) && ar.currentline > 0 && ar.source[0] == '@') {
    try {
      line = key_line_in_file(ar.source + 1, ar.currentline, path);
    } catch (const std::exception&) {  // (no memory for the text): the call's line
    }
  }
  if (line) {
    lua_pushfstring(L, "%s:%d: %s", ar.short_src, *line, msg.c_str());
    lua_error(L);
  }
  luaL_error(L, "%s", msg.c_str());
  __builtin_unreachable();  // lua_error unwinds (longjmp, or a C++ throw here)
}

bool has(lua_State* L, int idx, const char* key) {
  const bool present = lua_getfield(L, idx, key) != LUA_TNIL;
  lua_pop(L, 1);
  return present;
}

void check_keys(lua_State* L, int idx, const std::string& where, const std::vector<std::string>& allowed) {
  idx = lua_absindex(L, idx);
  lua_pushnil(L);
  while (lua_next(L, idx)) {
    lua_pop(L, 1);
    if (lua_type(L, -1) != LUA_TSTRING) fail_on(L, where, "expected named keys (key = value), got a list entry");
    const std::string key = lua_tostring(L, -1);
    bool ok = false;
    for (const auto& a : allowed) ok = ok || a == key;
    if (!ok) {
      KeyPath path = parse_path(where, false);  // (the key's line: in `where`'s table)
      if (!path.empty()) path.chain.push_back(key);
      fail_at(L, path,
              "unknown key '" + key + "' in " + where + did_you_mean(key, allowed) + "; valid keys: " + join(allowed));
    }
  }
}

std::string type_name(lua_State* L, int idx) {
  // with the value where it is short: an error that says "got number 2.5" or "got string 'abc'"
  // shows what was given, where "got number" left the reader to find it
  constexpr size_t kShown = 40;
  switch (lua_type(L, idx)) {
    case LUA_TNUMBER: {
      // as Lua writes it: a float of whole value with ".0" (n = 6/2 is "3.0", which is no integer)
      std::string text = number_text(lua_tonumber(L, idx));
      if (!lua_isinteger(L, idx) && text.find_first_of(".eEni") == std::string::npos) text += ".0";
      return "number " + text;
    }
    case LUA_TBOOLEAN:
      return lua_toboolean(L, idx) ? "boolean true" : "boolean false";
    case LUA_TSTRING: {
      size_t len = 0;
      const char* c = lua_tolstring(L, idx, &len);
      size_t cut = std::min({len, kShown, std::string_view(c, len).find('\0')});
      while (cut < len && cut > 0 && (static_cast<unsigned char>(c[cut]) & 0xC0) == 0x80)
        --cut;  // not inside a UTF-8 character
      const std::string text(c, cut);
      return "string '" + text + (text.size() < len ? "...'" : "'");
    }
    default:
      return luaL_typename(L, idx);
  }
}

// value of t[key] pushed; returns false (and pushes nothing) when nil
bool field(lua_State* L, int idx, const char* key) {
  lua_getfield(L, idx, key);
  if (lua_isnil(L, -1)) {
    lua_pop(L, 1);
    return false;
  }
  return true;
}

double to_number(lua_State* L, int idx, const std::string& what) {
  // (a string's text shown too: a number in quotes, a --set value given as "25")
  if (lua_type(L, idx) != LUA_TNUMBER) fail_on(L, what, "number expected, got " + type_name(L, idx));
  return lua_tonumber(L, idx);
}

std::optional<double> opt_number(lua_State* L, int t, const char* key, const std::string& where) {
  if (!field(L, t, key)) return std::nullopt;
  const double v = to_number(L, -1, where + "." + key);
  lua_pop(L, 1);
  return v;
}

std::string to_string(lua_State* L, int idx, const std::string& what) {
  if (lua_type(L, idx) != LUA_TSTRING) fail_on(L, what, std::string("string expected, got ") + type_name(L, idx));
  size_t len = 0;
  const char* c = lua_tolstring(L, idx, &len);
  std::string s(c, len);
  if (s.find('\0') != std::string::npos) fail_on(L, what, "a string without NUL characters expected");
  return s;
}

std::optional<std::string> opt_string(lua_State* L, int t, const char* key, const std::string& where) {
  if (!field(L, t, key)) return std::nullopt;
  std::string s = to_string(L, -1, where + "." + key);
  lua_pop(L, 1);
  return s;
}

std::optional<size_t> opt_choice(lua_State* L, int t, const char* key, const std::string& where,
                                 const std::vector<std::string>& choices) {
  const std::optional<std::string> v = opt_string(L, t, key, where);
  if (!v) return std::nullopt;
  for (size_t k = 0; k < choices.size(); ++k)
    if (*v == choices[k]) return k;
  std::vector<std::string> quoted;
  for (const std::string& c : choices) quoted.push_back("'" + c + "'");
  fail_on(L, where + "." + key, or_list(quoted) + " expected, got '" + *v + "'" + did_you_mean(*v, choices));
}

std::optional<bool> opt_bool(lua_State* L, int t, const char* key, const std::string& where) {
  if (!field(L, t, key)) return std::nullopt;
  if (lua_type(L, -1) != LUA_TBOOLEAN)
    fail_on(L, where + "." + key, std::string("boolean expected, got ") + type_name(L, -1));
  const bool b = lua_toboolean(L, -1);
  lua_pop(L, 1);
  return b;
}

int to_integer(lua_State* L, int idx, const std::string& what) {
  const double v = to_number(L, idx, what);
  if (v != std::floor(v) || std::abs(v) > 1e9) {
    fail_on(L, what, std::string("a whole number expected (got ") + rounded_text(v) + ")");
  }
  return static_cast<int>(v);
}

void require_table(lua_State* L, int idx, const std::string& what) {
  if (!lua_istable(L, idx)) fail_on(L, what, std::string("table expected, got ") + type_name(L, idx));
}

Vec2 to_vec2(lua_State* L, int idx, const std::string& what) {
  idx = lua_absindex(L, idx);
  if (!lua_istable(L, idx)) fail_on(L, what, std::string("a point {x, y} in metres expected, got ") + type_name(L, idx));
  if (const lua_Unsigned n = lua_rawlen(L, idx); n != 2)  // {0.25}: a coordinate left out
    fail_on(L, what,
            "a point {x, y} in metres expected, got a table of " + std::to_string(n) + (n == 1 ? " value" : " values"));
  Vec2 v;
  for (int k = 0; k < 2; ++k) {
    lua_rawgeti(L, idx, k + 1);
    v[k] = to_number(L, -1, what);
    lua_pop(L, 1);
    if (!std::isfinite(v[k])) {
      fail_on(L, what,
              std::string("a finite point {x, y} in metres expected (got ") + (k ? "y" : "x") + " = " +
                  rounded_text(v[k]) + ")");
    }
  }
  return v;
}

std::vector<lua_Integer> check_sequence(lua_State* L, int idx, const std::string& what) {
  idx = lua_absindex(L, idx);
  const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, idx));
  lua_Integer count = 0;
  lua_pushnil(L);
  while (lua_next(L, idx)) {
    lua_pop(L, 1);
    count++;
    if (!lua_isinteger(L, -1) || lua_tointeger(L, -1) < 1 || lua_tointeger(L, -1) > n)
      fail_on(L, what, "a list without holes or named keys expected");
  }
  if (count != n) fail_on(L, what, "a list without holes expected (an entry is nil)");
  std::vector<lua_Integer> k(static_cast<size_t>(n));
  for (lua_Integer i = 0; i < n; ++i) k[static_cast<size_t>(i)] = i + 1;
  return k;
}

void check_args(lua_State* L, const std::string& function, std::initializer_list<Arg> args, int first) {
  std::string sig = function + "(";
  int required = 0;
  for (const Arg& a : args) {
    sig += std::string(&a == args.begin() ? "" : ", ") + (a.optional ? "[" : "") + a.name + (a.optional ? "]" : "");
    if (!a.optional) required++;
  }
  sig += ")";
  const int n = lua_gettop(L) - (first - 1);
  const int max = static_cast<int>(args.size());
  if (n < required || n > max) {
    std::ostringstream s;
    s << sig << ": expected " << required;
    if (max > required) s << " to " << max;
    s << " argument" << (max == 1 && required == 1 ? "" : "s") << ", got " << n;
    fail_at(L, {}, s.str());  // (about the call, not a key)
  }
  int k = 0;
  for (const Arg& a : args) {
    const int idx = first + k++;
    const int t = lua_type(L, idx);
    if (a.optional && t == LUA_TNONE) break;
    if (a.optional && t == LUA_TNIL) continue;
    unsigned bit = 0;
    for (auto [lt, b] : {std::pair{LUA_TNUMBER, kNumber}, std::pair{LUA_TSTRING, kString}, std::pair{LUA_TTABLE, kTable},
                         std::pair{LUA_TFUNCTION, kFunction}, std::pair{LUA_TBOOLEAN, kBoolean}, std::pair{LUA_TNIL, kNil}})
      if (t == lt) bit = b;
    if (a.types & bit) continue;
    std::vector<std::string> names;
    for (auto [b, name] : {std::pair{kNumber, "number"}, std::pair{kString, "string"}, std::pair{kTable, "table"},
                           std::pair{kFunction, "function"}, std::pair{kBoolean, "boolean"}, std::pair{kNil, "nil"}})
      if (a.types & b) names.push_back(name);
    std::string expected;
    for (size_t i = 0; i < names.size(); ++i)
      expected += (i == 0 ? "" : i + 1 == names.size() ? " or " : ", ") + names[i];
    fail_at(L, {},
            sig + ": argument " + std::to_string(k) + " (" + a.name + "): " + expected + " expected, got " +
                type_name(L, idx));
  }
}

void set_number(lua_State* L, const char* key, double v) {
  lua_pushnumber(L, v);
  lua_setfield(L, -2, key);
}

namespace {

// __index of a results' table (strict_fields): upvalue 1 its kind, upvalue 2 the set of its fields
int index_fields(lua_State* L) {
  if (lua_type(L, 2) != LUA_TSTRING) return lua_pushnil(L), 1;
  lua_pushvalue(L, 2);
  if (lua_rawget(L, lua_upvalueindex(2)) != LUA_TNIL) return lua_pushnil(L), 1;  // a field it may lack
  std::vector<std::string> names;
  lua_pushnil(L);
  while (lua_next(L, lua_upvalueindex(2))) {
    lua_pop(L, 1);
    names.push_back(lua_tostring(L, -1));
  }
  std::sort(names.begin(), names.end());
  // its fields are those this table has: the kind's others (a tensioner arm's on a plain pulley)
  // it lacks (a user's trial found them listed); a misspelling is matched against all of them
  std::vector<std::string> has;
  lua_pushnil(L);
  while (lua_next(L, 1)) {
    lua_pop(L, 1);
    if (lua_type(L, -1) == LUA_TSTRING) has.push_back(lua_tostring(L, -1));
  }
  std::sort(has.begin(), has.end());
  const std::string name = lua_tostring(L, 2);
  fail_at(L, {},
          std::string(lua_tostring(L, lua_upvalueindex(1))) + " has no field '" + name + "'" +
              did_you_mean(name, names) + "; its fields: " + join(has));
}

}  // namespace

void strict_fields(lua_State* L, const char* kind, std::initializer_list<const char*> fields) {
  // kept in the registry (not luaL_newmetatable's, whose __name would change what tostring says)
  const std::string key = std::string("beltsim.fields.") + kind;
  if (lua_getfield(L, LUA_REGISTRYINDEX, key.c_str()) == LUA_TNIL) {
    lua_pop(L, 1);
    lua_createtable(L, 0, 2);
    lua_pushstring(L, kind);
    lua_createtable(L, 0, static_cast<int>(fields.size()));
    for (const char* f : fields) lua_pushboolean(L, 1), lua_setfield(L, -2, f);
    lua_pushcclosure(L, index_fields, 2);
    lua_setfield(L, -2, "__index");
    lua_createtable(L, 0, static_cast<int>(fields.size()));
    for (const char* f : fields)
      if (const std::optional<std::string> unit = known_unit(f))
        lua_pushstring(L, unit->c_str()), lua_setfield(L, -2, f);
    lua_setfield(L, -2, kUnitsField);
    lua_pushvalue(L, -1);
    lua_setfield(L, LUA_REGISTRYINDEX, key.c_str());
  }
  lua_setmetatable(L, -2);
}

void set_unit(lua_State* L, int idx, const std::string& name, const std::string& unit) {
  idx = lua_absindex(L, idx);
  if (!lua_getmetatable(L, idx)) {
    lua_createtable(L, 0, 1);
    lua_pushvalue(L, -1);
    lua_setmetatable(L, idx);
  }
  if (lua_getfield(L, -1, kUnitsField) != LUA_TTABLE) {
    lua_pop(L, 1);
    lua_newtable(L);
    lua_pushvalue(L, -1);
    lua_setfield(L, -3, kUnitsField);
  }
  lua_pushstring(L, unit.c_str());
  lua_setfield(L, -2, name.c_str());
  lua_pop(L, 2);
}

int index_methods(lua_State* L) {
  lua_pushvalue(L, 2);
  if (lua_rawget(L, lua_upvalueindex(1)) != LUA_TNIL || lua_type(L, 2) != LUA_TSTRING) return 1;
  const std::string kind = lua_tostring(L, lua_upvalueindex(2)), name = lua_tostring(L, 2);
  std::vector<std::string> names;
  lua_pushnil(L);
  while (lua_next(L, lua_upvalueindex(1))) {
    lua_pop(L, 1);
    if (lua_type(L, -1) == LUA_TSTRING) names.push_back(lua_tostring(L, -1));
  }
  std::sort(names.begin(), names.end());
  fail_at(L, {},
          kind + " has no field or method '" + name + "'" + did_you_mean(name, names) + "; it has: " + join(names));
}

}  // namespace beltsim::script
