// The instruction, memory and time limits and the Ctrl-C hook (see limits.hpp).
#include "script/limits.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "io/number_text.hpp"
#include "lauxlib.h"
#include "lualib.h"

namespace beltsim::script {

namespace {

// instructions between two calls of the hook (Ctrl-C is seen within microseconds). Any count hook
// sends every instruction through Lua's slow path (luaG_traceexec): pure Lua code runs at about
// half speed with it, whatever the count; hence no permanent hook without a limit that needs it.
constexpr int kSlice = 1000;

// the hook stays installed to count instructions and to see a call's time up in every coroutine
// (a coroutine takes its hook from the thread that makes it; the clock's thread can arm only the
// main one); otherwise it is armed when needed
bool permanent(const Limits& g) {
  return g.max_instructions != 0 || g.max_wall > 0 || g.max_cpu > 0;
}

void hook(lua_State* L, lua_Debug* ar);

// arms the hook to run at the next instruction (lua_sethook may be called asynchronously: from a
// signal handler, or from the allocator in the middle of an instruction)
void arm(Limits& g) {
  if (g.main) lua_sethook(g.main, hook, LUA_MASKCOUNT, 1);
}

std::string mib(std::size_t bytes) {
  return rounded_text(static_cast<double>(bytes) / (1 << 20), 6);
}

// the margin past the limit that small allocations may use while the hook comes round to
// raising the error
std::size_t margin(std::size_t max) {
  return std::min<std::size_t>(max / 4, std::size_t(256) << 20);
}

// the limit that fired in this host call, noting one passed just now ("": none; Ctrl-C is apart)
const std::string& check_fired(Limits& g) {
  if (!g.fired.empty()) return g.fired;
  if (g.max_instructions != 0 && g.used > g.max_instructions) {
    g.fired = "the instruction limit was reached: more than " + std::to_string(g.max_instructions) +
              " Lua instructions in one call (a script run or a console command, with the callbacks it runs; a "
              "loop that never ends?); --max-instructions N raises it, 0 removes it";
  } else if (g.over_memory) {
    g.over_memory = false;
    g.fired =
        "the Lua heap reached its limit of " + mib(g.max_bytes) + " MiB; --max-lua-memory MiB raises it, 0 removes it";
  } else if (const TimeUp up = time_up(); up != TimeUp::kNone) {
    g.fired = time_message(g, up);
  }
  return g.fired;
}

// raises "interrupted!" or the limit that fired, if any (a wrapper of a long C function)
void raise_fired(lua_State* L) {
  Limits& g = limits_of(L);
  if (g.interrupt.load(std::memory_order_relaxed)) luaL_error(L, "interrupted!");
  if (!check_fired(g).empty()) luaL_error(L, "%s", g.fired.c_str());
}

void hook(lua_State* L, lua_Debug* ar) {
  Limits& g = limits_of(L);
  const int count = lua_gethookcount(L);
  g.used += static_cast<std::uint64_t>(count);
  check_fired(g);
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

int xpcall_done(lua_State* L, int /*status*/, lua_KContext /*ctx*/) {
  return lua_gettop(L);
}

// xpcall(f, msgh, ...): Lua's (upvalue 1) with msgh guarded; none once a limit fired
int l_xpcall(lua_State* L) {
  raise_fired(L);
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

// collectgarbage(...): Lua's (upvalue 1), unless a limit fired (a loop of full collections of a
// large heap runs few instructions between them)
int l_collectgarbage(lua_State* L) {
  raise_fired(L);
  lua_pushvalue(L, lua_upvalueindex(1));
  lua_insert(L, 1);
  lua_call(L, lua_gettop(L) - 1, LUA_MULTRET);
  return lua_gettop(L);
}

// elements table.move moves between two looks at the limits (a few ms)
constexpr lua_Unsigned kMoveSlice = 1 << 16;

// table.move(a1, f, e, t [, a2]): Lua's (upvalue 1) over slices of the range in the order Lua's
// takes it, the limits checked between them: one call of Lua's over 2^62 elements runs for ever
// in C, where no hook is called
int l_table_move(lua_State* L) {
  const lua_Integer f = luaL_checkinteger(L, 2), e = luaL_checkinteger(L, 3), t = luaL_checkinteger(L, 4);
  if (e < f || static_cast<lua_Unsigned>(e) - static_cast<lua_Unsigned>(f) < kMoveSlice) {
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_insert(L, 1);
    lua_call(L, lua_gettop(L) - 1, 1);
    return 1;
  }
  const int tt = lua_isnoneornil(L, 5) ? 1 : 5;
  luaL_argcheck(L, f > 0 || e < LUA_MAXINTEGER + f, 3, "too many elements to move");  // Lua's own checks
  const lua_Integer n = e - f + 1;
  luaL_argcheck(L, t <= LUA_MAXINTEGER - n + 1, 4, "destination wrap around");
  const bool forward = t > e || t <= f || (tt != 1 && !lua_compare(L, 1, tt, LUA_OPEQ));
  for (lua_Unsigned k = 0; k < static_cast<lua_Unsigned>(n); k += kMoveSlice) {
    const auto len = static_cast<lua_Integer>(std::min(kMoveSlice, static_cast<lua_Unsigned>(n) - k));
    const lua_Integer lo = forward ? f + static_cast<lua_Integer>(k) : e - static_cast<lua_Integer>(k) - len + 1;
    lua_pushvalue(L, lua_upvalueindex(1));
    lua_pushvalue(L, 1);
    lua_pushinteger(L, lo);
    lua_pushinteger(L, lo + len - 1);
    lua_pushinteger(L, t + (lo - f));
    lua_pushvalue(L, tt);
    lua_call(L, 5, 0);
    raise_fired(L);
  }
  lua_pushvalue(L, tt);
  return 1;
}

void* limited_alloc(void* ud, void* ptr, size_t osize, size_t nsize) {
  auto* g = static_cast<Limits*>(static_cast<TimeLimits*>(ud));
  const std::size_t old = ptr ? osize : 0;  // without a block, osize is the kind of object
  if (nsize == 0) {
    std::free(ptr);
    g->bytes -= old;
    return nullptr;
  }
  if (nsize >= kLargeBlock && nsize > old && time_overdue()) {  // a loop of string.rep ends
    if (g->fired.empty()) g->fired = time_message(*g, time_up());
    g->time_refused = true;
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

}  // namespace

Limits& limits_of(lua_State* L) {
  void* ud = nullptr;
  lua_getallocf(L, &ud);
  return *static_cast<Limits*>(static_cast<TimeLimits*>(ud));
}

void use_limits(lua_State* L, Limits& g) {
  lua_setallocf(L, limited_alloc, static_cast<TimeLimits*>(&g));
}

Limits::Limits() {
  // the call's time is up (the clock's thread): the hook raises at the next instruction
  time_is_up = [](TimeLimits& t) { arm(static_cast<Limits&>(t)); };
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
  g.time_refused = false;
  g.fired.clear();
  g.interrupt.store(false);
  if (permanent(g))
    lua_sethook(g.main, hook, LUA_MASKCOUNT, kSlice);
  else
    lua_sethook(g.main, nullptr, 0, 0);
}

void clear_interrupt(lua_State* L) {
  limits_of(L).interrupt.store(false);
}

void interrupt(Limits& g) {
  g.interrupt.store(true);
  if (!permanent(g)) arm(g);
}

bool take_interrupt(lua_State* L) {
  return limits_of(L).interrupt.exchange(false);
}

bool limit_fired(lua_State* L) {
  const Limits& g = limits_of(L);
  return !g.fired.empty() || g.interrupt.load(std::memory_order_relaxed);
}

void guard_limits(lua_State* L) {
  lua_getglobal(L, "xpcall");
  lua_pushcclosure(L, l_xpcall, 1);
  lua_setglobal(L, "xpcall");
  lua_getglobal(L, "collectgarbage");
  lua_pushcclosure(L, l_collectgarbage, 1);
  lua_setglobal(L, "collectgarbage");
  lua_getglobal(L, LUA_TABLIBNAME);
  lua_getfield(L, -1, "move");
  lua_pushcclosure(L, l_table_move, 1);
  lua_setfield(L, -2, "move");
  lua_pop(L, 1);
}

bool memory_message(lua_State* L, int status, const std::string& where, std::string& msg) {
  // a memory error that passed through a C function's lua_error is a run-time error with Lua's text
  const char* text = lua_tostring(L, -1);
  if (status != LUA_ERRMEM && !(status == LUA_ERRRUN && text && std::strcmp(text, "not enough memory") == 0))
    return false;
  const Limits& g = limits_of(L);
  if (g.time_refused) {
    msg = where + ": " + g.fired;  // an allocation after the call's time was up
  } else if (g.max_bytes != 0 && g.refused != 0 && g.bytes + g.refused > g.max_bytes) {
    msg = where + ": the Lua heap reached its limit of " + mib(g.max_bytes) + " MiB (" + mib(g.bytes) +
          " MiB in use, " + mib(g.refused) + " MiB more asked for); --max-lua-memory MiB raises it, 0 removes it";
  } else {
    msg = where + ": not enough memory (the Lua heap held " + mib(g.bytes) + " MiB)";
  }
  return true;
}

}  // namespace beltsim::script
