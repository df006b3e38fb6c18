#include "script/console_complete.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include <readline/readline.h>

#include "script/console_print.hpp"
#include "script/lua_help.hpp"
#include "script/lua_sim.hpp"

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

// Where the cursor is when it is inside a string literal that is an argument of a call: the call
// `receiver:method(` (receiver "" for a global function), the argument's number, or inside the
// call's table argument the field's key ("" for the list part), and where the string's text starts.
struct StringSlot {
  std::string receiver, method, key;
  bool in_table = false;
  int arg = 1;
  size_t text_start = 0;
};

bool name_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// the call whose name ends just before `end` in line (`sim:pulley`, `help`), after blanks
bool callee(const std::string& line, size_t end, StringSlot& slot) {
  while (end > 0 && std::isspace(static_cast<unsigned char>(line[end - 1]))) --end;
  size_t b = end;
  while (b > 0 && (name_char(line[b - 1]) || line[b - 1] == '.' || line[b - 1] == ':')) --b;
  const std::string name = line.substr(b, end - b);
  if (name.empty() || !is_identifier(name.substr(name.find_last_of(".:") + 1))) return false;
  const size_t colon = name.rfind(':');
  slot.receiver = colon == std::string::npos ? "" : name.substr(0, colon);
  slot.method = colon == std::string::npos ? name : name.substr(colon + 1);
  return true;
}

// the slot of the string the line (up to the cursor) ends inside, if it is a call's argument
bool string_slot(const std::string& line, StringSlot& slot) {
  struct Open {
    char c;
    size_t at, item;  // the bracket's position, where its current item starts
    int commas;
  };
  std::vector<Open> open;
  char quote = 0;
  size_t quote_at = 0;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (quote) {
      if (c == '\\') ++i;
      else if (c == quote) quote = 0;
    } else if (c == '"' || c == '\'') {
      quote = c, quote_at = i;
    } else if (c == '-' && i + 1 < line.size() && line[i + 1] == '-') {
      return false;  // a comment
    } else if (c == '(' || c == '{' || c == '[') {
      open.push_back({c, i, i + 1, 0});
    } else if (c == ')' || c == '}' || c == ']') {
      if (!open.empty()) open.pop_back();
    } else if ((c == ',' || c == ';') && !open.empty()) {
      open.back().commas++, open.back().item = i + 1;
    }
  }
  if (!quote || open.empty() || open.back().c == '[') return false;
  const Open& o = open.back();
  std::string item = line.substr(o.item, quote_at - o.item);
  const size_t eq = item.find('=');
  std::string key = item.substr(0, eq == std::string::npos ? 0 : eq);
  auto blank = [](const std::string& t) {
    return std::all_of(t.begin(), t.end(), [](char c) { return std::isspace(static_cast<unsigned char>(c)); });
  };
  key.erase(std::remove_if(key.begin(), key.end(), [](char c) { return std::isspace(static_cast<unsigned char>(c)); }),
            key.end());
  const bool positional = eq == std::string::npos && blank(item);
  const bool field = eq != std::string::npos && blank(item.substr(eq + 1)) && is_identifier(key);
  if (!positional && !field) return false;
  slot.text_start = quote_at + 1;
  if (o.c == '(') {
    if (!key.empty()) return false;
    slot.arg = o.commas + 1;
    return callee(line, o.at, slot);
  }
  slot.in_table = true;
  slot.key = key;
  size_t before = o.at;  // f{ ... } or f({ ... }) as the call's first argument
  while (before > 0 && std::isspace(static_cast<unsigned char>(line[before - 1]))) --before;
  if (before > 0 && line[before - 1] == '(' && open.size() >= 2 && open[open.size() - 2].commas == 0)
    return callee(line, before - 1, slot);
  return callee(line, before, slot);
}

// completion inside a string argument: the names the call takes there (lua_sim.hpp
// argument_names, help's entries); false when the cursor is not in such a string
bool complete_string(lua_State* L, int start, int end) {
  StringSlot slot;
  if (!rl_line_buffer || !string_slot(std::string(rl_line_buffer, static_cast<size_t>(end)), slot)) return false;
  if (static_cast<size_t>(start) < slot.text_start) return false;
  std::vector<std::string> names;
  if (slot.receiver.empty()) {
    if (slot.method == "help" && !slot.in_table && slot.arg == 1)
      for (const HelpEntry& h : api_help()) names.push_back(h.name);
  } else {
    push_path(L, slot.receiver);
    names = argument_names(L, -1, slot.method, slot.in_table, slot.arg, slot.key);
    lua_pop(L, 1);
  }
  // readline's word may start after the string's first characters (a break character inside it)
  const std::string typed(rl_line_buffer + slot.text_start, rl_line_buffer + end);
  const size_t skip = static_cast<size_t>(start) - slot.text_start;
  std::set<std::string> done;
  for (const std::string& n : names)
    if (n.compare(0, typed.size(), typed) == 0 && done.insert(n).second) g_matches.push_back(n.substr(skip));
  rl_completion_append_character = rl_line_buffer[slot.text_start - 1];  // closes the string on a single match
  return true;
}

char* next_match(const char*, int state) {
  static size_t k = 0;
  if (state == 0) k = 0;
  return k < g_matches.size() ? strdup(g_matches[k++].c_str()) : nullptr;
}

char** complete(const char* text, int start, int end) {
  rl_attempted_completion_over = 1;  // never file names
  rl_completion_append_character = '\0';
  g_matches.clear();
  lua_State* L = g_L;
  if (!L) return nullptr;
  if (complete_string(L, start, end)) {
    std::sort(g_matches.begin(), g_matches.end());
    return g_matches.empty() ? nullptr : rl_completion_matches(text, next_match);
  }
  const std::string word = text;
  const size_t sep = word.find_last_of(".:");
  const std::string prefix = sep == std::string::npos ? "" : word.substr(0, sep + 1);
  const std::string partial = sep == std::string::npos ? word : word.substr(sep + 1);
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
