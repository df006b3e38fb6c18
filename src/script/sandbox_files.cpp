// A scenario script's files (see sandbox_files.hpp). A path a script names is placed first: made
// absolute and its `.` and `..` taken out as text, it must begin with the output folder or the
// script's folder (either as named or with the links on its way resolved); the rest is then opened
// beneath that folder's descriptor with io/beneath.hpp, which follows no link and cannot climb out.
#include "script/sandbox_files.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>

#include "io/beneath.hpp"
#include "io/output_dir.hpp"
#include "script/context.hpp"
#include "script/docall.hpp"
#include "script/load_source.hpp"

#include "lauxlib.h"
#include "lua.h"
#include "lualib.h"

namespace beltsim::script {

namespace {

namespace fs = std::filesystem;

// ---- where a path lies ---------------------------------------------------------------------

// absolute (from the working folder), `.` and `..` taken out as text, no trailing slash
fs::path lexical(const std::string& p) {
  std::error_code ec;
  fs::path a = fs::absolute(p, ec);
  if (ec) a = fs::path(p);
  a = a.lexically_normal();
  if (!a.has_filename() && a.has_parent_path() && a != a.root_path()) a = a.parent_path();  // "dir/"
  return a;
}

// absolute, with `..` and the links resolved as far as the path exists (for messages, and for a
// folder named through a link)
fs::path resolved(const std::string& p) {
  std::error_code ec;
  fs::path c = fs::weakly_canonical(lexical(p), ec);
  if (ec) c = lexical(p);
  if (!c.has_filename() && c.has_parent_path() && c != c.root_path()) c = c.parent_path();
  return c;
}

// the part of p below root ("" for root itself), nullopt when p does not begin with root
std::optional<std::string> below(const fs::path& p, const fs::path& root) {
  auto i = p.begin();
  for (auto r = root.begin(); r != root.end(); ++r, ++i)
    if (i == p.end() || *i != *r) return std::nullopt;
  fs::path rest;
  for (; i != p.end(); ++i) rest /= *i;
  return rest.string();
}

std::string out_folder(const Context& c) {
  return c.overrides.has("out") ? c.overrides.run.out_dir : c.default_out;
}

// a path a script names, in one of the sandbox's folders
struct Place {
  std::string root;  // the folder as beltsim has it (the output folder, the script's folder)
  std::string rel;   // the path below it, without `.` and `..` ("" for the folder itself)
  bool output;       // root is the output folder
};

// where path lies: the output folder (read and write) first, else the script's folder (read; and
// written by beltsim itself: `outputs`)
std::optional<Place> place(const Context& c, const std::string& path, bool write, bool outputs) {
  const fs::path p = lexical(path);
  const auto in = [&](const std::string& root) {
    std::optional<std::string> r = below(p, lexical(root));
    return r ? r : below(p, resolved(root));
  };
  if (auto r = in(out_folder(c))) return Place{out_folder(c), *r, true};
  if (!c.script_dir.empty() && (!write || outputs))
    if (auto r = in(c.script_dir)) return Place{c.script_dir, *r, false};
  return std::nullopt;
}

// "WHAT: reading|writing 'path' is not allowed in a scenario script" and why
std::string not_allowed(const std::string& what, const std::string& path, bool write, const std::string& why) {
  return what + ": " + (write ? "writing" : "reading") + " '" + path + "' is not allowed in a scenario script" + why +
         "; " + kHow;
}

// the refusal of a path outside the folders: they are named
std::string outside(const Context& c, const std::string& what, const std::string& path, bool write, bool outputs) {
  const bool has_script = !c.script_dir.empty();
  std::string allowed =
      (outputs ? "beltsim's outputs under " : "read and write under ") + resolved(out_folder(c)).string();
  if (has_script)
    allowed += (outputs ? " or " : ", read under ") + resolved(c.script_dir).string() + " (the script's folder)";
  return not_allowed(what, path, write, " (the sandbox: " + allowed + ")");
}

// ---- opening there ---------------------------------------------------------------------------

// root/rel, for messages
std::string joined(const std::string& root, const std::string& rel) {
  const std::string r = trimmed_path(root);
  if (rel.empty()) return r;
  return r == "/" ? r + rel : r + "/" + rel;
}

// the folder of a place: the output folder (made when missing and `make`) never through a link as
// its last component, as for beltsim's own outputs; the script's folder as it was named
int open_root(const Place& pl, bool make, BeneathError* e) {
  if (pl.output) return folder_path(pl.root, make, e);
  const int fd = ::open(pl.root.c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) e->kind = BeneathError::kSystem, e->err = errno, e->at = pl.root;
  return fd;
}

// a BeneathError that is the sandbox's refusal (not the system's answer) said, with the path
// concerned; "" for the system's
std::string sandbox_reason(const BeneathError& e, const std::string& at) {
  switch (e.kind) {
    case BeneathError::kLink: return at + " is a symbolic link (the sandbox follows no link in its folders)";
    case BeneathError::kNotRegular: return at + " is not a regular file (a FIFO or a device could block the script)";
    case BeneathError::kHardLinks:
      return at + " has " + std::to_string(e.links) + " hard links (the file's other name may lie outside the folders)";
    case BeneathError::kDotDot: return at + ": `..` would leave the folder";
    case BeneathError::kSystem:
    case BeneathError::kNotFolder: break;
  }
  return "";
}

// a folder on the way from the place's folder to the file it names (both included; to the folder
// it names, with `folder`) that another beltsim holds, its simulation writing there
// (io/output_dir.hpp), said as a refusal; "" when none. A folder still missing holds nothing, nor
// what would be made below it.
std::string held_on_the_way(const Place& pl, bool folder = false) {
  BeneathError e;
  FolderFd dir(open_root(pl, false, &e));
  std::string at = trimmed_path(pl.root), name;
  std::istringstream folders(folder ? pl.rel : split_path(pl.rel).first);
  while (dir.get() >= 0) {
    if (const std::string who = folder_holder(dir.get()); !who.empty())
      return "the folder " + at + " is in use by " + who + " (one writer per folder: its simulation writes there)";
    do
      if (!std::getline(folders, name, '/')) return "";
    while (name.empty() || name == ".");
    dir = FolderFd(folder_at(dir.get(), name, false, &e));
    at = joined(at, name);
  }
  return "";
}

// the file `path` opened for a script as m says (a write makes the missing folders under the
// output folder): a descriptor, or -1 with *err the system's error (Lua's own answers for a
// missing file, a permission); what the sandbox refuses raises "file:line: WHAT: ... not allowed"
int open_in_sandbox(lua_State* L, const Context& c, const char* what, const char* path, FileMode m, int* err) {
  const std::optional<Place> pl = place(c, path, m.write, false);
  if (!pl) return luaL_error(L, "%s", outside(c, what, path, m.write, false).c_str());
  m.make_folders = m.write;
  std::string refused = m.write ? held_on_the_way(*pl) : "";
  int fd = -1;
  if (refused.empty()) {
    BeneathError e;
    const FolderFd root(open_root(*pl, m.write, &e));
    if (root.get() >= 0) fd = file_beneath(root.get(), pl->rel, m, &e);
    if (fd < 0) {
      refused = sandbox_reason(e, root.get() >= 0 ? joined(pl->root, e.at) : e.at);
      *err = e.kind == BeneathError::kNotFolder ? ENOTDIR : e.err;
    }
  }
  if (!refused.empty()) return luaL_error(L, "%s", not_allowed(what, path, m.write, ": " + refused).c_str());
  return fd;
}

// a link already on the way to a place, below its folder and before its last component, said as
// a refusal; "" when there is none. beltsim's writers open the last component (a file, or the
// folder they write in) never through a link themselves (with their own message), and make the
// missing rest a component at a time; a link before it they would follow.
std::string link_on_the_way(const Place& pl) {
  BeneathError e;
  const FolderFd root(open_root(pl, false, &e));
  if (root.get() < 0) return e.kind == BeneathError::kLink ? sandbox_reason(e, e.at) : "";
  const FolderFd dir(folder_beneath(root.get(), split_path(pl.rel).first, false, &e));
  return dir.get() < 0 ? sandbox_reason(e, joined(pl.root, e.at)) : "";
}

// ---- Lua file handles --------------------------------------------------------------------------

// a handle's close (as io's own)
int close_stream(lua_State* L) {
  auto* p = static_cast<luaL_Stream*>(luaL_checkudata(L, 1, LUA_FILEHANDLE));
  return luaL_fileresult(L, std::fclose(p->f) == 0, nullptr);
}

// a Lua file handle, as io.open makes one, owning fd from here; false with *err when none is made
bool push_stream(lua_State* L, int fd, const char* mode, int* err) {
  auto* p = static_cast<luaL_Stream*>(lua_newuserdatauv(L, sizeof(luaL_Stream), 0));
  p->closef = nullptr;  // a closed file until it holds one
  luaL_setmetatable(L, LUA_FILEHANDLE);
  p->f = ::fdopen(fd, mode);
  if (!p->f) {
    *err = errno;
    ::close(fd);
    lua_pop(L, 1);
    return false;
  }
  p->closef = close_stream;
  return true;
}

Context& ctx_up(lua_State* L) { return *static_cast<Context*>(lua_touserdata(L, lua_upvalueindex(2))); }

// the file path opened in the sandbox as a Lua file handle on the stack: 0, or the system's error
// (nothing pushed)
int push_file(lua_State* L, const char* what, const char* path, const char* mode) {
  int err = 0;
  const int fd = open_in_sandbox(L, ctx_up(L), what, path, *file_mode(mode), &err);
  if (fd >= 0) push_stream(L, fd, mode, &err);
  return err;
}

// io.open(path [, mode]): the handle, or nil, "path: reason", errno
int l_open(lua_State* L) {
  const char* path = luaL_checkstring(L, 1);
  const char* mode = luaL_optstring(L, 2, "r");
  luaL_argcheck(L, file_mode(mode).has_value(), 2, "invalid mode");
  if (const int err = push_file(L, "io.open", path, mode)) {
    errno = err;
    return luaL_fileresult(L, 0, path);
  }
  return 1;
}

// the iterator of io.lines(path): file:lines' (upvalue 1), closing the file (upvalue 2) at the end
int lines_step(lua_State* L) {
  lua_settop(L, 0);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_call(L, 0, LUA_MULTRET);
  if (lua_gettop(L) > 0 && lua_toboolean(L, 1)) return lua_gettop(L);
  const auto* p = static_cast<const luaL_Stream*>(lua_touserdata(L, lua_upvalueindex(2)));
  if (p->closef) {
    lua_getfield(L, lua_upvalueindex(2), "close");
    lua_pushvalue(L, lua_upvalueindex(2));
    lua_call(L, 1, 0);
  }
  return 0;
}

// io.lines([path, formats...]): as Lua's, the iterator, nil, nil and the file (closed when a for
// loop leaves early)
int l_lines(lua_State* L) {
  if (lua_isnoneornil(L, 1)) return call_original(L, "io.lines");  // the default input
  const char* path = luaL_checkstring(L, 1);
  if (const int err = push_file(L, "io.lines", path, "r"))
    return luaL_error(L, "cannot open file '%s' (%s)", path, std::strerror(err));
  lua_replace(L, 1);  // file, formats...
  const int n = lua_gettop(L);
  lua_getfield(L, 1, "lines");
  for (int k = 1; k <= n; ++k) lua_pushvalue(L, k);
  lua_call(L, n, 1);  // file:lines(formats...)
  lua_pushvalue(L, 1);
  lua_pushcclosure(L, lines_step, 2);
  lua_pushnil(L);
  lua_pushnil(L);
  lua_pushvalue(L, 1);
  return 4;
}

// io.input(path) and io.output(path): the file opened here ("r", "w"), then given to the original
int input_output(lua_State* L, const char* what, const char* mode) {
  if (lua_type(L, 1) == LUA_TSTRING) {
    const char* path = lua_tostring(L, 1);
    if (const int err = push_file(L, what, path, mode))
      return luaL_error(L, "cannot open file '%s' (%s)", path, std::strerror(err));
    lua_replace(L, 1);
  }
  return call_original(L, what);
}
int l_input(lua_State* L) { return input_output(L, "io.input", "r"); }
int l_output(lua_State* L) { return input_output(L, "io.output", "w"); }

// ---- loading -------------------------------------------------------------------------------

// the file fname (nullptr: standard input) loaded as Lua source, opened in the sandbox: a status,
// and the function or the message on the stack
int load_named(lua_State* L, const char* what, const char* fname) {
  if (!fname) return load_source(L, stdin, "=stdin");
  int err = 0;
  const int fd = open_in_sandbox(L, ctx_up(L), what, fname, FileMode{}, &err);
  std::FILE* f = fd >= 0 ? ::fdopen(fd, "r") : nullptr;
  if (!f) {
    if (fd >= 0) err = errno, ::close(fd);
    lua_pushfstring(L, "cannot open %s: %s", fname, std::strerror(err));
    return LUA_ERRFILE;
  }
  const int status = load_source(L, f, std::string("@") + fname, &ctx_up(L).loaded);
  std::fclose(f);
  if (status != LUA_OK) explain_binary(L, -1, fname);
  return status;
}

// loadfile([filename [, mode [, env]]]): Lua source only
int l_loadfile(lua_State* L) {
  const char* fname = luaL_optstring(L, 1, nullptr);
  check_text_mode(L, luaL_optstring(L, 2, nullptr), "loadfile");
  const int env = !lua_isnone(L, 3) ? 3 : 0;
  if (load_named(L, "loadfile", fname) != LUA_OK) {
    lua_pushnil(L);
    lua_insert(L, -2);
    return 2;
  }
  if (env != 0) {
    lua_pushvalue(L, env);
    if (!lua_setupvalue(L, -2, 1)) lua_pop(L, 1);
  }
  return 1;
}

int dofile_continue(lua_State* L, int, lua_KContext) { return lua_gettop(L) - 1; }

// dofile([filename])
int l_dofile(lua_State* L) {
  const char* fname = luaL_optstring(L, 1, nullptr);
  lua_settop(L, 1);
  if (load_named(L, "dofile", fname) != LUA_OK) {
    luaL_where(L, 1);
    lua_pushliteral(L, "dofile: ");
    lua_rotate(L, -3, 2);
    lua_concat(L, 3);
    return lua_error(L);
  }
  lua_callk(L, 0, LUA_MULTRET, 0, dofile_continue);
  return dofile_continue(L, 0, 0);
}

// the module file rel (name.lua) of the script's folder loaded: a status and the function or the
// message on the stack, nothing and LUA_ERRFILE when there is no such file; what the sandbox
// refuses (a link on the way) raises
int load_module(lua_State* L, Context& c, const std::string& name, const std::string& rel) {
  const std::string path = joined(c.script_dir, rel);
  std::string refused;
  std::FILE* f = nullptr;
  {
    BeneathError e;
    const FolderFd root(open_root(Place{c.script_dir, rel, false}, false, &e));
    const int fd = root.get() >= 0 ? file_beneath(root.get(), rel, FileMode{}, &e) : -1;
    if (fd < 0) refused = sandbox_reason(e, joined(c.script_dir, e.at));
    if (fd >= 0 && !(f = ::fdopen(fd, "r"))) ::close(fd);
  }
  if (!refused.empty())
    return luaL_error(L, "%s", not_allowed("require '" + name + "'", path, false, ": " + refused).c_str());
  if (!f) return LUA_ERRFILE;
  const int status = load_source(L, f, "@" + path, &c.loaded);
  std::fclose(f);
  return status;
}

// require(name): a Lua file name.lua (dots are folders) in the script's folder, run once
int l_require(lua_State* L) {
  Context& c = ctx_up(L);
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
    if (ch == '.') ch = '/';  // so no `..` is left
  rel += ".lua";
  if (rel.front() == '/')
    return luaL_error(L, "require '%s': modules are Lua files in the script's folder (%s); %s", name.c_str(),
                      c.script_dir.c_str(), kHow);
  const std::string path = joined(c.script_dir, rel);
  const int status = load_module(L, c, name, rel);
  if (status == LUA_ERRFILE && lua_gettop(L) == 2)
    return luaL_error(L, "module '%s' not found: no file '%s' (a scenario script's require loads Lua files from the "
                         "script's folder only; --trusted gives package.path and C modules)", name.c_str(),
                      path.c_str());
  if (status != LUA_OK) {
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

// t[field] = closure(f; original t[field], ctx); t on the stack top
void wrap(lua_State* L, Context* ctx, const char* field, lua_CFunction f) {
  lua_getfield(L, -1, field);
  lua_pushlightuserdata(L, ctx);
  lua_pushcclosure(L, f, 2);
  lua_setfield(L, -2, field);
}

}  // namespace

std::string path_refusal(const Context& c, const std::string& what, const std::string& path, bool write, bool outputs,
                         Written written) {
  if (c.trusted) return "";
  const std::optional<Place> pl = place(c, path, write, outputs);
  if (!pl) return outside(c, what, path, write, outputs);
  std::string why = link_on_the_way(*pl);
  if (why.empty() && write && written != Written::kRunFolder) why = held_on_the_way(*pl, written == Written::kFolder);
  return why.empty() ? "" : not_allowed(what, path, write, ": " + why);
}

void explain_binary(lua_State* L, int idx, const char* what) {
  idx = lua_absindex(L, idx);
  const char* msg = lua_tostring(L, idx);
  if (msg && std::strstr(msg, "attempt to load a binary chunk")) {
    lua_pushfstring(L, "%s: a precompiled (binary) chunk is never loaded: beltsim loads Lua source only", what);
    lua_replace(L, idx);
  }
}

void check_text_mode(lua_State* L, const char* mode, const char* what) {
  if (mode && !std::strchr(mode, 't'))
    luaL_error(L, "%s: mode '%s' asks for precompiled (binary) chunks, which are not loaded (Lua source only); %s",
               what, mode, kHow);
}

void open_sandbox_files(lua_State* L, Context* ctx) {
  wrap(L, ctx, "open", l_open);
  wrap(L, ctx, "lines", l_lines);
  wrap(L, ctx, "input", l_input);
  wrap(L, ctx, "output", l_output);
  lua_pushglobaltable(L);
  wrap(L, ctx, "loadfile", l_loadfile);
  wrap(L, ctx, "dofile", l_dofile);
  wrap(L, ctx, "require", l_require);
  lua_pop(L, 1);
}

}  // namespace beltsim::script
