#include "script/console_complete.hpp"

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <readline/readline.h>

#include "script/console_print.hpp"

#include "lauxlib.h"
#include "lua.h"

namespace beltsim::script {

namespace {

lua_State* g_L = nullptr;
std::vector<std::string> g_matches;

// pushes the value the dotted path names (globals first), or nil
void push_path(lua_State* L, const std::string& path) {
  lua_pushglobaltable(L);
  size_t pos = 0;
  while (pos < path.size()) {
    const size_t dot = path.find('.', pos);
    const std::string part = path.substr(pos, dot == std::string::npos ? std::string::npos : dot - pos);
    if (!lua_istable(L, -1)) {
      lua_pop(L, 1);
      lua_pushnil(L);
      return;
    }
    lua_pushstring(L, part.c_str());
    lua_rawget(L, -2);  // raw: completing never runs Lua code (an __index could fail or loop)
    lua_remove(L, -2);
    if (dot == std::string::npos) break;
    pos = dot + 1;
  }
}

// the keys of the value on the top (a table, or a userdata's methods), popping it
void keys_of(lua_State* L, std::vector<std::pair<std::string, bool>>& out) {
  const int v = lua_gettop(L);
  auto from_table = [&](int t) {
    lua_pushnil(L);
    while (lua_next(L, t)) {
      if (lua_type(L, -2) == LUA_TSTRING) out.push_back({lua_tostring(L, -2), lua_isfunction(L, -1)});
      lua_pop(L, 1);
    }
  };
  if (lua_istable(L, v)) from_table(v);
  if (lua_getmetatable(L, v)) {
    const int mt = lua_gettop(L);
    for (const char* k : {"methods", "__index"}) {
      lua_pushstring(L, k);
      lua_rawget(L, mt);
      if (lua_istable(L, -1)) from_table(lua_gettop(L));
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
  }
  lua_settop(L, v - 1);
}

char* next_match(const char*, int state) {
  static size_t k = 0;
  if (state == 0) k = 0;
  return k < g_matches.size() ? strdup(g_matches[k++].c_str()) : nullptr;
}

char** complete(const char* text, int, int) {
  rl_attempted_completion_over = 1;  // never file names
  rl_completion_append_character = '\0';
  g_matches.clear();
  const std::string word = text;
  const size_t sep = word.find_last_of(".:");
  const std::string prefix = sep == std::string::npos ? "" : word.substr(0, sep + 1);
  const std::string partial = sep == std::string::npos ? word : word.substr(sep + 1);
  lua_State* L = g_L;
  if (!L) return nullptr;
  std::vector<std::pair<std::string, bool>> keys;
  if (prefix.empty()) {
    lua_pushglobaltable(L);
    keys_of(L, keys);
    for (const char* kw : {"and", "break", "do", "else", "elseif", "end", "false", "for", "function", "if", "in",
                           "local", "nil", "not", "or", "repeat", "return", "then", "true", "until", "while"})
      keys.push_back({kw, false});
  } else {
    push_path(L, prefix.substr(0, prefix.size() - 1));
    keys_of(L, keys);
  }
  const bool method = !prefix.empty() && prefix.back() == ':';
  std::set<std::string> done;
  for (const auto& [k, fn] : keys) {
    if (k.compare(0, partial.size(), partial) != 0 || !is_identifier(k) || done.count(k)) continue;
    if (!prefix.empty() && k.rfind("__", 0) == 0) continue;
    if (method && !fn) continue;
    done.insert(k);
    g_matches.push_back(prefix + k + (fn ? "(" : ""));
  }
  std::sort(g_matches.begin(), g_matches.end());
  if (g_matches.empty()) return nullptr;
  return rl_completion_matches(text, next_match);
}

}  // namespace

void complete_from(lua_State* L) {
  g_L = L;
  rl_attempted_completion_function = L ? complete : nullptr;
}

}  // namespace beltsim::script
