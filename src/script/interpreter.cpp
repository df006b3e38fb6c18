#include "script/interpreter.hpp"

#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>

#include "io/input_file.hpp"
#include "lauxlib.h"
#include "live/live_server.hpp"
#include "lua.h"
#include "lualib.h"
#include "script/context.hpp"
#include "script/docall.hpp"
#include "script/limits.hpp"
#include "script/load_source.hpp"
#include "script/lua_api.hpp"
#include "script/lua_args.hpp"
#include "script/lua_check.hpp"
#include "script/lua_law.hpp"
#include "script/progress.hpp"
#include "script/sandbox.hpp"

namespace beltsim::script {

namespace {

// print, Lua's own (its upvalue) on a line of its own: a progress line open on the terminal stdout
// shares is ended first (progress.hpp; a script's every callback prints while its run goes on)
int l_print(lua_State* L) {
  before_stdout();
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, 0);
  return 0;
}

// io.write(...) and file:write(...), Lua's own (upvalue 1; upvalue 2 true for the method), as
// print: a progress line open on the terminal is ended first when the file written is stdout or
// stderr (progress.hpp, before_write). The file and the values are checked here as Lua's write
// checks them, so that a wrong one is named as the script called it ("bad argument #1 to
// 'write'"); a closed file is left to Lua's write to refuse
int l_write(lua_State* L) {
  const bool method = lua_toboolean(L, lua_upvalueindex(2));
  const luaL_Stream* file = nullptr;
  if (method) {
    file = static_cast<const luaL_Stream*>(luaL_checkudata(L, 1, LUA_FILEHANDLE));
  } else {
    lua_getfield(L, LUA_REGISTRYINDEX, "_IO_output");  // io.output()'s file, where liolib keeps it
    file = static_cast<const luaL_Stream*>(luaL_testudata(L, -1, LUA_FILEHANDLE));
    lua_pop(L, 1);
  }
  for (int i = method ? 2 : 1; i <= lua_gettop(L); ++i)
    if (lua_type(L, i) != LUA_TNUMBER) luaL_checklstring(L, i, nullptr);
  if (file && file->closef) before_write(file->f);
  return call_original(L, method ? "write" : "io.write");
}

// t[name] = l_write over t[name] (method: a file's write); t on the stack top
void wrap_write(lua_State* L, const char* name, bool method) {
  lua_getfield(L, -1, name);
  lua_pushboolean(L, method);
  lua_pushcclosure(L, l_write, 2);
  lua_setfield(L, -2, name);
}

}  // namespace

Interpreter::Interpreter(const Safety& safety)
    : limits_(std::make_unique<Limits>()), ctx_(std::make_unique<Context>()), L_(luaL_newstate()) {
  if (!L_) throw std::runtime_error("cannot create a Lua state (out of memory)");
  // from here on every block goes through the counting allocator (the state's first ones were
  // made by luaL_newstate's, also realloc/free: they are counted from the collector's total)
  limits_->max_instructions = safety.max_instructions;
  limits_->max_bytes = safety.max_lua_memory;
  limits_->max_wall = safety.max_lua_wall;
  limits_->max_cpu = safety.max_lua_cpu;
  limits_->bytes = static_cast<std::size_t>(lua_gc(L_, LUA_GCCOUNT, 0)) * 1024 +
                   static_cast<std::size_t>(lua_gc(L_, LUA_GCCOUNTB, 0));
  use_limits(L_, *limits_);
  ctx_->trusted = safety.trusted;
  if (safety.trusted)
    luaL_openlibs(L_);
  else
    open_sandbox(L_, ctx_.get());
  lua_getglobal(L_, "print");
  lua_pushcclosure(L_, l_print, 1);
  lua_setglobal(L_, "print");
  // io.write and the files' write as print (io.stdout:write, io.stderr:write)
  lua_getglobal(L_, LUA_IOLIBNAME);
  wrap_write(L_, "write", false);
  lua_pop(L_, 1);
  luaL_getmetatable(L_, LUA_FILEHANDLE);
  lua_getfield(L_, -1, "__index");
  wrap_write(L_, "write", true);
  lua_pop(L_, 2);
  guard_limits(L_);  // also trusted: the limits hold for every script
  ctx_->law_host->L = L_;
  open_beltsim(L_, ctx_.get());
  install_hook(L_);
  if (safety.max_lua_wall > 0 || safety.max_lua_cpu > 0) start_lua_clock();
}

Interpreter::~Interpreter() {
  begin_call(L_);  // the finalisers lua_close runs get a budget of their own
  {
    const InsideLua closing(L_, "closing the Lua state");  // and their time (lua_clock.hpp)
    lua_close(L_);
  }
  ctx_->law_host->L = nullptr;  // laws kept elsewhere (a captured scene) must not call into it
  forget_limits(limits_.get());
}

void Interpreter::set_overrides(const Overrides& o) { ctx_->overrides = o; }
void Interpreter::set_stop_flag(const std::atomic<bool>* stop) { ctx_->stop = stop; }
void Interpreter::set_capture(Captured* c) { ctx_->capture = c; }
Context& Interpreter::context() { return *ctx_; }

std::string Interpreter::serve(int port) {
  live::ServeSettings ss;
  ss.port = port;
  ctx_->serve = std::make_shared<live::LiveServer>(ss);
  const std::string url = ctx_->serve->url();
  say("beltsim: live view at %s\n", url.c_str());
  return url;
}
bool Interpreter::interrupted() const { return ctx_->interrupted; }
std::vector<std::string> Interpreter::unread_args(const std::string& script) const {
  return unread_arg_messages(*ctx_, script);
}
void Interpreter::interrupt() { script::interrupt(*limits_); }
const std::vector<LoadedFile>& Interpreter::loaded_files() const { return ctx_->loaded; }

std::string default_out_dir(const std::string& script) {
  return (std::filesystem::path("out") / std::filesystem::path(script).stem()).string();
}

void Interpreter::run_file(const std::string& path, int nresults) {
  Context* ctx = ctx_.get();
  const std::filesystem::path p(path);
  ctx->default_out = default_out_dir(path);
  ctx->script_dir = p.has_parent_path() ? p.parent_path().string() : ".";
  ctx->script = path;
  ctx->interrupted = false;
  ctx->captured = false;
  ctx->args_read.clear();
  ctx->args_warned = false;
  std::error_code ec;
  if (std::filesystem::is_directory(p, ec))
    throw ScriptError(path + ": is a folder, not a script (give the Lua file to run)");
  // a regular file only (io/input_file.hpp): a FIFO without a writer held the program, deaf to
  // SIGTERM, and /dev/zero would never end
  std::optional<InputFile> in;
  try {
    in.emplace(path);
  } catch (const InputFileError& e) {
    throw ScriptError("cannot open " + path + ": " + e.reason);
  }
  if (in->size() == 0) throw ScriptError(path + ": the script is empty: nothing to run");
  begin_call(L_);
  // text only: a precompiled chunk is never loaded; the chunk is named "@path", so that its
  // errors read "path:line:"
  const int status = load_source(L_, in->stream(), "@" + path, &ctx->loaded);
  in.reset();
  if (status != LUA_OK) {
    std::string msg;
    if (!memory_message(L_, status, path, msg)) msg = lua_tostring(L_, -1) ? lua_tostring(L_, -1) : path;
    // a file that does not parse and is not named .lua is most likely another kind of file (a
    // run's timeseries.csv given to run gave Lua's ":2: '=' expected near '0'" alone): said first
    if (const std::string ext = p.extension().string(); status == LUA_ERRSYNTAX && ext != ".lua")
      msg = path + ": not a Lua script? (its name ends in '" + ext + "', not .lua" +
            (ext == ".csv" ? "; a run's CSV files are read by beltsim summary and beltsim plot" : "") +
            "); Lua's parser: " + msg;
    lua_settop(L_, 0);
    throw ScriptError(msg);
  }
  CallError error;
  const bool ok = docall(L_, 0, nresults, &error, path);
  if (!ok || nresults == 0) lua_settop(L_, 0);
  if (!ok && !ctx->captured)  // a capture ends the script on purpose
    throw ScriptError(error.message, error.traceback);
}

}  // namespace beltsim::script
