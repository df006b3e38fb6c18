#include "script/interpreter.hpp"

#include <filesystem>

#include "script/context.hpp"
#include "script/lua_api.hpp"

#include "lauxlib.h"
#include "lua.h"
#include "lualib.h"

namespace beltsim::script {

namespace {

Context* context_of(lua_State* L) {
  lua_getfield(L, LUA_REGISTRYINDEX, "beltsim.context");
  auto* c = static_cast<Context*>(lua_touserdata(L, -1));
  lua_pop(L, 1);
  return c;
}

}  // namespace

Interpreter::Interpreter() : L_(luaL_newstate()) {
  if (!L_) throw std::runtime_error("cannot create a Lua state (out of memory)");
  luaL_openlibs(L_);
  auto* ctx = new (lua_newuserdatauv(L_, sizeof(Context), 0)) Context();
  // the context lives in the registry; its destructor is run in ~Interpreter
  lua_setfield(L_, LUA_REGISTRYINDEX, "beltsim.context");
  open_beltsim(L_, ctx);
}

Interpreter::~Interpreter() {
  Context* ctx = context_of(L_);
  ctx->~Context();
  lua_close(L_);
}

void Interpreter::set_overrides(const Overrides& o) { context_of(L_)->overrides = o; }
void Interpreter::set_stop_flag(const std::atomic<bool>* stop) { context_of(L_)->stop = stop; }
void Interpreter::set_capture(Captured* c) { context_of(L_)->capture = c; }
Context& Interpreter::context() { return *context_of(L_); }
bool Interpreter::interrupted() const { return context_of(L_)->interrupted; }

void Interpreter::run_file(const std::string& path) {
  Context* ctx = context_of(L_);
  ctx->default_out = (std::filesystem::path("out") / std::filesystem::path(path).stem()).string();
  ctx->interrupted = false;
  ctx->captured = false;
  // text only: a precompiled chunk is never loaded
  int status = luaL_loadfilex(L_, path.c_str(), "t");
  if (status == LUA_OK) status = lua_pcall(L_, 0, 0, 0);
  if (status != LUA_OK && ctx->captured) status = LUA_OK;  // ended on purpose by a capture
  if (status != LUA_OK) {
    // errors carry "file:line:" (chunks are named "@path"); a non-string error object is named
    std::string msg = lua_tostring(L_, -1) ? lua_tostring(L_, -1)
                                           : std::string(path) + ": error object is a " + luaL_typename(L_, -1);
    lua_settop(L_, 0);
    throw ScriptError(msg);
  }
  lua_settop(L_, 0);
}

}  // namespace beltsim::script
