// The instruction and memory limits and the Ctrl-C hook (see limits.hpp).
#include "script/limits.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "lauxlib.h"

namespace beltsim::script {

namespace {

// instructions between two calls of the hook (Ctrl-C is seen within microseconds). Any count hook
// sends every instruction through Lua's slow path (luaG_traceexec): pure Lua code runs at about
// half speed with it, whatever the count; hence no permanent hook without an instruction limit.
constexpr int kSlice = 1000;

// the hook stays installed only to count instructions; otherwise it is armed when needed
bool permanent(const Limits& g) { return g.max_instructions != 0; }

void hook(lua_State* L, lua_Debug* ar);

// arms the hook to run at the next instruction (lua_sethook may be called asynchronously: from a
// signal handler, or from the allocator in the middle of an instruction)
void arm(Limits& g) {
  if (g.main) lua_sethook(g.main, hook, LUA_MASKCOUNT, 1);
}

std::string mib(std::size_t bytes) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", static_cast<double>(bytes) / (1 << 20));
  return b;
}

// the margin past the limit that small allocations may use while the hook comes round to
// raising the error
std::size_t margin(std::size_t max) { return std::min<std::size_t>(max / 4, std::size_t(256) << 20); }

void hook(lua_State* L, lua_Debug* ar) {
  Limits& g = limits_of(L);
  const int count = lua_gethookcount(L);
  g.used += static_cast<std::uint64_t>(count);
  if (g.fired.empty()) {
    if (g.max_instructions != 0 && g.used > g.max_instructions) {
      g.fired = "the instruction limit was reached: more than " + std::to_string(g.max_instructions) +
                " Lua instructions in one call (a script run or a console command, with the callbacks it runs; a "
                "loop that never ends?); --max-instructions N raises it, 0 removes it";
    } else if (g.over_memory) {
      g.over_memory = false;
      g.fired = "the Lua heap reached its limit of " + mib(g.max_bytes) +
                " MiB; --max-lua-memory MiB raises it, 0 removes it";
    }
  }
  const std::string why = g.interrupt.load(std::memory_order_relaxed) ? "interrupted!" : g.fired;
  if (why.empty()) {
    if (!permanent(g))
      lua_sethook(L, nullptr, 0, 0);  // armed for nothing (an interrupt already cleared)
    else if (count != kSlice)
      lua_sethook(L, hook, LUA_MASKCOUNT, kSlice);  // after a raise in an earlier call
    return;
  }
  // raise again at every instruction until the host's call ends (a pcall cannot swallow it), on
  // this thread and on the main one (the error may end a coroutine and return there)
  lua_sethook(L, hook, LUA_MASKCOUNT, 1);
  if (g.main && g.main != L) lua_sethook(g.main, hook, LUA_MASKCOUNT, 1);
  std::string where;
  if (lua_getinfo(L, "Sl", ar) && ar->currentline > 0)
    where = std::string(ar->short_src) + ":" + std::to_string(ar->currentline) + ": ";
  lua_pushstring(L, (where + why).c_str());
  lua_error(L);  // a C++ exception (liblua5.4-c++): the strings are destroyed
}

// the script's message handler (upvalue 1), unless a limit fired: Lua calls a handler with hooks
// off for an error the hook raised (its code could run for ever there), and that error is the
// limit's own, given back as it is
int guarded_handler(lua_State* L) {
  if (limit_fired(L)) return 1;
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, 1);
  return 1;
}

int xpcall_done(lua_State* L, int /*status*/, lua_KContext /*ctx*/) { return lua_gettop(L); }

// xpcall(f, msgh, ...): Lua's (upvalue 1) with msgh guarded; none once a limit fired
int l_xpcall(lua_State* L) {
  const Limits& g = limits_of(L);
  if (g.interrupt.load(std::memory_order_relaxed)) return luaL_error(L, "interrupted!");
  if (!g.fired.empty()) return luaL_error(L, "%s", g.fired.c_str());
  luaL_checktype(L, 2, LUA_TFUNCTION);
  const int n = lua_gettop(L);
  lua_pushvalue(L, 2);
  lua_pushcclosure(L, guarded_handler, 1);
  lua_replace(L, 2);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_callk(L, n, LUA_MULTRET, 0, xpcall_done);  // f may yield (in a coroutine)
  return xpcall_done(L, LUA_OK, 0);
}

}  // namespace

void* limited_alloc(void* ud, void* ptr, size_t osize, size_t nsize) {
  auto* g = static_cast<Limits*>(ud);
  const std::size_t old = ptr ? osize : 0;  // without a block, osize is the kind of object
  if (nsize == 0) {
    std::free(ptr);
    g->bytes -= old;
    return nullptr;
  }
  if (g->max_bytes != 0 && nsize > old) {
    const std::size_t after = g->bytes - old + nsize;
    if (after <= g->max_bytes) {
      g->retried = false;
    } else if (g->over_memory) {  // the hook is about to raise: no more collections meanwhile
      if (after > g->max_bytes + margin(g->max_bytes)) {
        g->refused = nsize;
        return nullptr;
      }
    } else if (!g->retried) {
      g->retried = true;  // Lua collects garbage and asks again
      g->refused = nsize;
      return nullptr;
    } else {
      g->retried = false;
      if (after > g->max_bytes + margin(g->max_bytes)) {
        g->refused = nsize;
        return nullptr;
      }
      g->over_memory = true;  // granted; the hook raises the error with file:line
      if (!permanent(*g)) arm(*g);
    }
  }
  void* p = std::realloc(ptr, nsize);
  if (!p) return nullptr;
  g->bytes = g->bytes - old + nsize;
  return p;
}

Limits& limits_of(lua_State* L) {
  void* ud = nullptr;
  lua_getallocf(L, &ud);
  return *static_cast<Limits*>(ud);
}

void install_hook(lua_State* L) {
  Limits& g = limits_of(L);
  g.main = L;
  if (permanent(g)) lua_sethook(L, hook, LUA_MASKCOUNT, kSlice);
}

void begin_call(lua_State* L) {
  Limits& g = limits_of(L);
  g.used = 0;
  g.over_memory = false;
  g.refused = 0;
  g.fired.clear();
  g.interrupt.store(false);
  if (permanent(g))
    lua_sethook(g.main, hook, LUA_MASKCOUNT, kSlice);
  else
    lua_sethook(g.main, nullptr, 0, 0);
}

void clear_interrupt(lua_State* L) { limits_of(L).interrupt.store(false); }

void interrupt(Limits& g) {
  g.interrupt.store(true);
  if (!permanent(g)) arm(g);
}

bool limit_fired(lua_State* L) {
  const Limits& g = limits_of(L);
  return !g.fired.empty() || g.interrupt.load(std::memory_order_relaxed);
}

void guard_limits(lua_State* L) {
  lua_getglobal(L, "xpcall");
  lua_pushcclosure(L, l_xpcall, 1);
  lua_setglobal(L, "xpcall");
}

bool memory_message(lua_State* L, int status, const std::string& where, std::string& msg) {
  // a memory error that passed through a C function's lua_error is a run-time error with Lua's text
  const char* text = lua_tostring(L, -1);
  if (status != LUA_ERRMEM && !(status == LUA_ERRRUN && text && std::strcmp(text, "not enough memory") == 0))
    return false;
  const Limits& g = limits_of(L);
  if (g.max_bytes != 0 && g.refused != 0 && g.bytes + g.refused > g.max_bytes) {
    msg = where + ": the Lua heap reached its limit of " + mib(g.max_bytes) + " MiB (" + mib(g.bytes) +
          " MiB in use, " + mib(g.refused) + " MiB more asked for); --max-lua-memory MiB raises it, 0 removes it";
  } else {
    msg = where + ": not enough memory (the Lua heap held " + mib(g.bytes) + " MiB)";
  }
  return true;
}

}  // namespace beltsim::script
