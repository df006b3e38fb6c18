// What the host is doing (running Lua code or its own work) and the clock that times each call
// into Lua against its wall-time and CPU-time limits (private to src/script;
// docs/limits-and-safety.md).
//
// A call into Lua begins where the host runs Lua code from outside any or from its own work: a
// script run, a console command, a sweep point; a law or an every/when callback while a run is
// under way. A Lua call made from Lua code (an io function the sandbox wraps) is part of the one
// under way. A thread looks at what the host is doing every few milliseconds and charges the time
// since its last look to the call under way when that call is running Lua code, not beltsim's own
// work (a run, and the laws and callbacks it calls, which are calls of their own): its wall time,
// and the CPU time of the thread that runs Lua. Past either limit the call's time is up: the hook
// raises the limit's error at its next instruction (limits.hpp; the hook is armed for it), the
// wrappers of long C functions (table.move, collectgarbage) raise it, and when the call is still in
// Lua code a second later (a loop of string.rep in a coroutine, where the hook comes
// only every slice of instructions, or never without an instruction limit) an allocation of
// kLargeBlock or more is refused. A C function that has
// still not returned kGraceAfterLimit later (a string pattern that backtracks, a read that blocks)
// cannot be stopped from inside Lua: the process ends with the limit's message on stderr and exit
// status 1, the outputs written so far kept (as after a kill).
#pragma once

#include <chrono>
#include <cstdint>
#include <string>
#include <vector>

struct lua_State;

namespace beltsim::script {

enum class LuaMode : int { kOutside = 0, kLua = 1, kWork = 2 };
enum class TimeUp : int { kNone = 0, kWall = 1, kCpu = 2 };

inline constexpr std::chrono::seconds kGraceAfterLimit{2};
inline constexpr std::chrono::milliseconds kLookEvery{10};  // the clock's looks (the limits are kept to this)
inline constexpr std::size_t kLargeBlock = std::size_t(1) << 20;

// The time limits of one interpreter's calls into Lua, as the clock reads them (limits.hpp's Limits
// holds them): its Lua state's allocator data points to them (use_limits), and when a call passes
// one the clock's thread calls time_is_up, which makes the hook raise its error.
struct TimeLimits {
  double max_wall = 0, max_cpu = 0;  // [s] per call into Lua; 0: none
  void (*time_is_up)(TimeLimits&) = nullptr;
};
// the message of a time limit passed (without a place)
std::string time_message(const TimeLimits& t, TimeUp up);

// what the host is doing (for the stop signals' watchdog, signals.hpp): the mode, and a counter
// that changes at every change of it
LuaMode lua_mode();
unsigned lua_mode_changes();

// the limit the call under way has passed (kNone: none, or no call under way)
TimeUp time_up();
// its time has been up for a second: large allocations are refused
bool time_overdue();

// starts the clock's thread (once per process; later calls do nothing)
void start_lua_clock();
// the interpreter that owns these limits is going away: the clock no longer looks at them
void forget_limits(const TimeLimits* limits);

// the host is running Lua code (docall, a callback) for the guard's lifetime; `what` names a new
// call for the message that ends the process (nullptr: the call under way's name is kept)
class InsideLua {
 public:
  explicit InsideLua(lua_State* L, const char* what = nullptr);
  ~InsideLua();
  InsideLua(const InsideLua&) = delete;
  InsideLua& operator=(const InsideLua&) = delete;

 private:
  std::uint64_t saved_;
  TimeLimits* saved_limits_ = nullptr;
  bool new_call_ = false;
};

// beltsim's own work called from Lua (a run, which polls the stop flag; closing the outputs)
class HostWork {
 public:
  HostWork();
  ~HostWork();
  HostWork(const HostWork&) = delete;
  HostWork& operator=(const HostWork&) = delete;

 private:
  std::uint64_t saved_;
};

// The charging of time to calls, from looks at what the host is doing (the clock's thread makes
// them; a test gives its own times).
class CallClock {
 public:
  struct Look {
    LuaMode mode;
    std::uint64_t call;  // the call under way (its serial number)
    int depth;           // how many calls it is inside (0: the host called it from outside Lua)
    double wall, cpu;    // [s] the clocks now
    bool steady;         // the host has not changed what it does since the last look
  };
  // charges the time since the last look to the call under way when it runs Lua code and was under
  // way at the last look too (all of it when the host was steady, else at most kLookEvery: the call
  // may have run only part of it); returns the limit it has passed (max_*: 0 for none)
  TimeUp look(const Look& now, double max_wall, double max_cpu);

 private:
  struct Call {
    std::uint64_t serial;
    double wall = 0, cpu = 0;  // [s] charged so far
  };
  std::vector<Call> calls_;  // by depth: the calls under way, the host's first
  double wall_ = 0, cpu_ = 0;
  bool looked_ = false;
};

}  // namespace beltsim::script
