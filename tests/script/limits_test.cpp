// The limits on every call into Lua (src/script/limits.cpp, lua_clock.cpp;
// docs/limits-and-safety.md): an instruction limit, a memory limit and wall-time and CPU-time
// limits with clear messages, Ctrl-C through the same hook, none of them escaped through a message
// handler or a long C function, and beltsim's own work not counted against a call's time.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <tuple>
#include <vector>

#include "lua.h"
#include "run_script.hpp"
#include "script/interpreter.hpp"
#include "script/lua_clock.hpp"
#include "support/scenes.hpp"
#include "support/scratch.hpp"

namespace beltsim::script {
namespace limits_test {

namespace fs = std::filesystem;
using test::expect_has;

fs::path root() {
  const fs::path d = beltsim::test::scratch_dir("beltsim_limits_test") / "limits";
  fs::create_directories(d / "out");
  return d;
}

// runs the text as <root>/limits.lua with the output folder <root>/out; the error message, or ""
std::string run(Interpreter& lua, const std::string& text) {
  return test::run_script(lua, root() / "limits.lua", text, root() / "out");
}

std::string run(const std::string& text, const Safety& s = {}) {
  Interpreter lua(s);
  return run(lua, text);
}

const std::string kScene = beltsim::test::two_pulley();

TEST(Limits, TheInstructionLimitStopsAnEndlessLoopWithinASecond) {
  Safety s;
  s.max_instructions = 10'000'000;
  for (const std::string& loop :
       {std::string("while true do end"), std::string("while true do pcall(function() while true do end end) end"),
        std::string("coroutine.wrap(function() while true do end end)()")}) {
    const auto t0 = std::chrono::steady_clock::now();
    const std::string msg = run("local x = 1\n" + loop + "\n", s);
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    expect_has(msg, {"limits.lua:2: ", "instruction limit", "10000000", "--max-instructions"});
    EXPECT_LT(wall, 1.0) << loop;
  }
}

TEST(Limits, TheInstructionBudgetIsPerCallFromTheHost) {
  Safety s;
  s.max_instructions = 10'000'000;
  Interpreter lua(s);
  // each run takes about 60 % of the budget: both pass
  const std::string body = "local x = 0 for i = 1, 3e6 do x = x + i end\n";
  EXPECT_EQ(run(lua, body), "");
  EXPECT_EQ(run(lua, body), "");
  EXPECT_NE(run(lua, body + body).find("instruction limit"), std::string::npos);
  EXPECT_EQ(run(lua, body), "") << "the next call has a budget again";
}

// the end.status row of the run's parameters.csv (in <root>/out)
std::string end_status() {
  std::ifstream f(root() / "out" / "parameters.csv");
  std::string line;
  while (std::getline(f, line))
    if (line.rfind("end.status,", 0) == 0) return line;
  return "";
}

// a limit that fires in a callback is named with the callback, its function's place and the
// simulated time, as an error of its own is, and parameters.csv says so (a user's trial: the
// limit's message alone, and end.status "failed" with "an error in a callback")
TEST(Limits, CallbacksCountAgainstTheCallThatRunsThem) {
  Safety s;
  s.max_instructions = 10'000'000;
  for (const auto& [callback, role, at] :
       {std::tuple{"sim:every(0.001, function() while true do end end)", "sim:every's function", "0.001"},
        std::tuple{"sim:when(function(sim) if sim.t > 0.002 then while true do end end return false end,\n"
                   "  function() end)",
                   "sim:when's condition", ""}}) {
    const std::string msg =
        run(std::string(kScene) + "local sim = s:start{ progress = false }\n" + callback + "\nsim:run_to(0.01)\n", s);
    // the callback's function at line 9, run_to after it
    const int run_to = 10 + static_cast<int>(std::string(callback).find('\n') != std::string::npos);
    const std::string where =
        role + std::string(" (function at ") + (root() / "limits.lua").string() + ":9) at t = " + at;
    expect_has(msg, {"limits.lua:" + std::to_string(run_to) + ": sim:run_to: " + where,
                     "limits.lua:9: ", "instruction limit"});
    expect_has(end_status(), {"end.status,failed,,derived,\"" + where, "instruction limit"});
  }
}

TEST(Limits, NoInstructionLimitMeansNone) {
  Safety s;
  s.max_instructions = 0;
  EXPECT_EQ(run("local x = 0 for i = 1, 2e7 do x = x + i end\n", s), "");
}

TEST(Limits, TheMemoryLimitStopsAGrowingTable) {
  Safety s;
  s.max_lua_memory = std::size_t(64) << 20;
  for (const std::uint64_t instructions : {std::uint64_t(10'000'000'000), std::uint64_t(0)}) {
    s.max_instructions = instructions;
    Interpreter lua(s);
    const std::string msg = run(lua, "local t = {}\nwhile true do t[#t + 1] = {} end\n");
    expect_has(msg, {"limits.lua:2: ", "the Lua heap reached its limit of 64 MiB", "--max-lua-memory"});
    EXPECT_EQ(run(lua, "local t = {} for i = 1, 1000 do t[i] = {} end\n"), "") << "usable afterwards";
  }
}

TEST(Limits, OneAllocationPastTheLimitIsRefusedAtOnce) {
  Safety s;
  s.max_lua_memory = std::size_t(64) << 20;
  const std::string msg = run("local x = 1\nlocal s = string.rep('x', 2^30)\n", s);
  expect_has(msg, {"limits.lua", "the Lua heap reached its limit of 64 MiB", "--max-lua-memory"});
}

// ---- message handlers --------------------------------------------------------------------------

// Lua calls a message handler with hooks off for an error the hook raised, so a handler's loop
// would run unlimited: every form stops with the limit's message
TEST(Limits, MessageHandlersRunUnderTheInstructionLimit) {
  const std::string loop = "function() while true do end end";
  const std::vector<std::string> forms{
      "xpcall(error, " + loop + ")",         // the limit fires in the handler; Lua calls it again
      "xpcall(" + loop + ", " + loop + ")",  // the handler is called for the limit's error
      "xpcall(error, function() pcall(" + loop + ") while true do end end)",
      "xpcall(" + loop + ", function() return xpcall(error, " + loop + ") end)",  // a handler set after it fired
      "xpcall(" + loop + ", function() return select(2, pcall(" + loop + ")) end)",
      "for i = 1, 3 do xpcall(" + loop + ", " + loop + ") end",
      "coroutine.wrap(function() xpcall(error, " + loop + ") end)()",
      "local co = coroutine.create(function() return xpcall(" + loop + ", " + loop +
          ") end) "
          "coroutine.resume(co) while true do end",
  };
  for (const bool trusted : {false, true}) {
    Safety s;
    s.trusted = trusted;
    s.max_instructions = 10'000'000;
    for (const std::string& form : forms)
      expect_has(run("local x = 1\n" + form + "\n", s), {"limits.lua:2: ", "instruction limit", "--max-instructions"});
  }
}

TEST(Limits, MessageHandlersRunUnderTheMemoryLimit) {
  Safety s;
  s.max_lua_memory = std::size_t(64) << 20;
  for (const std::uint64_t instructions : {std::uint64_t(10'000'000'000), std::uint64_t(0)}) {
    s.max_instructions = instructions;
    const std::string msg =
        run("local x = 1\nxpcall(function() local t = {} while true do t[#t + 1] = {} end end, "
            "function() while true do end end)\n",
            s);
    expect_has(msg, {"limits.lua:2: ", "the Lua heap reached its limit of 64 MiB"});
  }
}

TEST(Limits, XpcallIsLuasOtherwise) {
  Safety s;
  s.max_instructions = 10'000'000;
  EXPECT_EQ(
      run("local ok, m = xpcall(error, function(m) return 'h:' .. m end, 'e')\n"
          "assert(not ok and m == 'h:e', m)\n"
          "local ok2, tb = xpcall(function() error('boom') end, debug.traceback)\n"
          "assert(not ok2 and tb:find('boom') and tb:find('stack traceback'), tb)\n"
          "assert(select('#', xpcall(function() return 1, 2, 3 end, print)) == 4)\n"
          "local co = coroutine.wrap(function() return xpcall(function() coroutine.yield(1) return 2 end, print) end)\n"
          "assert(co() == 1)\n"
          "local ok3, v = co()\n"
          "assert(ok3 and v == 2)\n"
          "local ok4, e = pcall(xpcall, print)\n"
          "assert(not ok4 and e:find(\"bad argument #2 to 'xpcall'\"), e)\n",
          s),
      "");
}

// ---- time --------------------------------------------------------------------------------------

// The forms of Lua code and long C functions that stop in the process: every one stops with the
// limit's message, with and without a permanent hook (an instruction limit). (A string pattern
// that backtracks ends the process instead: tests/app/time_limits_test.py.) Each of the 18 runs
// spends the limit before it stops: 0.1 s, ten of the clock's 10 ms looks.
TEST(TimeLimits, EveryLongCallStops) {
  const std::string loop = "function() while true do end end";
  const std::vector<std::string> forms{
      "while true do end",
      "while true do pcall(" + loop + ") end",
      "xpcall(error, " + loop + ")",
      "coroutine.wrap(" + loop + ")()",
      "table.move({}, 1, 2^62, 2)",
      "local t = {} for i = 1, 1e5 do t[i] = {} end while true do collectgarbage() end",
      "while true do local s = ('x'):rep(2^24) end",
      "local s = ('x'):rep(2^24) while true do local u = s:upper() end",
      "coroutine.wrap(function() while true do pcall(string.rep, 'x', 2^24) end end)()",
  };
  for (const std::uint64_t instructions : {std::uint64_t(10'000'000'000), std::uint64_t(0)}) {
    Safety s;
    s.max_instructions = instructions;
    s.max_lua_wall = 0.1;
    for (const std::string& form : forms)
      expect_has(run("local x = 1\n" + form + "\n", s),
                 {"limits.lua", "the wall-time limit of a Lua call was reached: more than 0.1 s", "--max-lua-wall"});
  }
}

// in a coroutine the hook comes every 1000 instructions: 300 full collections of a heap of a
// million tables (10 ms each here) would pass the grace after the limit
TEST(TimeLimits, CollectionsInACoroutineStop) {
  Safety s;
  s.max_lua_wall = 1;  // past the making of the heap (0.2 s here)
  expect_has(run("local x = 1\n"
                 "coroutine.wrap(function() local t = {} for i = 1, 1e6 do t[i] = {} end "
                 "while true do collectgarbage() end end)()\n",
                 s),
             {"limits.lua:2: ", "the wall-time limit of a Lua call was reached", "--max-lua-wall"});
}

TEST(TimeLimits, TheCpuLimitStopsALoop) {
  Safety s;
  s.max_instructions = 0;
  s.max_lua_wall = 0;
  s.max_lua_cpu = 0.2;
  expect_has(run("local x = 1\nwhile true do end\n", s),
             {"limits.lua:2: the CPU-time limit of a Lua call was reached: more than 0.2 s", "--max-lua-cpu"});
}

// through the interpreter, on the CPU-time limit (the thread's CPU time, which a busy machine or
// the other tests running beside this one do not stretch, as they stretch wall time): 0.1 s of CPU
// a call passes a limit of 0.3 s however many calls came before, 0.4 s in one call does not. The
// wall-time limit is charged by the same code (CallClock, tested with given times below).
TEST(TimeLimits, EachCallHasItsOwnTime) {
  Safety s;
  s.max_lua_wall = 0;
  s.max_lua_cpu = 0.3;
  Interpreter lua(s);
  // os.clock: the process's CPU time, at least the Lua thread's (the clock's thread adds little)
  const std::string part = "local t0 = os.clock() while os.clock() - t0 < 0.1 do end\n";
  EXPECT_EQ(run(lua, part), "");
  EXPECT_EQ(run(lua, part), "");
  EXPECT_EQ(run(lua, part), "");
  EXPECT_NE(run(lua, part + part + part + part).find("CPU-time limit"), std::string::npos);
  EXPECT_EQ(run(lua, part), "") << "the next call has its time again";
}

// a run is beltsim's work, and each call of a law or callback in it a call of its own: a run that
// takes many times the limit, with a Lua law and a callback, passes
TEST(TimeLimits, BeltsimsOwnWorkIsNotCounted) {
  Safety s;
  s.max_lua_cpu = 0.05;  // five looks of the clock; CPU time, which a busy machine does not stretch
  s.max_lua_wall = 1;
  beltsim::test::TwoPulley p;
  p.driver = "torque = function(t, w) return -70 * math.min(t / 0.3, 1) end";
  const auto t0 = std::chrono::steady_clock::now();
  EXPECT_EQ(run(beltsim::test::two_pulley(p) + "local sim = s:start{ progress = false }\n"
                                               "local n = 0\n"
                                               "sim:every(0.001, function() n = n + 1 end)\n"
                                               "sim:run_to(1.0)\n"
                                               "assert(n > 100, n)\n",
                s),
            "");
  EXPECT_GT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 10 * s.max_lua_cpu)
      << "the script was too quick to show anything";
}

TEST(TimeLimits, ALawOrACallbackThatLoopsIsStopped) {
  Safety s;
  s.max_instructions = 0;
  s.max_lua_wall = 0.2;
  beltsim::test::TwoPulley p;
  p.driver = "torque = function(t, w) if t > 0.001 then while true do end end return -70 end";
  expect_has(run(beltsim::test::two_pulley(p) + "s:run{ t_end = 0.01, progress = false }\n", s),
             {"limits.lua:3: ", "wall-time limit", "--max-lua-wall"});
  expect_has(run(kScene + "local sim = s:start{ progress = false }\n"
                          "sim:every(0.001, function() while true do end end)\n"
                          "sim:run_to(0.01)\n",
                 s),
             {"limits.lua:10: sim:run_to: sim:every's function (function at " + (root() / "limits.lua").string() +
                  ":9) at t = 0.001 s: " + (root() / "limits.lua").string() + ":9: the wall-time limit",
              "--max-lua-wall"});
  expect_has(end_status(),
             {"end.status,failed,,derived,\"sim:every's function (function at " + (root() / "limits.lua").string() +
              ":9) at t = 0.001 s: " + (root() / "limits.lua").string() + ":9: the wall-time limit"});
}

// the clock's charging, from looks given here: only time in Lua code counts, a call's own
TEST(CallClock, ChargesLuaTimeToTheCallUnderWay) {
  using M = LuaMode;
  CallClock c;
  const auto look = [&](M mode, std::uint64_t call, int depth, double t, bool steady = true) {
    return c.look({mode, call, depth, t, t / 2, steady}, 1.0, 0.0);
  };
  EXPECT_EQ(look(M::kOutside, 0, 0, 0), TimeUp::kNone);
  EXPECT_EQ(look(M::kLua, 1, 0, 0.1), TimeUp::kNone);   // a new call: from the next look on
  EXPECT_EQ(look(M::kLua, 1, 0, 0.6), TimeUp::kNone);   // 0.5 s
  EXPECT_EQ(look(M::kWork, 1, 0, 5.0), TimeUp::kNone);  // beltsim's own work: not counted
  EXPECT_EQ(look(M::kLua, 2, 1, 5.1), TimeUp::kNone);   // a law: a call of its own
  EXPECT_EQ(look(M::kLua, 2, 1, 6.0), TimeUp::kNone);   // 0.9 s of the law's
  EXPECT_EQ(look(M::kLua, 3, 1, 6.5), TimeUp::kNone);   // the next law: its own time again
  EXPECT_EQ(look(M::kLua, 3, 1, 7.2), TimeUp::kNone);
  EXPECT_EQ(look(M::kLua, 1, 0, 7.3), TimeUp::kNone);  // back in the script: 0.6 s
  EXPECT_EQ(look(M::kLua, 1, 0, 7.6), TimeUp::kNone);  // 0.9 s
  // the host went to its own work and back in between: the call may have run only the last
  // kLookEvery of the 0.3 s
  EXPECT_EQ(look(M::kLua, 1, 0, 7.9, false), TimeUp::kNone);
  EXPECT_EQ(look(M::kLua, 1, 0, 8.0), TimeUp::kWall);  // 1.01 s
  EXPECT_EQ(look(M::kOutside, 0, 0, 8.0), TimeUp::kNone);
  EXPECT_EQ(look(M::kLua, 4, 0, 8.1), TimeUp::kNone);  // the next call from the host
  EXPECT_EQ(look(M::kLua, 4, 0, 8.9), TimeUp::kNone);
  // the CPU clock, charged the same way: 0.4 s so far (half the wall time here), then 0.25, 0.4
  EXPECT_EQ(c.look({M::kLua, 4, 0, 9.5, 4.7, true}, 0.0, 1.0), TimeUp::kNone);
  EXPECT_EQ(c.look({M::kLua, 4, 0, 10.0, 5.1, true}, 0.0, 1.0), TimeUp::kCpu);
}

// a global function running() for the script to call as its loop starts: it sets *flag
void announce_running(Interpreter& lua, std::atomic<bool>& flag) {
  lua_State* L = lua.state();
  lua_pushlightuserdata(L, &flag);
  lua_pushcclosure(
      L,
      [](lua_State* l) -> int {
        auto* f = static_cast<std::atomic<bool>*>(lua_touserdata(l, lua_upvalueindex(1)));
        f->store(true);
        f->notify_all();
        return 0;
      },
      1);
  lua_setglobal(L, "running");
}

TEST(Limits, InterruptRaisesInLuaCode) {
  // a loop, and a loop whose message handler loops too (called with hooks off for "interrupted!")
  for (const std::string& loop :
       {std::string("while true do x = x + 1 end"), std::string("xpcall(function() while true do x = x + 1 end end, "
                                                                "function() while true do end end)")})
    for (const std::uint64_t instructions : {std::uint64_t(10'000'000'000), std::uint64_t(0)}) {
      Safety s;
      s.max_instructions = instructions;
      Interpreter lua(s);
      std::atomic<bool> looping{false};
      announce_running(lua, looping);
      // Ctrl-C once the loop runs (one before the call would be cleared as the call starts)
      std::thread ctrl_c([&] {
        looping.wait(false);
        lua.interrupt();
      });
      const std::string msg = run(lua, "local x = 1\nrunning() " + loop + "\n");
      looping = true;  // (the thread ends also when the script failed before its loop)
      looping.notify_all();
      ctrl_c.join();
      expect_has(msg, {"limits.lua:2: interrupted!"});
      EXPECT_EQ(run(lua, "local x = 1\n"), "") << "the next call is not interrupted";
    }
}

}  // namespace limits_test
}  // namespace beltsim::script
