// The host's mode and the clock of each call into Lua (see lua_clock.hpp).
#include "script/lua_clock.hpp"

#include <pthread.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <string>
#include <thread>

#include "io/number_text.hpp"
#include "lua.h"
#include "script/progress.hpp"

namespace beltsim::script {

namespace {

// how long the hook has to raise a time limit before large allocations are refused (their error
// names no line)
constexpr double kRefuseAfter = 1;

// what the host is doing, in one word for one atomic load: the call under way (a serial number)
// << 10 | how many calls it is inside (saturated at 255) << 2 | the mode
std::uint64_t pack(std::uint64_t call, int depth, LuaMode mode) {
  return call << 10 | static_cast<std::uint64_t>(std::min(depth, 255)) << 2 | static_cast<std::uint64_t>(mode);
}
LuaMode mode_of(std::uint64_t s) {
  return static_cast<LuaMode>(s & 3);
}
int depth_of(std::uint64_t s) {
  return static_cast<int>((s >> 2) & 255);
}
std::uint64_t call_of(std::uint64_t s) {
  return s >> 10;
}

std::atomic<std::uint64_t> g_state{0};
std::atomic<unsigned> g_changes{0};
std::uint64_t g_calls = 0;                // the last call's serial number (the Lua thread's alone)
std::atomic<std::uint64_t> g_expired{0};  // the call whose time is up (0: none)
std::atomic<int> g_expired_kind{0};       // its TimeUp
std::atomic<std::uint64_t> g_overdue{0};  // the call still in Lua code kRefuseAfter after it (0: none)
std::atomic<clockid_t> g_cpu_clock{CLOCK_THREAD_CPUTIME_ID};  // of the thread that runs Lua
std::atomic<bool> g_cpu_known{false};
std::atomic<TimeLimits*> g_limits{nullptr};  // the limits of the call under way
char g_what[512] = "";                       // the outermost call's name (a script's path, "stdin")
static_assert(std::atomic<std::uint64_t>::is_always_lock_free && std::atomic<clockid_t>::is_always_lock_free);

// the clock's use of g_limits against the interpreter going away (never destroyed: the thread may
// still run while the process exits)
std::mutex& limits_mutex() {
  static auto* m = new std::mutex;
  return *m;
}

double cpu_seconds() {
  timespec ts{};
  if (!g_cpu_known.load() || clock_gettime(g_cpu_clock.load(), &ts) != 0) return -1;
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// the C function under way did not return after the limit: the process ends (write(2) only on
// stderr; stdout is flushed unless the Lua thread holds it, as in a write that blocks)
[[noreturn]] void end_process(const TimeLimits& g, TimeUp up) {
  std::string m = "\nbeltsim: ";
  if (g_what[0]) m += std::string(g_what) + ": ";
  m += time_message(g, up) +
       "; a C function called from Lua (a string pattern that backtracks, a read that waits) "
       "did not return within " +
       std::to_string(kGraceAfterLimit.count()) +
       " s of it, and Lua cannot stop one: beltsim ends here; the outputs written so far are kept\n";
  if (ftrylockfile(stdout) == 0) {
    std::fflush(stdout);
    funlockfile(stdout);
  }
  [[maybe_unused]] const ssize_t n = write(STDERR_FILENO, m.data(), m.size());
  restore_echo();  // a progress line's (progress.hpp): _exit unwinds nothing
  _exit(1);
}

void clock_thread() {
  using clock = std::chrono::steady_clock;
  const clock::time_point t0 = clock::now();
  CallClock calls;
  double stuck_since = -1;  // [s] since when the call whose time is up has been seen in Lua code
  double cpu = 0;
  unsigned changes = 0;
  for (;;) {
    std::this_thread::sleep_for(kLookEvery);
    const std::uint64_t s = g_state.load();
    const unsigned now_changes = g_changes.load();
    const bool steady = now_changes == changes;
    changes = now_changes;
    const double wall = std::chrono::duration<double>(clock::now() - t0).count();
    if (const double c = cpu_seconds(); c >= 0) cpu = c;
    const std::lock_guard<std::mutex> lock(limits_mutex());
    TimeLimits* g = g_limits.load();
    const TimeUp up =
        calls.look({mode_of(s), call_of(s), depth_of(s), wall, cpu, steady}, g ? g->max_wall : 0, g ? g->max_cpu : 0);
    if (!g) continue;
    if (up != TimeUp::kNone && g_expired.load() != call_of(s)) {
      g_expired_kind.store(static_cast<int>(up));
      g_expired.store(call_of(s));
      stuck_since = -1;
      if (g->time_is_up) g->time_is_up(*g);
    }
    if (g_expired.load() != call_of(s) || mode_of(s) != LuaMode::kLua) {
      stuck_since = -1;
    } else if (stuck_since < 0) {
      stuck_since = wall;
    } else if (wall - stuck_since > kRefuseAfter && g_overdue.load() != call_of(s)) {
      g_overdue.store(call_of(s));
    } else if (wall - stuck_since > std::chrono::duration<double>(kGraceAfterLimit).count()) {
      end_process(*g, static_cast<TimeUp>(g_expired_kind.load()));
    }
  }
}

}  // namespace

LuaMode lua_mode() {
  return mode_of(g_state.load());
}
unsigned lua_mode_changes() {
  return g_changes.load();
}

TimeUp time_up() {
  const std::uint64_t s = g_state.load(std::memory_order_relaxed);
  if (mode_of(s) == LuaMode::kOutside || call_of(s) != g_expired.load(std::memory_order_relaxed)) return TimeUp::kNone;
  return static_cast<TimeUp>(g_expired_kind.load(std::memory_order_relaxed));
}

bool time_overdue() {
  const std::uint64_t s = g_state.load(std::memory_order_relaxed);
  return mode_of(s) != LuaMode::kOutside && call_of(s) == g_overdue.load(std::memory_order_relaxed);
}

void start_lua_clock() {
  static std::once_flag once;
  std::call_once(once, [] {
    // the thread takes no signals (the stop signals' handlers run on the main thread)
    sigset_t all, old;
    sigfillset(&all);
    pthread_sigmask(SIG_SETMASK, &all, &old);
    std::thread(clock_thread).detach();
    pthread_sigmask(SIG_SETMASK, &old, nullptr);
  });
}

void forget_limits(const TimeLimits* limits) {
  const std::lock_guard<std::mutex> lock(limits_mutex());
  if (g_limits.load() == limits) g_limits.store(nullptr);
}

InsideLua::InsideLua(lua_State* L, const char* what) : saved_(g_state.load(std::memory_order_relaxed)) {
  const LuaMode mode = mode_of(saved_);
  if (mode != LuaMode::kLua) {  // a new call: from outside Lua, or from the host's work
    new_call_ = true;
    int depth = 0;
    if (mode == LuaMode::kOutside) {
      clockid_t c;
      if (pthread_getcpuclockid(pthread_self(), &c) == 0) g_cpu_clock.store(c), g_cpu_known.store(true);
      if (what) std::snprintf(g_what, sizeof g_what, "%s", what);
    } else {
      depth = depth_of(saved_) + 1;
    }
    void* ud = nullptr;
    lua_getallocf(L, &ud);  // the state's limits (use_limits)
    saved_limits_ = g_limits.exchange(static_cast<TimeLimits*>(ud));
    g_state.store(pack(++g_calls, depth, LuaMode::kLua));
  }
  g_changes.fetch_add(1);
}

InsideLua::~InsideLua() {
  if (new_call_) g_limits.store(saved_limits_);
  g_state.store(saved_);
  g_changes.fetch_add(1);
}

HostWork::HostWork() : saved_(g_state.load(std::memory_order_relaxed)) {
  g_state.store(pack(call_of(saved_), depth_of(saved_), LuaMode::kWork));
  g_changes.fetch_add(1);
}

HostWork::~HostWork() {
  g_state.store(saved_);
  g_changes.fetch_add(1);
}

std::string time_message(const TimeLimits& g, TimeUp up) {
  const bool wall = up == TimeUp::kWall;
  const std::string s = rounded_text(wall ? g.max_wall : g.max_cpu, 6);
  return std::string("the ") + (wall ? "wall-time" : "CPU-time") + " limit of a Lua call was reached: more than " + s +
         " s of " + (wall ? "wall" : "CPU") +
         " time in one call (a script run, a console command, a sweep point, a callback or a law, beltsim's own "
         "work in it not counted; a loop or a string pattern that never ends" +
         (wall ? ", or a read that waits" : "") + "?); " + (wall ? "--max-lua-wall" : "--max-lua-cpu") +
         " S raises it, 0 removes it";
}

TimeUp CallClock::look(const Look& now, double max_wall, double max_cpu) {
  const double wall = looked_ ? now.wall - wall_ : 0, cpu = looked_ ? std::max(0.0, now.cpu - cpu_) : 0;
  wall_ = now.wall;
  cpu_ = now.cpu;
  looked_ = true;
  if (now.mode == LuaMode::kOutside) {
    calls_.clear();
    return TimeUp::kNone;
  }
  const auto depth = static_cast<std::size_t>(now.depth);
  if (calls_.size() > depth + 1) calls_.resize(depth + 1);  // the calls inside it have ended
  if (calls_.size() == depth + 1 && calls_[depth].serial != now.call) calls_.resize(depth);
  if (calls_.size() < depth + 1) {  // a call not seen before: charged from the next look on
    calls_.resize(depth + 1, Call{0});
    calls_[depth] = Call{now.call};
    return TimeUp::kNone;
  }
  Call& c = calls_[depth];
  if (now.mode != LuaMode::kLua) return TimeUp::kNone;
  const double most = now.steady ? wall : std::chrono::duration<double>(kLookEvery).count();
  c.wall += std::min(wall, most);
  c.cpu += std::min(cpu, most);
  if (max_wall > 0 && c.wall > max_wall) return TimeUp::kWall;
  if (max_cpu > 0 && c.cpu > max_cpu) return TimeUp::kCpu;
  return TimeUp::kNone;
}

}  // namespace beltsim::script
