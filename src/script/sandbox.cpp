// The sandboxed libraries (see sandbox.hpp). The standard functions that touch files are
// replaced by sandbox_files.cpp's, which open their files in the sandbox's folders.
#include "script/sandbox.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "lauxlib.h"
#include "lua.h"
#include "lualib.h"
#include "script/context.hpp"
#include "script/sandbox_files.hpp"
#include "sweep/results.hpp"

namespace beltsim::script {

namespace {

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

// ---- loading: text only ---------------------------------------------------------------------

// calls the original loader (upvalue 1) with its mode argument (at mode_at) forced to "t"; a mode
// without "t" is an error, and a binary chunk refused by Lua is explained
int call_text_only(lua_State* L, int mode_at, const char* what, const std::string& name) {
  check_text_mode(L, luaL_optstring(L, mode_at, nullptr), what);
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

std::string output_refusal(const Context& c, const std::string& what, const std::string& path, bool write,
                           Written written) {
  return path_refusal(c, what, path, write, true, written);
}

std::string run_paths_refusal(const Context& c, const std::string& what, const RunSettings& rs) {
  std::string r = output_refusal(c, what + ".out", rs.out_dir, true, Written::kRunFolder);
  // a sweep's study is no run's folder, whatever the sandbox allows (a run that is captured,
  // for beltsim wp or modes, writes elsewhere)
  if (r.empty() && !c.capture) r = sweep::study_folder_refusal(what + ".out", rs.out_dir);
  if (r.empty() && rs.frames) {
    if (!rs.frames->png_dir.empty())
      r = output_refusal(c, what + ".frames.png", output_path(rs, rs.frames->png_dir), true, Written::kFolder);
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

  // base: text-only loading (loadfile, dofile and require are replaced with io's functions)
  wrap_global(L, ctx, "load", l_load);
  wrap_global(L, ctx, "setmetatable", l_setmetatable);

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
  open_sandbox_files(L, ctx);  // also loadfile, dofile and require
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
