// The Lua scenario API's checks of its input: bad input stops before simulating with file:line, the
// reason and the value; unknown keys are errors. Its runs and what they write: lua_api_runs_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "lua_api_support.hpp"
#include "support/scenes.hpp"

namespace beltsim::script {
namespace lua_api_test {

TEST(LuaApi, ValidSceneBuilds) { EXPECT_EQ(run_text(scene_text("")), ""); }

// scene:info()'s fields carry their units, which beltsim.print and the console print after them
// (trial 19: its lengths printed bare where sim:stats()'s times said s)
TEST(LuaApi, SceneInfoFieldsCarryTheirUnits) {
  EXPECT_EQ(
      run_text(scene_text("") +
               "local u = getmetatable(s:info()).__units\n"
               "for f, want in pairs{ pitch = 'm', rest_length = 'm', route_length = 'm', s_length = 'm', "
               "mass = 'kg', k = 'N/m', c = 'N·s/m', kt = 'N·m/rad', ct = 'N·m·s/rad', static_tension = 'N', "
               "static_residual = 'm/s²' } do\n"
               "  assert(u[f] == want, f .. ': ' .. tostring(u[f]))\n"
               "end\n"
               "assert(u.elements == nil and u.strain == nil)\n"
               "local b = getmetatable(s:info().bending_loss).__units\n"
               "assert(b.belt_speed == 'm/s' and b.transmitted == 'W' and b.dissipated == 'W' and b.share == nil)\n"),
      "");
}

// values that used to be taken silently or misread (issue 12): each is an error naming the key
TEST(LuaApi, SilentMisreadingsAreErrors) {
  struct Case {
    std::string text, expect;
  };
  const std::string ok_scene = scene_text("");
  // the test scene with n elements and a line of more scene keys
  auto with_elements = [](int n, const std::string& scene_keys) {
    beltsim::test::TwoPulley p;
    p.elements = n, p.extra = scene_keys;
    return beltsim::test::two_pulley(p);
  };
  for (const Case& c : std::vector<Case>{
           {scene_text("mu = {}"), "belt.mu: an empty list"},
           {scene_text("EA = 1e308"), "belt.EA (per SDE: EA / l0) is beyond what double precision integrates"},
           {scene_text("axial_damping = 1e308"), "belt.axial_damping (per SDE: axial_damping / l0)"},
           {scene_text("mu = {1, nil, 1}"), "belt.mu: a list without holes"},
           {scene_text("route = {}"), "belt.route: at least two pulley names"},
           {scene_text("", "centre = {0.29, 0}, center = {0.3, 0}, radius = 0.1"), "give centre or center, not both"},
           {scene_text("", "centre = {0/0, 0}, radius = 0.1"), "a finite point"},
           {ok_scene + "s:element_near{0/0, 0}\n", "a finite point"},
           {ok_scene + "s:run{ t_end = 0.01, probe = {0/0, 0} }\n", "a finite point"},
           {ok_scene + "s:run{ t_end = 0.01, events = { {t = 0.001, mu = 0.5}, nil, {t = 0.002, mu = 0.5} } }\n",
            "run.events: a list without holes"},
           {ok_scene + "s:run{ t_end = 0.01, events = { {t = 0.001, mu = '0.5'} } }\n",
            "number or function(site) expected"},
           {ok_scene + "s:run{ t_end = 0.01, atol = -1 }\n", "run.atol: must be > 0"},
           // a value in a message as given, not rounded to six decimals ("got -0.000000")
           {ok_scene + "s:run{ t_end = 0.01, atol = -1e-9 }\n",
            "run.atol: must be > 0 and finite, or left out to mean rtol (got -1e-09)"},
           {ok_scene + "s:run{ t_end = 0.01, max_wall = -1e-9 }\n",
            "run.max_wall: must be > 0 s and finite (got -1e-09 s)"},
           {ok_scene + "s:run{ t_end = 0.01, snapshots = { every = -1e-9 } }\n",
            "run.snapshots.every: must be > 0 s and finite (got -1e-09 s)"},
           {ok_scene + "s:run{ t_end = 0.01, rtol = 1e-15 }\n",
            "run.rtol: must be in [1e-12, 1) (got 1e-15): double precision"},
           {ok_scene + "s:run{ t_end = 0.01, rtol = 0 }\n", "run.rtol: must be in [1e-12, 1) (got 0)"},
           {ok_scene + "s:run{ t_end = 0.01, integrator = 'esdirk32\\0x' }\n", "without NUL"},
           {ok_scene + "s:run{ t_end = 0.01, frames = { size = {1e300, 720}, png = true } }\n", "16..8192"},
           {ok_scene + "s:run{ t_end = 0.01, frames = { view = { width = 1e-300 }, png = true } }\n", "view.width"},
           {ok_scene + "s:run{ t_end = 0.01, frames = { view = { centre = {0/0, 0} }, png = true } }\n",
            "a finite point"},
           {ok_scene + "s:run{ t_end = 1, sample = 1e-12 }\n", "would write 1e+12 rows"},
           {ok_scene + "s:start{ sample = 1e-12 }:run_to(1)\n", "set allow_large = true"},
           {ok_scene + "local sim = s:start{ progress = false }\nsim:every(1e-12, function() end)\nsim:run_to(0.01)\n",
            "every: a callback every 1e-12 s would be called"},
           {ok_scene + "s:run{ t_end = 0.02, frames = { slowdown = 1e6, png = true } }\n",
            "would render 600000 frames"},
           {with_elements(1000000, ""), "more than the limit of 20000"},
           {with_elements(1000001, "allow_large = true"),
            "1000001 elements are more than beltsim can hold (1000000, allow_large or not)"},
       }) {
    const std::string msg = run_text(c.text);
    EXPECT_NE(msg.find("scene.lua:"), std::string::npos) << c.expect << " -> " << msg;
    EXPECT_NE(msg.find(c.expect), std::string::npos) << c.expect << " -> " << msg;
  }
}

// an error in a μ function names its key, the function and the element it was called for, as a
// torque law's names its law and time (trial 16: Lua's bare "attempt to index a nil value")
TEST(LuaApi, MuFunctionErrorsNameTheKeyAndTheElement) {
  struct Case {
    std::string text, expect;
  };
  const std::string ok_scene = scene_text("");
  for (const Case& c : std::vector<Case>{
           {scene_text("mu = function(site) return site.nope.x end"), "belt.mu (function at "},
           {scene_text("mu = function(site) return 'x' end"), "it returned string 'x', a number expected"},
           {ok_scene + "s:run{ t_end = 0.01, events = { {t = 0.001, mu = function(site) return site.nope.x end} } }\n",
            "run.events[1].mu (function at "},
           {ok_scene + "s:run{ t_end = 0.01, events = { {t = 0.001, mu = 0.3}, {t = 0.002, mu = function(site)\n"
                       "  if site.index == 7 then error('seven') end return 0.3 end} } }\n",
            "run.events[2].mu (function at "},
       }) {
    const std::string msg = run_text(c.text);
    EXPECT_NE(msg.find("scene.lua:"), std::string::npos) << c.expect << " -> " << msg;
    EXPECT_NE(msg.find(c.expect), std::string::npos) << c.expect << " -> " << msg;
    EXPECT_NE(msg.find(") for element "), std::string::npos) << msg;
  }
  const std::string seven = run_text(ok_scene +
                                     "s:run{ t_end = 0.01, events = { {t = 0.002, mu = function(site)\n"
                                     "  if site.index == 7 then error('seven') end return 0.3 end} } }\n");
  EXPECT_NE(seven.find(") for element 7 at s = "), std::string::npos) << seven;
  EXPECT_NE(seven.find("scene.lua:8) for element 7"), std::string::npos) << seven;  // the function's line
  EXPECT_NE(seven.find("scene.lua:9: seven"), std::string::npos) << seven;          // the error's
}

// absurd but finite values: the message names the parameter and its value (gravity = 1e308 used
// to get "a few elements more or fewer usually works"; contact.c1 = 1e308 a route with radii -nan)
TEST(LuaApi, AbsurdButFiniteValuesNameTheParameter) {
  // the test scene with 60 elements and scene_keys on line 7
  auto with = [](const std::string& scene_keys) {
    beltsim::test::TwoPulley p;
    p.elements = 60, p.extra = scene_keys;
    return beltsim::test::two_pulley(p);
  };
  for (const std::string g : {"1e308", "-1e308", "2e4"}) {
    const std::string msg = run_text(with("gravity = " + g + ","));
    EXPECT_NE(msg.find("scene.lua:7: gravity makes the belt's weight over its longest span"), std::string::npos) << msg;
    EXPECT_NE(msg.find("larger than its tension at rest (500 N)"), std::string::npos) << msg;
    EXPECT_NE(msg.find("(got " + std::string(g == "2e4" ? "20000" : g == "1e308" ? "1e+308" : "-1e+308") + " m/s²)"),
              std::string::npos)
        << msg;
    EXPECT_EQ(msg.find("elements more or fewer"), std::string::npos) << msg;
  }
  // the limit is the belt's weight over the 0.29 m span against the pretension: 1.8e4 m/s² here
  EXPECT_EQ(run_text(with("gravity = 1.7e4,")), "");
  const std::string msg = run_text(with("contact = { c1 = 1e308 },"));
  EXPECT_NE(msg.find("scene.lua:7: contact.c1 gives no finite static penetration on 'driver' with contact.c2 = 650000 "
                     "N/m (beyond double precision) (got 1e+308 N/m²)"),
            std::string::npos)
      << msg;
  EXPECT_EQ(msg.find("nan"), std::string::npos) << msg;
}

// error objects that are not strings still name file:line; an empty script is an error
TEST(LuaApi, EveryErrorNamesFileAndLine) {
  EXPECT_NE(run_text("\nerror(42)\n").find("scene.lua:2: 42"), std::string::npos) << run_text("\nerror(42)\n");
  const std::string t = "error(setmetatable({}, { __tostring = function() return 'custom' end }))\n";
  EXPECT_NE(run_text(t).find("scene.lua:1: custom"), std::string::npos) << run_text(t);
  EXPECT_NE(run_text("error({})\n").find("scene.lua:1: (an error object that is a table value)"), std::string::npos)
      << run_text("error({})\n");
  EXPECT_NE(run_text("").find("the script is empty"), std::string::npos) << run_text("");
}

// a video path that cannot be written stops the run before any CSV is written
TEST(LuaApi, BadVideoPathWritesNothing) {
  const fs::path out = temp_dir() / "out";  // run_text's output folder
  fs::remove_all(out);
  const std::string msg =
      run_text(scene_text("") + "s:run{ t_end = 0.01, frames = { video = '/proc/no/such/dir/x.mp4' } }\n");
  EXPECT_NE(msg.find("scene.lua:"), std::string::npos) << msg;
  EXPECT_FALSE(fs::exists(out / "timeseries.csv")) << msg;
  EXPECT_FALSE(fs::exists(out / "parameters.csv")) << msg;
}

TEST(LuaApi, NegativeRadiusNamesFileLineAndValue) {
  expect_error(scene_text("", "centre = {0.29, 0}, radius = -0.1"), "scene.lua:4:",
               {"pulley 'driven'.radius must be > 0", "-0.1 m"});
}

TEST(LuaApi, ZeroInertiaIsRejected) {
  expect_error(scene_text("", "centre = {0.29, 0}, radius = 0.1, inertia = 0"), "scene.lua:4:",
               {"inertia must be > 0", "got 0 kg·m²"});
}

// named on the later pulley's line (its centre), not the call's (line 1)
TEST(LuaApi, OverlappingPulleysAreRejected) {
  expect_error(scene_text("", "centre = {0.15, 0}, radius = 0.1"),
               "scene.lua:4: pulley 'driven'.centre: ", {"overlap", "0.15 m apart"});
}

// a static solve that fails on a contact far stiffer than the belt names the contact's key on its
// line (7), with its value, not belt.elements on the belt's line
TEST(LuaApi, AContactTooStiffForTheStaticStartIsNamed) {
  beltsim::test::expect_warnings({WarningKind::static_retry});
  beltsim::test::TwoPulley p;
  p.extra = "contact = { c2 = 1e14 },";
  expect_error(beltsim::test::two_pulley(p), "scene.lua:7: contact.c2 makes the contact ",
               {"times as stiff as the belt", "(got 1e+14 N/m)"});
}

TEST(LuaApi, NonPositivePretensionIsRejected) {
  expect_error(scene_text("pretension = -5"), "scene.lua:6:", {"belt.pretension must be > 0", "got -5 N"});
}

TEST(LuaApi, TooFewElementsForTheWrap) {
  expect_error(scene_text("elements = 8"), "scene.lua:6:", {"too few elements", "'driver'", "got 8 elements"});
}

TEST(LuaApi, RouteThatCannotClose) {
  // four pulleys at the corners of a square visited diagonally: the spans would cross (a layout of
  // its own, which no other test uses)
  const std::string text =
      "beltsim.scene {\n"
      "  pulleys = {\n"
      "    { name = 'a', centre = {0, 0}, radius = 0.05 },\n"
      "    { name = 'b', centre = {0.5, 0}, radius = 0.05 },\n"
      "    { name = 'c', centre = {0.5, 0.5}, radius = 0.05 },\n"
      "    { name = 'd', centre = {0, 0.5}, radius = 0.05 },\n"
      "  },\n"
      "  belt = { route = {'a', 'c', 'b', 'd'} },\n"
      "}\n";
  expect_error(text, "scene.lua:1:", {"route: "});
}

TEST(LuaApi, MisspeltKeyIsAnErrorWithASuggestion) {
  expect_error(scene_text("pretention = 400"), "scene.lua:6:",
               {"unknown key 'pretention' in belt", "did you mean 'pretension'"});
}

// a string where a number is due shows its text (a --set value in quotes, '25', reads as text), cut
// to 40 characters
TEST(LuaApi, WrongTypeSaysWhatWasExpected) {
  expect_error(scene_text("elements = 'sixty'"), "scene.lua:6:", {"belt.elements: number expected, got string 'sixty'"});
  expect_error(scene_text("EA = '1.5e5'"), "scene.lua:6:", {"belt.EA: number expected, got string '1.5e5'"});
  expect_error(scene_text("EA = string.rep('x', 100)"), "scene.lua:6:",
               {"belt.EA: number expected, got string '" + std::string(40, 'x') + "...'"});
  // cut before a UTF-8 character that would not fit whole: 13 of the three-byte '∞' are 39 bytes
  expect_error(scene_text("EA = string.rep('\u221e', 20)"),
               "scene.lua:6:", {"belt.EA: number expected, got string '" + [] {
                 std::string s;
                 for (int k = 0; k < 13; ++k) s += "\u221e";
                 return s;
               }() + "...'"});
  expect_error(scene_text("elements = {}"), "scene.lua:6:", {"belt.elements: number expected, got table"});
  // a boolean and a float of whole value as Lua writes them
  expect_error(scene_text("EA = true"), "scene.lua:6:", {"belt.EA: number expected, got boolean true"});
  // a point with a coordinate left out says how many it got (it said "got table")
  const std::string one = run_text(scene_text("", "centre = {0.29}, radius = 0.1"));
  EXPECT_NE(one.find("centre: a point {x, y} in metres expected, got a table of 1 value"), std::string::npos) << one;
}

TEST(LuaApi, SyntaxErrorNamesTheLine) {
  expect_error("local a = 1\nlocal b = = 2\n", "scene.lua:2:", {});
}

// Lua's parser reports a script nested past its 200 C levels as a bare "C stack overflow", with no
// file or line (issue 45 §9); the line is the one the parser had reached, whoever loads the file
TEST(LuaApi, NestingTooDeepNamesTheLine) {
  const std::string deep = "local t = " + std::string(300, '{') + std::string(300, '}') + "\n";
  expect_error("local a = 1\n\n" + deep, "scene.lua:3: C stack overflow", {"nests deeper", "200 levels"});
  const std::string other = (temp_dir() / "deep.lua").string();
  std::ofstream(other) << "\n" << deep;
  expect_error("dofile('" + other + "')\n", "deep.lua:2: C stack overflow", {"nests deeper"});
  expect_error("local f, err = loadfile('" + other + "')\nerror(err, 0)\n", "deep.lua:2: C stack overflow", {});
}

TEST(LuaApi, UnknownIntegratorListsTheValidOnes) {
  expect_error(scene_text("") + "s:run{ t_end = 0.001, integrator = 'euler' }\n", "scene.lua:8:",
               {"unknown integrator 'euler'", "esdirk32"});
}

// an event at or after the script's own t_end is refused with its line, as a snapshot time is
TEST(LuaApi, AnEventAfterTheRunsEndNamesItsLine) {
  const std::string text = beltsim::test::two_pulley() +
                           "s:run { t_end = 0.05, progress = false,\n"
                           "  events = { { t = 0.2, mu = 0.2, from = 0, to = 0.3 } } }\n";
  const std::string msg = run_text(text, "late.lua");
  const int line = static_cast<int>(std::count(text.begin(), text.end(), '\n'));  // the events line
  EXPECT_NE(
      msg.find("late.lua:" + std::to_string(line) + ": run.events[1].t: must be before t_end = 0.05 s (got 0.2 s)"),
      std::string::npos)
      << msg;
}

TEST(LuaApi, BadProbesAndSnapshotsAreRejectedWithFileLine) {
  expect_error(scene_text("") + "s:run{ t_end = 0.01, probe = {0, 0} }\n", "scene.lua:8:",
               {"run.probe[2]", "element 0 is probed already", "{0.0, 0.1}"});
  expect_error(scene_text("") + "s:run{ t_end = 0.01, probe = {3, 60} }\n", "scene.lua:8:",
               {"probe", "0..59", "60"});
  expect_error(scene_text("") + "s:run{ t_end = 0.01, snapshots = { time = {0.005} } }\n", "scene.lua:8:",
               {"unknown key 'time'", "times"});
  expect_error(scene_text("") + "s:run{ t_end = 0.01, snapshots = { times = {0.005, 0.002} } }\n", "scene.lua:8:",
               {"run.snapshots.times[2]", "increase", "0.002"});
  expect_error(scene_text("") + "s:run{ t_end = 0.01, snapshots = { times = {0.02} } }\n", "scene.lua:8:",
               {"run.snapshots.times[1]", "t_end", "0.02"});
  expect_error(scene_text("") + "s:run{ t_end = 0.01, snapshots = { every = -1 } }\n", "scene.lua:8:",
               {"run.snapshots.every", "> 0"});
  expect_error(scene_text("") + "s:run{ t_end = 0.01, snapshots = {} }\n", "scene.lua:8:",
               {"run.snapshots", "times", "every"});
}

TEST(LuaApi, BadEventsAreRejectedWithFileLine) {
  expect_error(scene_text("") + "s:run{ t_end = 0.01, events = { { mu = 0.2 } } }\n", "scene.lua:8:",
               {"run.events[1].t", "missing"});
  expect_error(scene_text("") + "s:run{ t_end = 0.01, events = { { t = -0.5, mu = 0.2 } } }\n", "scene.lua:8:",
               {"run.events[1].t: must be > 0 s and finite (got -0.5 s)"});
  expect_error(scene_text("") + "s:run{ t_end = 0.01, events = { { t = 0.005, mu = -1 } } }\n", "scene.lua:8:",
               {"run.events[1].mu", "must be in [0, 10]", "-1"});
  expect_error(scene_text("") + "s:run{ t_end = 0.01, events = { { t = 0.005, mu = 0.2, from = 0.1 } } }\n",
               "scene.lua:8:", {"both from and to"});
  expect_error(scene_text("") + "s:run{ t_end = 0.01, events = { { t = 0.005, mu = 0.2, wet = true } } }\n",
               "scene.lua:8:", {"wet"});
  // a stretch that holds no element would change nothing, logged as a wetting all the same (trial 21)
  expect_error(
      scene_text("") + "s:run{ t_end = 0.01, events = { { t = 0.005, mu = 0.2, from = 0.3001, to = 0.3001 } } }\n",
      "scene.lua:8:", {"run.events[1]: the stretch [0.3001, 0.3001] m holds no element", "change nothing"});
}

}  // namespace lua_api_test
}  // namespace beltsim::script
