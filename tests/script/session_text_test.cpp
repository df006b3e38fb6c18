// The console's session.lua statements for a command whose run Ctrl-C stopped or the live view's
// page changed (script/console_session.hpp): the runs to where each change came and the changes,
// and an assignment of the run's result kept on the last run, so that a later command reading it
// replays (the run itself, replayed against the page, is live_console_test.py's); and for what the
// prompt printed: printed again as the prompt showed it, after the command as it was typed.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "lauxlib.h"
#include "lua.h"
#include "script/console_session.hpp"

namespace beltsim::script {
namespace session_text_test {

class SessionText : public ::testing::Test {
 protected:
  void SetUp() override {
    L = luaL_newstate();
    lua_newuserdata(L, 1);  // the simulation `sim` (only its address is read)
    sim = lua_topointer(L, -1);
    lua_setglobal(L, "sim");
  }
  void TearDown() override { lua_close(L); }
  lua_State* L = nullptr;
  const void* sim = nullptr;
};

TEST_F(SessionText, AnAssignmentChangedFromThePageIsKeptOnItsLastRun) {
  // the user's: `r = sim:run_to(1.0)` was replayed without `r =`, and `print(r.t)` after it failed
  const std::vector<PageChange> page{{sim, 0.25, "set_torque(\"driven\", -60)"}, {sim, 1, ""}};
  EXPECT_EQ(replayable(L, "r = sim:run_to(1.0)", false, false, {}, page),
            "-- r = sim:run_to(1.0)  -- changed from the live view while it ran\n"
            "sim:run_to(0.25)\n"
            "sim:set_torque(\"driven\", -60)\n"
            "r = sim:run_to(1)");
  const std::string local = replayable(L, "local r = sim:advance(1)", false, false, {}, page);
  EXPECT_TRUE(local.ends_with("\nsim:set_torque(\"driven\", -60)\nlocal r = sim:run_to(1)")) << local;
  // no assignment: the runs alone, as before
  EXPECT_EQ(replayable(L, "sim:run_to(1.0)", false, false, {}, page),
            "-- sim:run_to(1.0)  -- changed from the live view while it ran\n"
            "sim:run_to(0.25)\n"
            "sim:set_torque(\"driven\", -60)\n"
            "sim:run_to(1)");
}

TEST_F(SessionText, ARunThatEndedWhereThePageChangedItHoldsTheResultInARunOfNoSteps) {
  // Ctrl-C during the page's pause: the run ends where the last change came
  const std::vector<PageChange> page{{sim, 0.25, "set_torque(\"driven\", -60)"}, {sim, 0.25, ""}};
  EXPECT_EQ(replayable(L, "r = sim:run_to(1.0)", false, false, {{sim, 0.25}}, page),
            "-- r = sim:run_to(1.0)  -- changed from the live view while it ran\n"
            "sim:run_to(0.25)\n"
            "sim:set_torque(\"driven\", -60)\n"
            "r = sim:run_to(0.25)");
}

TEST_F(SessionText, OnlyTheResultOfTheNamedSimulationsRunIsKept) {
  lua_newuserdata(L, 1);
  const void* other = lua_topointer(L, -1);
  lua_setglobal(L, "other");
  const std::vector<PageChange> page{{other, 0.25, "set_torque(\"driven\", -60)"}, {other, 1, ""}};
  EXPECT_EQ(replayable(L, "r = sim:run_to(1.0)", false, false, {}, page).find("r = other"), std::string::npos);
  // Ctrl-C: kept as before
  EXPECT_EQ(replayable(L, "r = sim:advance(10)", false, false, {{sim, 0.5}}, {}),
            "-- r = sim:advance(10)  -- stopped by Ctrl-C\nr = sim:run_to(0.5)");
  // an assignment that failed assigned nothing: the runs alone
  EXPECT_EQ(failed_replayable(L, "r = sim:run_to(1.0)", false, "stdin:1: x", {},
                              {{sim, 0.25, "save(\"a.ckpt\")"}, {sim, 0.5, ""}}),
            "-- failed at the prompt: stdin:1: x\n"
            "-- r = sim:run_to(1.0)  -- changed from the live view while it ran\n"
            "sim:run_to(0.25)\n"
            "sim:save(\"a.ckpt\")\n"
            "sim:run_to(0.5)");
}

TEST_F(SessionText, WhatThePromptPrintedIsPrintedAsItShowedItAfterTheCommandAsTyped) {
  // the user's: `r` (a run's result) was recorded as print(r), which a replay prints as
  // "table: 0x55d0...", and which reads as if print(r) had been typed
  EXPECT_EQ(replayable(L, "r", true, true, {}, {}), "-- > r\nbeltsim.print(r)");
  EXPECT_EQ(replayable(L, "r.t, r.steps", true, true, {}, {}), "-- > r.t, r.steps\nbeltsim.print(r.t, r.steps)");
  EXPECT_EQ(replayable(L, "return 6*7", false, true, {}, {}),
            "-- > return 6*7\nbeltsim.print((function(...)\nreturn 6*7\nend)())");
  // a trailing comment, and a chunk of two lines, as the prompt showed them ("> ", ">> ")
  EXPECT_EQ(replayable(L, "f() + 1 -- a comment", true, true, {}, {}),
            "-- > f() + 1 -- a comment\nbeltsim.print(f() + 1 -- a comment\n)");
  EXPECT_EQ(replayable(L, "1 +\n2", true, true, {}, {}), "-- > 1 +\n-- >> 2\nbeltsim.print(1 +\n2)");
  // as typed: a call (a run, a reading: made again, its values not printed again), a statement
  EXPECT_EQ(replayable(L, "sim:pulley(\"driven\")", true, true, {}, {}), "sim:pulley(\"driven\")");
  EXPECT_EQ(replayable(L, "print(z)", true, false, {}, {}), "print(z)");
  EXPECT_EQ(replayable(L, "y = 2", false, false, {}, {}), "y = 2");
  EXPECT_EQ(replayable(L, "return", false, false, {}, {}), "do (function(...)\nreturn\nend)() end");
  // an expression that failed would have been printed; a call that failed is replayed as it is
  EXPECT_EQ(failed_replayable(L, "nosuch.x", true, "stdin:1: attempt to index a nil value", {}, {}),
            "-- failed at the prompt: stdin:1: attempt to index a nil value\npcall(function()\n-- > nosuch.x\n"
            "beltsim.print(nosuch.x)\nend)");
  EXPECT_EQ(failed_replayable(L, "nosuch()", true, "stdin:1: x", {}, {}),
            "-- failed at the prompt: stdin:1: x\npcall(function()\nnosuch()\nend)");
}

}  // namespace session_text_test
}  // namespace beltsim::script
