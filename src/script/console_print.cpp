#include "script/console_print.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <set>
#include <utility>
#include <vector>

#include "io/number_text.hpp"
#include "lauxlib.h"
#include "lua.h"
#include "script/lua_check.hpp"
#include "script/progress.hpp"

namespace beltsim::script {

std::string quoted(const char* s, size_t n) {
  std::string q = "\"";
  for (size_t k = 0; k < n; ++k) {
    const char c = s[k];
    if (c == '"' || c == '\\') q += '\\', q += c;
    else if (c == '\n') q += "\\n";
    else if (static_cast<unsigned char>(c) < 32) {
      char b[8];
      std::snprintf(b, sizeof b, "\\%d", c);
      q += b;
    } else {
      q += c;
    }
  }
  return q + "\"";
}

bool is_identifier(const std::string& s) {
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_')) return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_')) return false;
  return true;
}

namespace {

// a string of several lines as a Lua long string, its lines as they print ([[ and a line break,
// which Lua skips, then the text and ]]; as many = between the brackets as keep its own ]] out):
// sim:summary{}'s table text read as one escaped line (a user's trial); NUL and the other control
// characters but the tab keep the quoted form
bool long_string(const char* s, size_t n, std::string& out) {
  if (std::find(s, s + n, '\n') == s + n) return false;
  for (size_t k = 0; k < n; ++k)
    if (static_cast<unsigned char>(s[k]) < 32 && s[k] != '\n' && s[k] != '\t') return false;
  const std::string text(s, n);
  std::string eq;
  while (text.find("]" + eq + "]") != std::string::npos) eq += '=';
  out += "[" + eq + "[\n" + text + "]" + eq + "]";
  return true;
}

constexpr int kMaxItems = 12;  // list entries shown before "... N more"
constexpr int kMaxDepth = 3;

std::string number(lua_State* L, int idx) {
  if (lua_isinteger(L, idx)) return std::to_string(lua_tointeger(L, idx));
  return rounded_text(lua_tonumber(L, idx));
}

void pretty_into(lua_State* L, int idx, std::string& out, int depth, std::set<const void*>& seen);

bool scalar(lua_State* L, int idx) {
  const int t = lua_type(L, idx);
  return t != LUA_TTABLE;
}

void pretty_table(lua_State* L, int idx, std::string& out, int depth, std::set<const void*>& seen) {
  const void* p = lua_topointer(L, idx);
  if (seen.count(p) || depth >= kMaxDepth) {
    out += seen.count(p) ? "{ --[[ cycle ]] }" : "{ ... }";
    return;
  }
  seen.insert(p);
  const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, idx));
  // the named keys, sorted; the list part 1..n in order
  std::vector<std::string> names;
  std::vector<std::pair<std::string, int>> other;  // keys that are neither names nor list indices
  lua_pushnil(L);
  while (lua_next(L, idx)) {
    lua_pop(L, 1);
    if (lua_type(L, -1) == LUA_TSTRING) {
      names.push_back(lua_tostring(L, -1));
    } else if (lua_isinteger(L, -1) && lua_tointeger(L, -1) >= 1 && lua_tointeger(L, -1) <= n) {
      continue;
    } else {
      lua_pushvalue(L, -1);
      other.push_back({luaL_tolstring(L, -1, nullptr), 0});
      lua_pop(L, 2);
    }
  }
  std::sort(names.begin(), names.end());
  // a field's unit as the result that made the table recorded it (lua_check.hpp, kUnitsField);
  // none for a field it does not name and for a table of the user's own
  const auto field_unit = [&](const std::string& k) {
    std::string unit;
    const int units = luaL_getmetafield(L, idx, kUnitsField);  // pushed unless nil
    if (units == LUA_TTABLE && lua_getfield(L, -1, k.c_str()) == LUA_TSTRING) unit = lua_tostring(L, -1);
    if (units == LUA_TTABLE) lua_pop(L, 1);
    if (units != LUA_TNIL) lua_pop(L, 1);
    return unit;
  };
  bool flat = n + static_cast<lua_Integer>(names.size()) <= 6 && other.empty();
  for (const std::string& k : names) flat = flat && field_unit(k).empty();
  // one line only when no entry is a table; each value looked at is popped before the next
  for (lua_Integer k = 1; k <= n && flat; ++k) {
    flat = lua_rawgeti(L, idx, k) != LUA_TTABLE;
    lua_pop(L, 1);
  }
  for (size_t k = 0; k < names.size() && flat; ++k) {
    lua_getfield(L, idx, names[k].c_str());
    flat = scalar(L, -1);
    lua_pop(L, 1);
  }
  if (n == 0 && names.empty() && other.empty()) {
    out += "{}";
    seen.erase(p);
    return;
  }
  const std::string pad(2 * (depth + 1), ' '), end_pad(2 * depth, ' ');
  out += flat ? "{ " : "{\n";
  bool first = true;
  auto item = [&](const std::string& key, const std::string& unit) {
    std::string v;
    pretty_into(L, lua_gettop(L), v, depth + 1, seen);
    if (flat) {
      out += (first ? "" : ", ") + key + v;
    } else {
      out += pad + key + v + ",";
      if (!unit.empty() && lua_type(L, -1) == LUA_TNUMBER) out += " -- " + unit;
      out += "\n";
    }
    first = false;
  };
  const lua_Integer shown = std::min<lua_Integer>(n, kMaxItems);
  for (lua_Integer k = 1; k <= shown; ++k) {
    lua_rawgeti(L, idx, k);
    item("", "");
    lua_pop(L, 1);
  }
  if (n > shown) out += flat ? ", ..." : pad + "-- ... " + std::to_string(n - shown) + " more\n";
  for (const std::string& k : names) {
    lua_getfield(L, idx, k.c_str());
    std::string key = is_identifier(k) ? k : std::string("[");
    if (!is_identifier(k)) key.append(quoted(k.data(), k.size())).append("]");
    key += " = ";
    item(key, field_unit(k));
    lua_pop(L, 1);
  }
  for (const auto& o : other) out += (flat ? "" : pad) + "[" + o.first + "] = ...," + (flat ? " " : "\n");
  out += flat ? " }" : end_pad + "}";
  seen.erase(p);
}

void pretty_into(lua_State* L, int idx, std::string& out, int depth, std::set<const void*>& seen) {
  idx = lua_absindex(L, idx);
  switch (lua_type(L, idx)) {
    case LUA_TNUMBER: out += number(L, idx); break;
    case LUA_TSTRING: {
      size_t len = 0;
      const char* s = lua_tolstring(L, idx, &len);
      if (!long_string(s, len, out)) out += quoted(s, len);
      break;
    }
    case LUA_TTABLE: pretty_table(L, idx, out, depth, seen); break;
    default:
      out += luaL_tolstring(L, idx, nullptr);
      lua_pop(L, 1);
  }
}

}  // namespace

int print_values(lua_State* L) {
  before_stdout();  // beltsim.print from a run's callback: below the progress line, not on it
  const int n = lua_gettop(L);
  std::string line;
  for (int k = 1; k <= n; ++k) {
    std::set<const void*> seen;
    pretty_into(L, k, line, 0, seen);
    line += k < n ? '\t' : '\n';
  }
  std::fputs(line.c_str(), stdout);
  std::fflush(stdout);
  return 0;
}

}  // namespace beltsim::script
