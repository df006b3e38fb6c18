// Limits on what one call into Lua may take (private to src/script; docs/limits-and-safety.md).
//
// Instructions: one count hook on the main thread (coroutines inherit it) adds up the instructions
// run since the host last called into Lua (a script run, a console command; the every/when
// callbacks of a live simulation count against the command that runs them) and raises an error
// naming file:line when the budget is spent. The same hook honours Ctrl-C: the console's signal
// handler calls interrupt(), which sets a flag, and the hook raises "interrupted!" at the next
// slice of instructions. Once a limit or Ctrl-C fires, the hook runs at every instruction and
// raises again each time until the host call ends, so a `pcall` in a loop cannot swallow it for
// ever. Lua calls a message handler with hooks off when the error was raised by the hook, where no
// limit could stop it: guard_limits' xpcall gives such an error back unchanged without running the
// script's handler, and refuses to start once a limit fired.
// Any count hook halves the speed of pure Lua code (Lua 5.4 then traps every instruction), so
// without an instruction limit or a time limit there is no permanent hook: interrupt() and the
// allocator arm the same hook for the next instruction when they need it.
//
// Memory: a lua_Alloc that counts the bytes of the Lua heap. An allocation that would pass the
// limit is first refused once (Lua then collects garbage, without finalisers, and asks again);
// if the heap is still over the limit, a small allocation is granted and the hook raises the
// error with file:line at its next slice, while one that would take the heap past the limit plus
// a margin (a quarter of the limit, at most 256 MiB) is refused: Lua's "not enough memory",
// which the host rewrites with memory_message() (Lua gives no file:line for memory errors).
//
// Time: the wall time and CPU time of each call into Lua, without beltsim's own work in it, timed
// by lua_clock.hpp, which also says what happens past them.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <string>

#include "lua.h"
#include "script/lua_clock.hpp"

namespace beltsim::script {

// with the time limits, max_wall and max_cpu [s] per call into Lua (lua_clock.hpp; 0: none)
struct Limits : TimeLimits {
  Limits();
  std::uint64_t max_instructions = 0;  // per call from the host; 0: none
  std::size_t max_bytes = 0;           // Lua heap; 0: none
  std::uint64_t used = 0;              // instructions since the host's call began
  std::size_t bytes = 0;               // the Lua heap now
  bool retried = false;                // an allocation was refused once: the next one is Lua's retry
  bool over_memory = false;            // a small allocation went past the limit: the hook raises
  std::size_t refused = 0;             // size of the last allocation refused outright (bytes)
  bool time_refused = false;           // an allocation was refused because the call's time was up
  std::string fired;                   // the limit that fired in this host call ("": none); raised again
  std::atomic<bool> interrupt{false};  // Ctrl-C: set from a signal handler, cleared by the host
  lua_State* main = nullptr;
};

// L's blocks from here on through the allocator that counts them against g (its data: g as the
// clock's TimeLimits)
void use_limits(lua_State* L, Limits& g);
Limits& limits_of(lua_State* L);
// installs the hook on L (the main thread) once, after the state is made
void install_hook(lua_State* L);
// a new call from the host: the instruction budget starts again and no interrupt is pending
void begin_call(lua_State* L);
// run_to stopped at a step end because of Ctrl-C: the stop was honoured there, no "interrupted!"
void clear_interrupt(lua_State* L);
// Ctrl-C: "interrupted!" at the next slice of instructions (async-signal-safe)
void interrupt(Limits& g);
// a limit fired in this host call, or Ctrl-C is pending: no more Lua code is to run in it
bool limit_fired(lua_State* L);
// Ctrl-C (or SIGTERM, SIGHUP) is pending: Lua code that failed now was interrupted. A law's or a
// callback's (lua_law.cpp, lua_sim.cpp) then stops the run it was called by, which honours the
// interrupt: it is taken (cleared, as run_to clears one it stopped for), so the Lua code that
// follows (a law evaluated as the outputs close, the script after the run) runs as after any
// stopped run. True when one was pending
bool take_interrupt(lua_State* L);
// replaces xpcall (both in the sandbox and with --trusted) with one whose message handler does not
// run once a limit fired (see above), and table.move and collectgarbage, which can run long in C,
// with ones that raise a limit that fired or a time that is up (table.move between slices of its
// range)
void guard_limits(lua_State* L);
// true when `status`/the error object on the stack top is a memory error; then `msg` is the
// message naming the limit (prefixed with `where`, e.g. the script's name)
bool memory_message(lua_State* L, int status, const std::string& where, std::string& msg);

}  // namespace beltsim::script
