// The sandboxed libraries (see sandbox.hpp). The standard functions that touch files are wrapped:
// the wrapper checks the path, then calls the original with the same arguments.
#include "script/sandbox.hpp"

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "script/context.hpp"
#include "script/docall.hpp"

#include "lauxlib.h"
#include "lua.h"
#include "lualib.h"

namespace beltsim::script {

namespace {

namespace fs = std::filesystem;

constexpr const char* kHow = "beltsim --trusted allows it (docs/limits-and-safety.md)";

// ---- forbidden functions ---------------------------------------------------------------------

int l_forbidden(lua_State* L) {
  return luaL_error(L, "%s is not allowed in a scenario script (the sandbox); %s", lua_tostring(L, lua_upvalueindex(1)),
                    kHow);
}

// t[name] = a function that raises "<lib>.<name> is not allowed"; t on the stack top
void forbid(lua_State* L, const char* lib, const char* name) {
  lua_pushfstring(L, "%s.%s", lib, name);
  lua_pushcclosure(L, l_forbidden, 1);
  lua_setfield(L, -2, name);
}

// ---- paths -----------------------------------------------------------------------------------

// absolute, `..` and symbolic links resolved as far as the path exists
fs::path resolved(const std::string& p) {
  std::error_code ec;
  fs::path a = fs::absolute(p, ec);
  if (ec) a = fs::path(p);
  fs::path c = fs::weakly_canonical(a, ec);
  if (ec) c = a.lexically_normal();
  if (!c.has_filename() && c.has_parent_path() && c != c.root_path()) c = c.parent_path();  // "dir/"
  return c;
}

bool under(const fs::path& p, const fs::path& root) {
  auto i = p.begin();
  for (auto r = root.begin(); r != root.end(); ++r, ++i)
    if (i == p.end() || *i != *r) return false;
  return true;
}

std::string out_folder(const Context& c) { return c.overrides.out ? *c.overrides.out : c.default_out; }

// "" when the sandbox allows the access, else why not: a path under the output folder is read and
// written, one under the script's folder read (and written by beltsim itself: `outputs`)
std::string refusal(const Context& c, const std::string& what, const std::string& path, bool write, bool outputs) {
  if (c.trusted) return "";
  const fs::path p = resolved(path), out = resolved(out_folder(c));
  if (under(p, out)) return "";
  const bool has_script = !c.script_dir.empty();
  const fs::path dir = has_script ? resolved(c.script_dir) : fs::path();
  if ((!write || outputs) && has_script && under(p, dir)) return "";
  std::string allowed = (outputs ? "beltsim's outputs under " : "read and write under ") + out.string();
  if (has_script) allowed += (outputs ? " or " : ", read under ") + dir.string() + " (the script's folder)";
  return what + ": " + (write ? "writing" : "reading") + " '" + path +
         "' is not allowed in a scenario script (the sandbox: " + allowed + "); " + kHow;
}

// raises "file:line: WHAT: reading|writing 'path' is not allowed ..." unless the path is under the
// output folder (read, write) or the script's folder (read)
void check_path(lua_State* L, const Context& c, const char* what, const char* path, bool write) {
  const std::string r = refusal(c, what, path, write, false);
  if (!r.empty()) luaL_error(L, "%s", r.c_str());
}

Context& ctx_up(lua_State* L) { return *static_cast<Context*>(lua_touserdata(L, lua_upvalueindex(2))); }

// "attempt to load a binary chunk (mode is 't')" said plainly
void explain_binary(lua_State* L, int idx, const char* what) {
  idx = lua_absindex(L, idx);
  const char* msg = lua_tostring(L, idx);
  if (msg && std::strstr(msg, "attempt to load a binary chunk")) {
    lua_pushfstring(L, "%s: a precompiled (binary) chunk is never loaded: beltsim loads Lua source only", what);
    lua_replace(L, idx);
  }
}

// ---- io --------------------------------------------------------------------------------------

enum FileAccess { kOpen, kRead, kWrite };

// upvalues: the original function, the Context, the name, the FileAccess. A string first argument is
// a path to check (io.open: its mode says read or write); errors get the caller's file:line.
int l_file_function(lua_State* L) {
  const char* name = lua_tostring(L, lua_upvalueindex(3));
  if (lua_type(L, 1) == LUA_TSTRING) {
    const auto kind = static_cast<FileAccess>(lua_tointeger(L, lua_upvalueindex(4)));
    bool write = kind == kWrite;
    if (kind == kOpen) {
      const char* mode = luaL_optstring(L, 2, "r");
      write = std::strpbrk(mode, "wa+") != nullptr;
    }
    check_path(L, ctx_up(L), name, lua_tostring(L, 1), write);
    if (write) {  // the script cannot make folders itself: those missing under the output folder are made
      std::error_code ec;
      const fs::path parent = fs::path(lua_tostring(L, 1)).parent_path();
      if (!parent.empty()) fs::create_directories(parent, ec);
    }
  }
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  CallError e;
  if (docall(L, lua_gettop(L) - 1, LUA_MULTRET, &e, name)) return lua_gettop(L);
  // called from C, the original's error has no file:line: the script's is added
  luaL_where(L, 1);
  lua_pushstring(L, e.message.c_str());
  lua_concat(L, 2);
  return lua_error(L);
}

void wrap_file_function(lua_State* L, Context* ctx, const char* field, const char* name, FileAccess kind) {
  lua_getfield(L, -1, field);
  lua_pushlightuserdata(L, ctx);
  lua_pushstring(L, name);
  lua_pushinteger(L, kind);
  lua_pushcclosure(L, l_file_function, 4);
  lua_setfield(L, -2, field);
}

// ---- loading: text only, files in the allowed folders ----------------------------------------

// calls the original loader (upvalue 1) with its mode argument (at mode_at) forced to "t"; a mode
// without "t" is an error, and a binary chunk refused by Lua is explained
int call_text_only(lua_State* L, int mode_at, const char* what, const std::string& name) {
  const char* mode = luaL_optstring(L, mode_at, nullptr);
  if (mode && !std::strchr(mode, 't'))
    return luaL_error(L, "%s: mode '%s' asks for precompiled (binary) chunks, which are not loaded (Lua source "
                         "only); %s", what, mode, kHow);
  const int n = std::max(lua_gettop(L), mode_at);
  lua_settop(L, n);
  lua_pushliteral(L, "t");
  lua_replace(L, mode_at);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, n, LUA_MULTRET);
  if (lua_gettop(L) == 2 && lua_isnil(L, 1)) explain_binary(L, 2, name.c_str());
  return lua_gettop(L);
}

// load(chunk [, chunkname [, mode [, env]]]): mode "t" whatever is asked; "b" alone is an error
int l_load(lua_State* L) { return call_text_only(L, 3, "load", "load"); }

// loadfile([filename [, mode [, env]]])
int l_loadfile(lua_State* L) {
  const char* fname = luaL_optstring(L, 1, nullptr);
  if (fname) check_path(L, ctx_up(L), "loadfile", fname, false);
  return call_text_only(L, 2, "loadfile", fname ? fname : "stdin");
}

int dofile_continue(lua_State* L, int, lua_KContext) { return lua_gettop(L) - 1; }

// dofile([filename])
int l_dofile(lua_State* L) {
  const char* fname = luaL_optstring(L, 1, nullptr);
  if (fname) check_path(L, ctx_up(L), "dofile", fname, false);
  lua_settop(L, 1);
  if (luaL_loadfilex(L, fname, "t") != LUA_OK) {
    explain_binary(L, -1, fname ? fname : "stdin");
    luaL_where(L, 1);
    lua_pushliteral(L, "dofile: ");
    lua_rotate(L, -3, 2);
    lua_concat(L, 3);
    return lua_error(L);
  }
  lua_callk(L, 0, LUA_MULTRET, 0, dofile_continue);
  return dofile_continue(L, 0, 0);
}

// require(name): a Lua file name.lua (dots are folders) in the script's folder, run once
int l_require(lua_State* L) {
  const Context& c = *static_cast<Context*>(lua_touserdata(L, lua_upvalueindex(1)));
  const std::string name = luaL_checkstring(L, 1);
  lua_settop(L, 1);
  luaL_getsubtable(L, LUA_REGISTRYINDEX, LUA_LOADED_TABLE);  // 2
  if (lua_getfield(L, 2, name.c_str()) != LUA_TNIL && lua_toboolean(L, -1)) return 1;
  lua_pop(L, 1);
  if (c.script_dir.empty())
    return luaL_error(L, "require '%s': a scenario script's modules are Lua files in its own folder, and this "
                         "session has no script; %s", name.c_str(), kHow);
  std::string rel = name;
  for (char& ch : rel)
    if (ch == '.') ch = '/';
  const std::string path = (fs::path(c.script_dir) / (rel + ".lua")).string();
  if (!under(resolved(path), resolved(c.script_dir)))
    return luaL_error(L, "require '%s': modules are Lua files in the script's folder (%s); %s", name.c_str(),
                      c.script_dir.c_str(), kHow);
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    return luaL_error(L, "module '%s' not found: no file '%s' (a scenario script's require loads Lua files from the "
                         "script's folder only; --trusted gives package.path and C modules)", name.c_str(),
                      path.c_str());
  if (luaL_loadfilex(L, path.c_str(), "t") != LUA_OK) {
    explain_binary(L, -1, path.c_str());
    return luaL_error(L, "error loading module '%s' from file '%s':\n\t%s", name.c_str(), path.c_str(),
                      lua_tostring(L, -1));
  }
  lua_pushstring(L, name.c_str());
  lua_pushstring(L, path.c_str());
  lua_call(L, 2, 1);
  if (!lua_isnil(L, -1)) lua_setfield(L, 2, name.c_str());
  else lua_pop(L, 1);
  if (lua_getfield(L, 2, name.c_str()) == LUA_TNIL) {
    lua_pop(L, 1);
    lua_pushboolean(L, 1);
    lua_pushvalue(L, -1);
    lua_setfield(L, 2, name.c_str());
  }
  lua_pushstring(L, path.c_str());
  return 2;
}

// setmetatable(t, mt) without a __gc field: Lua runs finalisers with hooks off, so neither the
// instruction limit nor Ctrl-C could stop one that loops
int l_setmetatable(lua_State* L) {
  if (lua_type(L, 2) == LUA_TTABLE) {
    lua_pushliteral(L, "__gc");
    if (lua_rawget(L, 2) != LUA_TNIL)
      return luaL_error(L, "setmetatable: a __gc finaliser is not allowed in a scenario script (Lua runs finalisers "
                           "where no instruction limit or Ctrl-C can stop them); %s", kHow);
    lua_pop(L, 1);
  }
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
  return lua_gettop(L);
}

// _G[name] = closure(original _G[name], ctx)
void wrap_global(lua_State* L, Context* ctx, const char* name, lua_CFunction f) {
  lua_getglobal(L, name);
  lua_pushlightuserdata(L, ctx);
  lua_pushcclosure(L, f, 2);
  lua_setglobal(L, name);
}

}  // namespace

std::string output_refusal(const Context& c, const std::string& what, const std::string& path, bool write) {
  return refusal(c, what, path, write, true);
}

std::string run_paths_refusal(const Context& c, const std::string& what, const RunSettings& rs) {
  std::string r = output_refusal(c, what + ".out", rs.out_dir, true);
  if (r.empty() && rs.frames) {
    if (!rs.frames->png_dir.empty())
      r = output_refusal(c, what + ".frames.png", output_path(rs, rs.frames->png_dir), true);
    if (r.empty() && !rs.frames->video_path.empty())
      r = output_refusal(c, what + ".frames.video", output_path(rs, rs.frames->video_path), true);
  }
  return r;
}

void open_sandbox(lua_State* L, Context* ctx) {
  const luaL_Reg libs[] = {{LUA_GNAME, luaopen_base},         {LUA_COLIBNAME, luaopen_coroutine},
                           {LUA_TABLIBNAME, luaopen_table},   {LUA_IOLIBNAME, luaopen_io},
                           {LUA_OSLIBNAME, luaopen_os},       {LUA_STRLIBNAME, luaopen_string},
                           {LUA_MATHLIBNAME, luaopen_math},   {LUA_UTF8LIBNAME, luaopen_utf8}};
  for (const luaL_Reg& lib : libs) {
    luaL_requiref(L, lib.name, lib.func, 1);
    lua_pop(L, 1);
  }

  // base: text-only loading, files checked, require from the script's folder
  wrap_global(L, ctx, "load", l_load);
  wrap_global(L, ctx, "loadfile", l_loadfile);
  wrap_global(L, ctx, "dofile", l_dofile);
  wrap_global(L, ctx, "setmetatable", l_setmetatable);
  lua_pushlightuserdata(L, ctx);
  lua_pushcclosure(L, l_require, 1);
  lua_setglobal(L, "require");

  // string: no dump (the tables are changed in place: package.loaded holds the same ones)
  lua_getglobal(L, LUA_STRLIBNAME);
  forbid(L, "string", "dump");
  lua_pop(L, 1);

  // os: time, clock, date, difftime, getenv; the rest raise
  lua_getglobal(L, LUA_OSLIBNAME);
  std::vector<std::string> os_names;
  lua_pushnil(L);
  while (lua_next(L, -2)) {
    lua_pop(L, 1);
    os_names.push_back(lua_tostring(L, -1));
  }
  for (const std::string& n : os_names)
    if (n != "time" && n != "clock" && n != "date" && n != "difftime" && n != "getenv") forbid(L, "os", n.c_str());
  lua_pop(L, 1);

  // io: files in the allowed folders only; no processes or temporary files
  lua_getglobal(L, LUA_IOLIBNAME);
  wrap_file_function(L, ctx, "open", "io.open", kOpen);
  wrap_file_function(L, ctx, "lines", "io.lines", kRead);
  wrap_file_function(L, ctx, "input", "io.input", kRead);
  wrap_file_function(L, ctx, "output", "io.output", kWrite);
  forbid(L, "io", "popen");
  forbid(L, "io", "tmpfile");
  lua_pop(L, 1);

  // debug: traceback only (the full library is opened unregistered to take it from)
  luaL_getsubtable(L, LUA_REGISTRYINDEX, LUA_LOADED_TABLE);  // loaded
  luaopen_debug(L);                                           // loaded, full
  std::vector<std::string> debug_names;
  lua_pushnil(L);
  while (lua_next(L, -2)) {
    lua_pop(L, 1);
    debug_names.push_back(lua_tostring(L, -1));
  }
  lua_newtable(L);  // loaded, full, debug
  for (const std::string& n : debug_names) {
    if (n == "traceback") {
      lua_getfield(L, -2, "traceback");
      lua_setfield(L, -2, "traceback");
    } else {
      forbid(L, "debug", n.c_str());
    }
  }
  lua_remove(L, -2);  // loaded, debug
  lua_pushvalue(L, -1);
  lua_setfield(L, -3, LUA_DBLIBNAME);
  lua_setglobal(L, LUA_DBLIBNAME);  // loaded

  // package: the loaded modules; no C libraries
  lua_newtable(L);
  lua_pushvalue(L, -2);
  lua_setfield(L, -2, "loaded");
  forbid(L, "package", "loadlib");
  forbid(L, "package", "searchpath");
  lua_pushvalue(L, -1);
  lua_setfield(L, -3, LUA_LOADLIBNAME);
  lua_setglobal(L, LUA_LOADLIBNAME);
  lua_pop(L, 1);
}

}  // namespace beltsim::script
