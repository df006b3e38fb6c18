// Pulley laws through Lua (docs/lua-api.md, "Laws"), the argument checks of every API function, the
// suggestions for misspelt names, and the script parameters of --set (beltsim.args).
//
// The physics tests take the belt's friction away (μ = 0: the belt's torque on a pulley,
// Σ r·μ·N, is then exactly zero), so that each pulley obeys I·dΩ/dt = M(t, Ω) alone and has a
// closed-form answer.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "lua.h"
#include "run_script.hpp"
#include "script/interpreter.hpp"
#include "script/script_args.hpp"
#include "support/scenes.hpp"
#include "support/scratch.hpp"

namespace beltsim::script {
namespace laws_api_test {

namespace fs = std::filesystem;

fs::path temp_dir() { return beltsim::test::scratch_dir("beltsim_laws_test"); }

// two pulleys on a frictionless belt: each turns under its own law alone (inertia 0.025 kg·m²)
std::string isolated(const std::string& driver, const std::string& driven) {
  beltsim::test::TwoPulley p;
  p.driver = "inertia = 0.025, " + driver, p.driven = "inertia = 0.025, " + driven;
  p.belt = "mu = 0", p.extra = "gravity = 0,";
  return beltsim::test::two_pulley(p);
}

// runs the text (file laws.lua) and returns the error ("" when it ran); `numbers` gets the global
// table `result` when the script made one
std::string run_text(const std::string& text, std::vector<double>* numbers = nullptr, const Safety& safety = {},
                     const fs::path& out = temp_dir() / "out") {
  Interpreter lua(safety);
  Overrides o;
  o.run.out_dir = out.string(), o.give("out");
  lua.set_overrides(o);
  std::ofstream(temp_dir() / "laws.lua") << text;
  try {
    lua.run_file((temp_dir() / "laws.lua").string());
  } catch (const ScriptError& e) {
    return e.what();
  }
  if (numbers) {
    lua_State* L = lua.state();
    lua_getglobal(L, "result");
    for (lua_Integer k = 1; lua_istable(L, -1) && k <= static_cast<lua_Integer>(lua_rawlen(L, -1)); ++k) {
      lua_rawgeti(L, -1, k);
      numbers->push_back(lua_tonumber(L, -1));
      lua_pop(L, 1);
    }
    lua_pop(L, 1);
  }
  return "";
}

// samples Ω of `pulley` at t = 0.05, 0.10, ..., 0.50 s into `result`
std::string sample_omega(const std::string& pulley, const std::string& start = "rtol = 1e-8") {
  return "local sim = s:start{ progress = false, " + start + " }\n"
         "result = {}\n"
         "for k = 1, 10 do sim:run_to(0.05 * k); result[k] = sim:pulley('" + pulley + "').omega end\n"
         "sim:close()\n";
}

// M = 10 − 0.1·Ω as a speed map: Ω(t) = 100·(1 − exp(−t/τ)) with τ = I/b = 0.025/0.1 = 0.25 s.
// The integrator's global error at rtol 1e-8 is ≲ 1e2·rtol·|Ω| = 1e-4 rad/s (measured: 3e-7);
// asked: 1e-4 rad/s on Ω and 1e-5 relative on the time constant fitted from two samples.
void expect_spin_up(const std::vector<double>& w) {
  ASSERT_EQ(w.size(), 10u);
  for (int k = 1; k <= 10; ++k) {
    const double t = 0.05 * k;
    EXPECT_NEAR(w[k - 1], 100 * (1 - std::exp(-t / 0.25)), 1e-4) << "t = " << t;
  }
  const double tau = (0.5 - 0.1) / std::log((100 - w[1]) / (100 - w[9]));
  EXPECT_NEAR(tau, 0.25, 0.25 * 1e-5);
}

TEST(LawsApi, SpeedMapSpinsUpWithTimeConstantIOverB) {
  std::vector<double> w;
  // held constant outside its ends: the map's two points span the whole run
  ASSERT_EQ(run_text(isolated("speed = 0", "torque = { per_speed_table = {{0, 10}, {50, 5}, {200, -10}} }") +
                         sample_omega("driven"),
                     &w),
            "");
  expect_spin_up(w);
}

TEST(LawsApi, LuaFunctionLawSpinsUpTheSame) {
  std::vector<double> w;
  ASSERT_EQ(run_text(isolated("speed = 0", "torque = function(t, omega) return 10 - 0.1 * omega end") +
                         sample_omega("driven"),
                     &w),
            "");
  expect_spin_up(w);
}

// a crankshaft's pulsation as a prescribed speed: Ω(t) = 80 + 3·sin(2·80·t) + sin(4·80·t + 0.5),
// and the torque that holds it, I·Ω'(t) (the belt adds none at μ = 0); both are evaluated, not
// integrated: rounding only (asked 1e-12 rad/s, 1e-10 N·m)
TEST(LawsApi, HarmonicsSpeedMatchesTheFormula) {
  std::vector<double> r;
  ASSERT_EQ(run_text(isolated("speed = { constant = 80, mean_speed = 80, harmonics = {{2, 3, 0}, {4, 1, 0.5}} }",
                              "torque = 0") +
                         "local sim = s:start{ progress = false }\n"
                         "result = {}\n"
                         "for k = 1, 10 do\n"
                         "  sim:run_to(0.0037 * k)\n"
                         "  local p = sim:pulley('driver')\n"
                         "  result[2 * k - 1], result[2 * k] = p.omega, p.torque\n"
                         "end\n",
                     &r),
            "");
  ASSERT_EQ(r.size(), 20u);
  for (int k = 1; k <= 10; ++k) {
    const double t = 0.0037 * k;
    EXPECT_NEAR(r[2 * k - 2], 80 + 3 * std::sin(160 * t) + std::sin(320 * t + 0.5), 1e-12) << t;
    const double accel = 3 * 160 * std::cos(160 * t) + 320 * std::cos(320 * t + 0.5);
    EXPECT_NEAR(r[2 * k - 1], 0.025 * accel, 1e-10) << t;
  }
}

// a torque step at t0 = 0.0123 s: Ω = 5·(t − t0)/I after it. Piecewise linear, which every method
// integrates exactly: only rounding is left (asked 1e-9 relative). A step ending on the jump that
// saw the value after it, or a restart there that saw the value before it, is off by ~h·5/I.
TEST(LawsApi, TorqueStepIsLandedOn) {
  // (rkf45 is left out: explicit, it takes 5e5 steps on the belt. cvode is in: after the last
  // landing it used to estimate an infinite first step and stop with CV_REPTD_RHSFUNC_ERR)
  for (const char* integrator : {"esdirk32", "trbdf2", "ros34pw2", "cvode"}) {
    std::vector<double> w;
    ASSERT_EQ(run_text(isolated("speed = 0", "torque = beltsim.step(0.0123, 0, 5)") +
                           sample_omega("driven", std::string("integrator = '") + integrator + "'"),  // rtol 1e-4
                       &w),
              "");
    ASSERT_EQ(w.size(), 10u);
    for (int k = 1; k <= 10; ++k) {
      const double expect = 5 * (0.05 * k - 0.0123) / 0.025;
      EXPECT_NEAR(w[k - 1], expect, 1e-9 * expect) << integrator << " t = " << 0.05 * k;
    }
  }
}

// a speed step: the driver turns at 10 rad/s from t = 0.01 s on, so its angle (integrated from
// the prescribed speed) is 10·(t − 0.01) after it, to the integrator's tolerance (rtol 1e-8 of
// 0.4 rad, asked 1e-9 rad); a jump taken late or smeared over a step is off by ~h·10 rad
TEST(LawsApi, SpeedStepTurnsThePulleyFromItsTime) {
  std::vector<double> r;
  ASSERT_EQ(run_text(isolated("speed = beltsim.step(0.01, 0, 10)", "torque = 0") +
                         "local sim = s:start{ progress = false, rtol = 1e-8 }\n"
                         "sim:run_to(0.05)\n"
                         "result = { sim:pulley('driver').omega, sim:pulley('driver').angle }\n",
                     &r),
            "");
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r[0], 10.0);
  EXPECT_NEAR(r[1], 10 * (0.05 - 0.01), 1e-9);
}

// the helpers' laws against their formulas (prescribed speeds: evaluated, rounding only)
TEST(LawsApi, RampStepSineAndSums) {
  std::vector<double> r;
  ASSERT_EQ(run_text(isolated("speed = { beltsim.ramp{ t0 = 0.01, t1 = 0.03, from = 2, to = 6, shape = 'cosine' },\n"
                              "  beltsim.sine{ mean = 1, amplitude = 0.5, frequency = 40, phase = 0.2 },\n"
                              "  beltsim.step(0.025, 0, -3), beltsim.ramp(0.04, 8),\n"
                              "  beltsim.step{ t = 0.035, to = 1.5 }, beltsim.step{ t = 0.02, from = 0.25, to = 0 } }",
                              "torque = 0") +
                         "local sim = s:start{ progress = false }\n"
                         "result = {}\n"
                         "for k = 1, 10 do sim:run_to(0.0047 * k); result[k] = sim:pulley('driver').omega end\n",
                     &r),
            "");
  ASSERT_EQ(r.size(), 10u);
  for (int k = 1; k <= 10; ++k) {
    const double t = 0.0047 * k;
    const double s = std::clamp((t - 0.01) / 0.02, 0.0, 1.0);
    const double expect = 2 + 4 * (1 - std::cos(M_PI * s)) / 2 + 1 + 0.5 * std::sin(2 * M_PI * 40 * t + 0.2) +
                          (t > 0.025 ? -3 : 0) + 8 * std::min(t / 0.04, 1.0) +
                          // the table form of beltsim.step (trial 12: refused, "expected 3 arguments")
                          (t > 0.035 ? 1.5 : 0) + (t < 0.02 ? 0.25 : 0);
    EXPECT_NEAR(r[k - 1], expect, 1e-12) << t;
  }
}

// The engine runs no Lua while integrating unless a law is a Lua function: the Lua calls made
// during a run (a call hook set by the script, --trusted for the debug library) do not grow with
// the run's length, and do with a Lua law (one call per evaluation at least).
long lua_calls_during_run(const std::string& driven, double t_end) {
  Safety trusted;
  trusted.trusted = true;
  std::vector<double> r;
  const std::string err = run_text(isolated("torque = beltsim.ramp{ t1 = 0.3, to = -70, shape = 'cosine' }", driven) +
                                       "local n = 0\n"
                                       "debug.sethook(function() n = n + 1 end, 'c')\n"
                                       "s:run{ t_end = " + std::to_string(t_end) + ", progress = false }\n"
                                       "debug.sethook()\n"
                                       "result = { n }\n",
                                   &r, trusted);
  EXPECT_EQ(err, "");
  return r.empty() ? -1 : static_cast<long>(r[0]);
}

TEST(LawsApi, NoLuaWhileIntegratingWithoutALuaLaw) {
  const std::string builtin = "torque = { per_speed_table = {{0, 0}, {100, -5}}, beltsim.sine{ amplitude = 1, frequency = 30 } }";
  const long short_run = lua_calls_during_run(builtin, 0.01), long_run = lua_calls_during_run(builtin, 0.05);
  EXPECT_EQ(short_run, long_run);
  EXPECT_LT(long_run, 5);  // the calls of s:run and debug.sethook themselves
  // the same count sees a Lua law: a call per evaluation, growing with the run
  const std::string lua_law = "torque = function(t, omega) return -0.05 * omega end";
  const long lua_short = lua_calls_during_run(lua_law, 0.01), lua_long = lua_calls_during_run(lua_law, 0.05);
  EXPECT_GT(lua_short, 10 * long_run);
  EXPECT_GT(lua_long, 2 * lua_short);
}

// an error inside a Lua law stops the run with the law's file:line and the run's; the samples
// up to then are whole rows of a closed file
TEST(LawsApi, ErrorInALuaLawNamesFileLineAndClosesTheOutputs) {
  const fs::path out = temp_dir() / "law_error";
  fs::remove_all(out);
  const std::string msg = run_text(isolated("speed = 0", "torque = function(t, omega)\n"
                                                         "  if t > 0.02 then error('no torque beyond 0.02 s') end\n"
                                                         "  return 1\n"
                                                         "end") +
                                       "s:run{ t_end = 0.1, progress = false }\n",
                                   nullptr, {}, out);
  EXPECT_NE(msg.find("laws.lua:12:"), std::string::npos) << msg;  // the run
  EXPECT_NE(msg.find("laws.lua:5: no torque beyond 0.02 s"), std::string::npos) << msg;  // the law's own line
  EXPECT_NE(msg.find("laws.lua:4) at t = "), std::string::npos) << msg;
  // the samples end whole, at or before the time of the failing evaluation
  const size_t at = msg.find(" at t = ");
  ASSERT_NE(at, std::string::npos) << msg;
  const double t_fail = std::stod(msg.substr(at + 8));
  std::ifstream csv(out / "timeseries.csv");
  const std::string text((std::istreambuf_iterator<char>(csv)), {});
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n');
  const double t_last = std::stod(text.substr(text.rfind('\n', text.size() - 2) + 1));
  EXPECT_GT(t_fail, 0.02);
  EXPECT_GT(t_last, 0.005);
  EXPECT_LE(t_last, t_fail);
  for (const auto& [law, expect] : std::vector<std::pair<std::string, std::string>>{
           {"function(t, omega) return 'x' end", "it returned string, a number expected"},
           {"function(t, omega) return 1 / 0 end", "a finite number expected"},
           {"function(t, omega) error({}) end", "an error object that is a table value"},
       }) {
    // (raised while beltsim.scene seeks the static state: the line of the driven pulley's torque,
    // 4; or in the run, line 9)
    const std::string m = run_text(isolated("speed = 0", "torque = " + law) + "s:run{ t_end = 0.01, progress = false }\n");
    EXPECT_TRUE(m.find("laws.lua:4:") != std::string::npos || m.find("laws.lua:9:") != std::string::npos) << m;
    EXPECT_NE(m.find(expect), std::string::npos) << law << " -> " << m;
  }
}

// every API function rejects a missing, extra or mistyped argument with file:line, and a misspelt
// name gets a suggestion when one valid name is close
TEST(LawsApi, BadArgumentsAndMisspeltNames) {
  struct Case {
    std::string code, expect;
  };
  const std::string pre = isolated("speed = 0", "torque = 0");  // 8 lines: the case is line 9
  for (const Case& c : std::vector<Case>{
           {"beltsim.ramp(0.05, 0.6, 12)", "beltsim.ramp(t1, to): expected 2 arguments, got 3"},
           {"beltsim.ramp(0.05)", "beltsim.ramp(t1, to): expected 2 arguments, got 1"},
           {"beltsim.ramp('0.05', 1)", "argument 1 (t1): number expected, got string"},
           {"beltsim.ramp{ t1 = 0.1, to = 1, shape = 'cosin' }", "did you mean 'cosine'"},
           {"beltsim.ramp({ t1 = 0.1, to = 1 }, 2)", "expected 1 argument, got 2"},
           {"beltsim.ramp{ t0 = 0.2, t1 = 0.1, to = 1 }", "t1 must be > t0"},
           {"beltsim.ramp{ t1 = 0.1 }", "beltsim.ramp.to is required"},
           {"beltsim.step(0.1, 1)", "beltsim.step(t, from, to): expected 3 arguments, got 2"},
           {"beltsim.step(0.1, 1, 2, 3)", "expected 3 arguments, got 4"},
           {"beltsim.step(0.1, 1, {})", "argument 3 (to): number expected, got table"},
           {"beltsim.step{ t = 0.1 }", "beltsim.step.to is required"},
           {"beltsim.step{ t = 0.1, form = 1, to = 2 }", "did you mean 'from'"},
           {"beltsim.step({ t = 0.1, to = 1 }, 2)", "expected 1 argument, got 2"},
           {"beltsim.sine{ amplitude = 1 }", "frequency is required"},
           {"beltsim.sine{ amplitude = 1, frequncy = 2 }", "did you mean 'frequency'"},
           {"beltsim.sine(1, 2)", "expected 1 argument, got 2"},
           {"beltsim.rpm('60')", "argument 1 (n): number expected, got string"},
           {"beltsim.rpm(60, 1)", "expected 1 argument, got 2"},
           {"beltsim.integrators(1)", "beltsim.integrators(): expected 0 arguments, got 1"},
           {"beltsim.scene()", "beltsim.scene({pulleys, belt, ...}): expected 1 argument, got 0"},
           {"beltsim.scene({}, 1)", "expected 1 argument, got 2"},
           {"beltsim.resume()",
            "beltsim.resume(path, [{progress, rewind, max_wall, out}]): expected 1 to 2 arguments, got 0"},
           {"help(1)", "argument 1 (name): string expected, got number"},
           {"s:info(1)", "scene:info(): expected 0 arguments, got 1"},
           {"s:element_near({0, 0}, 1)", "expected 1 argument, got 2"},
           {"s:run(5)", "argument 1 ({t_end, integrator, ...}): table expected, got number"},
           {"s:start({}, 1)", "scene:start([{integrator, rtol, ...}]): expected 0 to 1 arguments, got 2"},
           {"s.run{}", "scene:run: call it as scene:run(...) on a scene"},
           {"beltsim.rmp(60)", "beltsim has no field or method 'rmp' (did you mean 'ramp' or 'rpm'?)"},
           {"s:rnu{}", "scene has no field or method 'rnu' (did you mean 'run'?)"},
           {"local sim = s:start{ progress = false }; sim:advnce(0.1)", "(did you mean 'advance'?)"},
           {"local sim = s:start{ progress = false }; sim:set_torque('driven', 1, 2)",
            "sim:set_torque(name, law): expected 2 arguments, got 3"},
           {"local sim = s:start{ progress = false }; sim:set_speed('driver', { per_speed = 1 })",
            "a prescribed speed cannot depend on the speed"},
           {"s:run{ t_ned = 1 }", "did you mean 't_end'"},
       }) {
    const std::string msg = run_text(pre + c.code + "\n");
    EXPECT_NE(msg.find("laws.lua:9: "), std::string::npos) << c.code << " -> " << msg;
    EXPECT_NE(msg.find(c.expect), std::string::npos) << c.code << " -> " << msg;
  }
}

// laws in the scene: bad terms name the pulley, the key and the value
TEST(LawsApi, BadLawsNameTheKey) {
  struct Case {
    std::string driven, expect;
  };
  for (const Case& c : std::vector<Case>{
           {"torque = { per_sped = 1 }",
            "unknown key 'per_sped' in pulley 'driven'.torque (did you mean 'per_speed'?)"},
           {"torque = { harmonics = {{2, 1, 0}} }", "mean_speed [rad/s] is required"},
           {"torque = { mean_speed = 80 }", "only for harmonics"},
           {"torque = { per_speed_table = {{0, 1}, {0, 2}} }",
            "per_speed_table entry 2 must be larger than the entry before it (got 0 rad/s)"},
           {"torque = { per_speed_table = {{0, 1}, {1}} }",
            "per_speed_table entry 2 ({omega, value}): two numbers expected"},
           {"torque = { table = {} }", "at least one {t, value} pair expected"},
           {"torque = 'x'", "a number, a law table or function(t, omega) expected, got string"},
           {"torque = { 1, { sine = { amplitude = 1, frequency = -2 } } }", "sine.frequency must be >= 0"},
           {"speed = { per_speed_table = {{0, 1}, {1, 2}} }", "a prescribed speed cannot depend on the speed"},
           {"torque = { [5] = 1 }", "named terms and a list of laws without holes expected"},
           // a helper's value is checked where it is given, in that key's unit (a speed's NaN was
           // "beltsim ramp.to ... (got nan N·m)"); its own keys name it with a dot
           {"speed = beltsim.ramp{ t1 = 0.05, to = 0/0 }",
            "pulley 'driven'.speed ramp.to must be a finite number (got nan rad/s)"},
           {"speed = beltsim.sine{ amplitude = 1/0, frequency = 2 }",
            "pulley 'driven'.speed sine.amplitude must be a finite number (got inf rad/s)"},
           {"torque = beltsim.step(0.1, 0, 0/0)",
            "pulley 'driven'.torque step.to must be a finite number (got nan N·m)"},
           {"torque = beltsim.sine{ amplitude = 1, frequency = -2 }",
            "beltsim.sine.frequency must be >= 0 (got -2 Hz)"},
           {"torque = beltsim.ramp{ t0 = 0/0, t1 = 1, to = 1 }", "beltsim.ramp: t1 must be > t0"},
           {"torque = beltsim.step(1/0, 0, 1)", "beltsim.step.t must be a finite number (got inf s)"},
           // an unknown key of a named pulley names it as the others do (it was "pulley 2")
           {"torque = 1, inertia_kg = 1", "unknown key 'inertia_kg' in pulley 'driven'; valid keys: name,"},
       }) {
    const std::string msg = run_text(isolated("speed = 0", c.driven));
    EXPECT_NE(msg.find("laws.lua:4: "), std::string::npos) << c.driven << " -> " << msg;  // the driven pulley's line
    EXPECT_NE(msg.find(c.expect), std::string::npos) << c.driven << " -> " << msg;
  }
  // a misspelt scene key: one close key, or both that hold the word
  const std::string msg = run_text(
      "beltsim.scene{ pulleys = {}, belt = { damping = 1 } }\n");
  EXPECT_NE(msg.find("(did you mean 'axial_damping' or 'bending_damping'?)"), std::string::npos) << msg;
  EXPECT_NE(run_text("beltsim.scene{ pulleys = {}, belt = { elemnts = 1 } }\n").find("(did you mean 'elements'?)"),
            std::string::npos);
}

// a law changed on a live simulation is written to events.csv as Lua that reads back; a Lua law
// cannot go into a checkpoint
TEST(LawsApi, LiveLawChangesAndCheckpoints) {
  const fs::path out = temp_dir() / "live_laws";
  fs::remove_all(out);
  EXPECT_EQ(run_text(isolated("speed = 0", "torque = 0") +
                         "local sim = s:start{ progress = false }\n"
                         "sim:set_torque('driven', { beltsim.step(0.02, 0, 2), mean_speed = 50, harmonics = {{2, 1}} })\n"
                         "sim:run_to(0.01)\n",
                     nullptr, {}, out),
            "");
  std::ifstream ev(out / "events.csv");
  const std::string events((std::istreambuf_iterator<char>(ev)), {});
  EXPECT_NE(events.find("{ step = { t = 0.02, from = 0, to = 2 } }"), std::string::npos) << events;
  EXPECT_NE(events.find("{ mean_speed = 50, harmonics = { {2, 1, 0} } }"), std::string::npos) << events;
  // the refusal names the pulley and the law (a user's failed after the run with the function's
  // file:line alone); said where the state is saved, not at every start: a simulation with a Lua
  // law that is never saved runs without a word (each start warned, saved or not)
  const std::string text = isolated("speed = 0", "torque = function(t, w) return 0 end") +
                           "local sim = s:start{ progress = false }\n"
                           "sim:save('x.ckpt')\n";
  const long line = 1 + std::count(text.begin(), text.begin() + static_cast<long>(text.find("function(t, w)")), '\n');
  const std::string where = "(function at " + (temp_dir() / "laws.lua").string() + ":" + std::to_string(line) + ")";
  testing::internal::CaptureStderr();
  // (a folder of its own: the program's other tests leave their outputs in the shared one, which
  // a run warns of)
  const std::string msg = run_text(text, nullptr, {}, temp_dir() / "live_laws_save");
  std::string err = testing::internal::GetCapturedStderr();
  // (the frictionless scene's own warning aside: belt.mu = 0 transmits nothing)
  if (const size_t mu0 = err.find("warning: belt.mu = 0 on every element"); mu0 != std::string::npos)
    err.erase(mu0, err.find('\n', mu0) - mu0);
  EXPECT_EQ(err.find("warning"), std::string::npos) << err;
  EXPECT_NE(msg.find("laws.lua:10: sim:save: pulley 'driven'.torque " + where +
                     " is Lua code, which a checkpoint cannot hold: give the law as a table (constant, per_speed, "
                     "ramps, sines, ...) to save this simulation"),
            std::string::npos)
      << msg;
  // a law set to Lua code on the way, and set back to a table: the scene's own is still Lua code
  EXPECT_EQ(run_text(isolated("speed = 0", "torque = 0") + "local sim = s:start{ progress = false }\n"
                                                           "sim:set_torque('driven', function(t, w) return 0 end)\n"
                                                           "sim:run_to(0.001)\n"
                                                           "sim:set_torque('driven', 0)\n"
                                                           "sim:save('y.ckpt')\n"),
            "");
  EXPECT_NE(run_text(text.substr(0, text.find("local sim")) + "local sim = s:start{ progress = false }\n"
                                                              "sim:set_torque('driven', 0)\n"
                                                              "sim:save('z.ckpt')\n")
                .find("sim:save: the scene's pulley 'driven'.torque " + where + " is Lua code"),
            std::string::npos);
}

// --set KEY=VALUE: the values' types, and the errors of values that start like numbers
TEST(ScriptArgs, ValuesAreTypedAndChecked) {
  const std::vector<ScriptArg> a = parse_sets({"elements=120", "mu=0.3", "wet=true", "integrator=esdirk32",
                                               "n=-3", "e=1e-3", "code=\"0x10\"", "empty="});
  EXPECT_EQ(std::get<long long>(a[0].value), 120);
  EXPECT_EQ(std::get<double>(a[1].value), 0.3);
  EXPECT_EQ(std::get<bool>(a[2].value), true);
  EXPECT_EQ(std::get<std::string>(a[3].value), "esdirk32");
  EXPECT_EQ(std::get<long long>(a[4].value), -3);
  EXPECT_EQ(std::get<double>(a[5].value), 1e-3);
  EXPECT_EQ(std::get<std::string>(a[6].value), "0x10");
  EXPECT_EQ(std::get<std::string>(a[7].value), "");
  for (const auto& [kv, expect] : std::vector<std::pair<std::string, std::string>>{
           {"size=0x10", "must be a finite decimal number"},
           {"mu=1e", "must be a finite decimal number"},
           {"mu=.", "must be a finite decimal number"},
           {"t=2s", "must be a finite decimal number"},
           {"x=-inf", "must be a finite decimal number"},
           {"elements", "KEY=VALUE expected"},
           {"=3", "must be a Lua name"},
           {"1x=3", "must be a Lua name"},
           {"a.b=3", "must be a Lua name"},
       }) {
    try {
      parse_set(kv);
      ADD_FAILURE() << kv << " was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("--set " + kv + ": "), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(expect), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(parse_sets({"mu=0.3", "mu=0.4"}), std::invalid_argument);
}

TEST(ScriptArgs, ScriptReadsThemAndUnreadOnesAreNamed) {
  const std::vector<ScriptArg> sets = parse_sets({"elements=48", "mu=0.3", "wet=false", "elemnts=120"});
  Interpreter lua;
  Overrides o;
  o.set = sets;
  lua.set_overrides(o);
  const std::string err = test::run_script(
      lua, temp_dir() / "args.lua",
      "local a = beltsim.args\n"
      "assert(math.type(a.elements) == 'integer' and a.elements == 48)\n"
      "assert(math.type(a.mu) == 'float' and a.mu == 0.3)\n"
      "assert(a.wet == false and a.missing == nil)\n"
      "assert(not pcall(function() a.mu = 1 end), 'read-only')\n");
  EXPECT_EQ(err, "");
  const std::vector<std::string> unread = lua.unread_args("args.lua");
  ASSERT_EQ(unread.size(), 1u);
  EXPECT_EQ(unread[0],
            "--set elemnts=120 was never read by args.lua (did you mean 'elements'?); keys it read: elements, mu, wet, "
            "missing");
  // pairs() reads every key
  EXPECT_EQ(test::run_script(lua, temp_dir() / "args2.lua", "for k, v in pairs(beltsim.args) do end\n"), "");
  EXPECT_TRUE(lua.unread_args("args2.lua").empty());
}

}  // namespace laws_api_test
}  // namespace beltsim::script
