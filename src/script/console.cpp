#include "script/console.hpp"

#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <set>
#include <sstream>

#include <readline/history.h>
#include <readline/readline.h>

#include "io/output_dir.hpp"
#include "io/units.hpp"
#include "script/context.hpp"
#include "script/limits.hpp"
#include "term/term_image.hpp"

#include "lauxlib.h"
#include "lua.h"

namespace beltsim::script {

namespace {

// ---- signals (lua.c's laction/lstop, plus readline) ------------------------------------------

lua_State* g_L = nullptr;
Interpreter* g_lua = nullptr;
std::atomic<bool>* g_stop = nullptr;
volatile sig_atomic_t g_at_prompt = 0, g_sigint = 0;
// a SIGTERM was received. Atomic: two sent back to back can be handled at once by two threads (the
// encoder's, llvmpipe's), and exactly one of them must find it unset (lock-free: safe in a handler)
std::atomic<int> g_sigterm{0};
bool g_cancelled = false;

void on_sigint(int) {
  if (g_at_prompt) {
    g_sigint = 1;  // read() returns EINTR; console_getc clears the line
    return;
  }
  if (g_stop) g_stop->store(true);  // run_to stops at the last finished step
  // Lua code (a loop, a callback) raises "interrupted!" within a slice of instructions: the
  // interpreter's one count hook (limits.hpp) sees the flag; the hook is never swapped here
  if (g_lua) g_lua->interrupt();
}

// SIGTERM: a run stops as for Ctrl-C, Lua code stops, and the console leaves as for Ctrl-D (every
// output closed), exit status 143; a second SIGTERM ends the process at once
void on_sigterm(int) {
  if (g_sigterm.exchange(1) != 0) {  // a stop is under way: this one ends the process
    std::signal(SIGTERM, SIG_DFL);
    std::raise(SIGTERM);
    return;
  }
  if (g_stop) g_stop->store(true);
  if (g_lua) g_lua->interrupt();
}

// readline's input: Ctrl-C at the prompt ends the line, emptied. SIGINT is blocked except while
// waiting in ppoll, so a Ctrl-C that comes while readline is busy (echoing, redrawing) is seen at
// the next wait instead of being lost.
int console_getc(FILE* f) {
  sigset_t block, orig;
  sigemptyset(&block);
  sigaddset(&block, SIGINT);
  sigaddset(&block, SIGTERM);
  for (;;) {
    sigprocmask(SIG_BLOCK, &block, &orig);
    if (g_sigterm) {  // the line is dropped (not run), then readline returns NULL as for Ctrl-D
      sigprocmask(SIG_SETMASK, &orig, nullptr);
      rl_replace_line("", 0);
      return EOF;
    }
    if (g_sigint) {
      sigprocmask(SIG_SETMASK, &orig, nullptr);
      g_sigint = 0;
      g_cancelled = true;
      rl_replace_line("", 0);
      return '\n';
    }
    pollfd p{fileno(f), POLLIN, 0};
    const int r = ppoll(&p, 1, nullptr, &orig);  // SIGINT and SIGTERM may arrive only while waiting here
    sigprocmask(SIG_SETMASK, &orig, nullptr);
    if (r < 0) {
      if (errno == EINTR) continue;
      return EOF;
    }
    unsigned char c;
    const ssize_t n = read(fileno(f), &c, 1);
    if (n == 1) return c;
    if (n == 0) return EOF;
    if (errno != EINTR) return EOF;
  }
}

// ---- pretty printing -------------------------------------------------------------------------

constexpr int kMaxItems = 12;  // list entries shown before "... N more"
constexpr int kMaxDepth = 3;

std::string number(lua_State* L, int idx) {
  char b[64];
  if (lua_isinteger(L, idx))
    std::snprintf(b, sizeof b, "%lld", static_cast<long long>(lua_tointeger(L, idx)));
  else
    std::snprintf(b, sizeof b, "%.10g", lua_tonumber(L, idx));
  return b;
}

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
  bool flat = n + static_cast<lua_Integer>(names.size()) <= 6 && other.empty();
  for (const std::string& k : names) flat = flat && unit_of(k).empty();
  if (flat) {
    for (lua_Integer k = 1; k <= n && flat; ++k) flat = lua_rawgeti(L, idx, k) != LUA_TTABLE, lua_pop(L, 1);
    for (const std::string& k : names) flat = flat && (lua_getfield(L, idx, k.c_str()), scalar(L, -1)), lua_pop(L, 1);
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
    item((is_identifier(k) ? k : "[" + quoted(k.data(), k.size()) + "]") + " = ", unit_of(k));
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
      out += quoted(s, len);
      break;
    }
    case LUA_TTABLE: pretty_table(L, idx, out, depth, seen); break;
    default:
      out += luaL_tolstring(L, idx, nullptr);
      lua_pop(L, 1);
  }
}

// ---- running chunks --------------------------------------------------------------------------

int msghandler(lua_State* L) {
  const char* msg = lua_tostring(L, 1);
  if (!msg) {
    if (luaL_callmeta(L, 1, "__tostring") && lua_type(L, -1) == LUA_TSTRING) return 1;
    msg = lua_pushfstring(L, "(error object is a %s value)", luaL_typename(L, 1));
  }
  luaL_traceback(L, L, msg, 1);
  return 1;
}

// the traceback without the console's own frames ("[C]: in ?")
std::string short_traceback(const std::string& tb) {
  std::istringstream in(tb);
  std::string line, out;
  int frames = 0;
  while (std::getline(in, line)) {
    if (line.find("[C]: in ?") != std::string::npos) continue;
    if (line.rfind("\t", 0) == 0 && ++frames > 6) continue;
    out += line + "\n";
  }
  return out;
}

enum class Compile { ok, incomplete, error };

// lua.c: try "return <chunk>" first, so that an expression prints its value
Compile compile(lua_State* L, const std::string& chunk, bool& expression) {
  const std::string ret = "return " + chunk + ";";
  if (luaL_loadbufferx(L, ret.data(), ret.size(), "=stdin", "t") == LUA_OK) {
    expression = true;
    return Compile::ok;
  }
  lua_pop(L, 1);
  expression = false;
  const int status = luaL_loadbufferx(L, chunk.data(), chunk.size(), "=stdin", "t");
  if (status == LUA_OK) return Compile::ok;
  size_t len = 0;
  const char* msg = lua_tolstring(L, -1, &len);
  if (status == LUA_ERRSYNTAX && len >= 5 && std::strcmp(msg + len - 5, "<eof>") == 0) {
    lua_pop(L, 1);
    return Compile::incomplete;
  }
  return Compile::error;
}

// prints its arguments as the console shows values; called protected, since a __tostring
// metamethod is Lua code that may fail or loop
int print_values(lua_State* L) {
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

// calls the function below the `nargs` values on the stack top with the message handler; the
// error's text, or "" (the results, if any, are left on the stack)
std::string protected_call(lua_State* L, int nargs, int nresults) {
  const int fn = lua_gettop(L) - nargs;
  lua_pushcfunction(L, msghandler);
  lua_insert(L, fn);
  std::string error;
  int status = LUA_OK;
  try {
    status = lua_pcall(L, nargs, nresults, fn);
  } catch (const std::exception& e) {  // a C++ error that escaped a binding
    status = LUA_ERRRUN;
    lua_settop(L, fn);
    error = e.what();
  }
  if (status != LUA_OK && error.empty() && !memory_message(L, status, "stdin", error))
    error = lua_tostring(L, -1) ? lua_tostring(L, -1) : "(error)";
  if (status != LUA_OK) {
    lua_settop(L, fn - 1);
    if (error.empty()) error = "(error)";
  } else {
    lua_remove(L, fn);  // the handler
  }
  return error;
}

// runs the compiled chunk on the stack top; prints results or the error. True when it ran.
bool execute(lua_State* L) {
  const int base = lua_gettop(L) - 1;  // below the chunk
  begin_call(L);  // the instruction budget is per command; no Ctrl-C pending
  const std::string error = protected_call(L, 0, LUA_MULTRET);
  std::string print_error;
  if (error.empty() && lua_gettop(L) > base) {
    // the results, printed (within the same command's budget); the command itself has run
    lua_pushcfunction(L, print_values);
    lua_insert(L, base + 1);
    print_error = protected_call(L, lua_gettop(L) - base - 1, 0);
  }
  if (g_stop) g_stop->store(false);
  lua_settop(L, base);
  if (!error.empty() || !print_error.empty()) {
    std::fprintf(stderr, "%s", short_traceback(error.empty() ? "printing the result: " + print_error : error).c_str());
    std::fflush(stderr);
  }
  return error.empty();
}

// ---- completion ------------------------------------------------------------------------------

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

// ---- the session -----------------------------------------------------------------------------

// the name of the global holding the value with this address, or ""
std::string global_named(lua_State* L, const void* p) {
  std::string name;
  lua_pushglobaltable(L);
  lua_pushnil(L);
  while (lua_next(L, -2)) {
    if (lua_type(L, -2) == LUA_TSTRING && lua_topointer(L, -1) == p) name = lua_tostring(L, -2);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  return name;
}

// a command as session.lua replays it: one whose run Ctrl-C stopped becomes run_to(where it
// stopped), so the replay stops at the same step end (and gives the same outputs)
std::string replayable(lua_State* L, const std::string& chunk, const std::vector<std::pair<const void*, double>>& stopped) {
  if (stopped.empty()) return chunk;
  std::string out = "-- " + chunk;
  for (size_t k = 0; k < out.size(); ++k)
    if (out[k] == '\n') out.insert(k + 1, "-- ");
  out += "  -- stopped by Ctrl-C";
  for (const auto& [p, t] : stopped) {
    char b[64];
    std::snprintf(b, sizeof b, ":run_to(%.17g)", t);
    const std::string name = global_named(L, p);
    out += "\n" + (name.empty() ? "-- (a simulation not held by a global)" : name) + b;
  }
  return out;
}

std::string history_path() {
  if (const char* h = std::getenv("BELTSIM_HISTORY")) return h;
  if (const char* home = std::getenv("HOME")) return std::string(home) + "/.beltsim_history";
  return ".beltsim_history";
}

// `text` as a Lua long string: [==[ ... ]==] with as many '=' as it takes
std::string long_string(const std::string& text) {
  std::string eq;
  while (text.find("]" + eq + "]") != std::string::npos) eq += '=';
  return "[" + eq + "[\n" + text + "\n]" + eq + "]";  // the first newline is not part of the string
}

// s as one word of a POSIX shell command line: as it is when it holds only characters no shell
// treats specially, else in single quotes ('\'' for a quote); with a control character (a
// newline would end session.lua's comment line) as bash's $'...' with escapes
std::string shell_word(const std::string& s) {
  auto plain = [](unsigned char c) { return std::isalnum(c) || (c != 0 && std::strchr("_./=:,+-@%", c)); };
  if (!s.empty() && std::all_of(s.begin(), s.end(), plain)) return s;
  const bool control = std::any_of(s.begin(), s.end(), [](unsigned char c) { return c < 0x20 || c == 0x7f; });
  if (!control) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
  }
  std::string q = "$'";
  for (unsigned char c : s) {
    if (c == '\'' || c == '\\') {
      q += '\\';
      q += static_cast<char>(c);
    } else if (c == '\n') {
      q += "\\n";
    } else if (c == '\t') {
      q += "\\t";
    } else if (c < 0x20 || c == 0x7f) {
      char b[8];
      std::snprintf(b, sizeof b, "\\x%02x", c);
      q += b;
    } else {
      q += static_cast<char>(c);
    }
  }
  return q + "'";
}

void write_session(const std::string& dir, const std::optional<std::string>& script, std::string script_text,
                   const std::vector<std::string>& args, const std::vector<ScriptArg>& sets,
                   const std::vector<std::string>& commands) {
  if (commands.empty()) return;
  namespace fs = std::filesystem;
  const std::string path = (fs::path(dir) / "session.lua").string();
  std::ostringstream f;  // written whole at the end (io/output_dir.hpp: never through a link)
  f << "-- The commands of a beltsim console session that ran without error, in order.\n"
    << "-- Replay with: beltsim run " << shell_word(path);
  // beltsim.args as in the session, each --set quoted for the shell
  for (const ScriptArg& a : sets) f << " --set " << shell_word(a.key + "=" + a.text);
  f << "\n";
  if (script) {
    // the scenario's text is copied in (as it was when the session began), so the replay needs
    // no access to the scenario's folder, which the sandbox would refuse (README, Console)
    f << "-- The scenario " << *script << " is copied below as it was when the session began; its errors\n"
      << "-- name it and its own lines. A scenario that reads files beside it, or whose runs wrote outside\n"
      << "-- this file's folder (out = ..., an argument naming a folder), needs: beltsim run --trusted\n";
    f << "arg = { [0] = " << quoted(script->data(), script->size());
    for (const std::string& a : args) f << ", " << quoted(a.data(), a.size());
    f << " }\n";
    // as luaL_loadfile reads a file: no UTF-8 byte order mark, a first line "#..." skipped (kept
    // as a comment, so the line numbers stay)
    if (script_text.rfind("\xEF\xBB\xBF", 0) == 0) script_text.erase(0, 3);
    if (!script_text.empty() && script_text[0] == '#') script_text.insert(0, "--");
    const std::string chunkname = "@" + *script;
    f << "assert(load(" << long_string(script_text) << ", " << quoted(chunkname.data(), chunkname.size())
      << ", \"t\"))()\n";
  }
  for (const std::string& c : commands) f << c << "\n";
  try {
    write_file_whole(OutputDir(dir), "session.lua", f.str());  // the folder made when missing
  } catch (const std::exception& e) {  // recorded: the exit status says so (app/main.cpp)
    std::fprintf(stderr, "beltsim: %s\n", e.what());
    mark_output_failure_shown(e.what());
    return;
  }
  std::fprintf(stderr, "beltsim: the session's commands are in %s\n", path.c_str());
}

}  // namespace

std::string pretty(lua_State* L, int idx) {
  std::set<const void*> seen;
  std::string s;
  pretty_into(L, idx, s, 0, seen);
  return s;
}

int run_console(const std::optional<std::string>& script, const std::vector<std::string>& args, const Overrides& o,
                const Safety& safety, std::atomic<bool>* stop) {
  const bool interactive = isatty(STDIN_FILENO);
  Interpreter lua(safety);
  lua.set_overrides(o);
  lua.set_stop_flag(stop);
  lua_State* L = lua.state();
  g_L = L;
  g_lua = &lua;
  g_stop = stop;
  Context& ctx = lua.context();
  const bool tty_out = isatty(STDOUT_FILENO);
  ctx.on_picture = [tty_out](const std::string& png) {
    std::string why;
    if (!tty_out || !term::show_image_in_terminal(png, stdout, &why)) std::printf("picture: %s\n", png.c_str());
    std::fflush(stdout);
  };
  // arg as lua.c makes it: arg[0] the script, arg[1..] what follows --
  lua_createtable(L, static_cast<int>(args.size()), 1);
  if (script) lua_pushstring(L, script->c_str()), lua_rawseti(L, -2, 0);
  for (size_t k = 0; k < args.size(); ++k) lua_pushstring(L, args[k].c_str()), lua_rawseti(L, -2, static_cast<int>(k + 1));
  lua_setglobal(L, "arg");

  struct sigaction sa {};
  sa.sa_handler = on_sigint;
  sigemptyset(&sa.sa_mask);
  sa.sa_flags = 0;  // no SA_RESTART: a read at the prompt returns EINTR
  sigaction(SIGINT, &sa, nullptr);
  sa.sa_handler = on_sigterm;  // no SA_RESTART either: a read of standard input returns
  sigaction(SIGTERM, &sa, nullptr);

  bool failed = false;
  std::string script_text;  // as it was when the session began, for session.lua
  if (script) {
    std::ifstream in(*script, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    script_text = text.str();
    try {
      lua.run_file(*script);
      for (const std::string& m : lua.unread_args(*script)) std::fprintf(stderr, "beltsim: warning: %s\n", m.c_str());
    } catch (const ScriptError& e) {
      std::fprintf(stderr, "%s\n", short_traceback(e.what()).c_str());
      failed = true;
    }
    if (stop) stop->store(false);
  } else {
    ctx.default_out = "out/console";
  }

  const std::string hist = history_path();
  if (interactive) {
    std::printf("beltsim 0.1.0 console (Lua 5.4): help() lists the API; Ctrl-C stops a run, Ctrl-D leaves\n");
    std::fflush(stdout);
    rl_readline_name = "beltsim";
    rl_catch_signals = 0;
    rl_getc_function = console_getc;
    rl_attempted_completion_function = complete;
    rl_basic_word_break_characters = const_cast<char*>(" \t\n\"\\'><=;+-*/%^~#{}()[],");
    using_history();
    // append_history does not create the file: make it on first use
    if (std::FILE* f = std::fopen(hist.c_str(), "a")) std::fclose(f);
    read_history(hist.c_str());
  }

  std::vector<std::string> commands;
  std::string chunk;
  for (;;) {
    if (g_sigterm) break;
    std::string line;
    if (interactive) {
      g_at_prompt = 1;
      g_cancelled = false;
      char* in = readline(chunk.empty() ? "> " : ">> ");
      g_at_prompt = 0;
      if (!in) {
        std::printf("\n");
        break;
      }
      line = in;
      std::free(in);
      if (g_cancelled) {
        chunk.clear();
        continue;
      }
      if (!line.empty()) {
        add_history(line.c_str());
        append_history(1, hist.c_str());
        history_truncate_file(hist.c_str(), 1000);
      }
    } else if (!std::getline(std::cin, line)) {
      if (!chunk.empty() && !g_sigterm) {
        std::fprintf(stderr, "stdin: unfinished input at the end: %s\n", chunk.c_str());
        failed = true;
      }
      break;
    }
    chunk = chunk.empty() ? line : chunk + "\n" + line;
    if (chunk.find_first_not_of(" \t") == std::string::npos) {
      chunk.clear();
      continue;
    }
    bool expression = false;
    const Compile c = compile(L, chunk, expression);
    if (c == Compile::incomplete) continue;
    if (c == Compile::error) {
      std::fprintf(stderr, "%s\n", lua_tostring(L, -1));
      lua_pop(L, 1);
      failed = true;
    } else if (ctx.stopped_runs.clear(), execute(L)) {
      commands.push_back(replayable(L, chunk, ctx.stopped_runs));
    } else {
      failed = true;
    }
    chunk.clear();
  }
  g_L = nullptr;
  g_lua = nullptr;
  // the finalisers below run with a fresh budget and no interrupt pending (~Interpreter)
  write_session(o.out ? *o.out : ctx.default_out, script, script_text, args, o.set, commands);  // --out wins, as for the runs
  // the interpreter's end closes every simulation (their finalisers flush and finalise outputs)
  if (g_sigterm) {
    std::fprintf(stderr, "beltsim: terminated; the outputs written so far are kept\n");
    return 143;
  }
  return interactive ? 0 : (failed ? 1 : 0);
}

}  // namespace beltsim::script
