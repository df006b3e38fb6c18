// The live simulation from Lua: scene:start, run_to/advance, reading, changes, every and when,
// argument checks. Each script asserts with error(), so a wrong value fails with its line.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "script/interpreter.hpp"
#include "run_script.hpp"
#include "support/scenes.hpp"
#include "support/scratch.hpp"

namespace beltsim::script {
namespace live_api_test {

namespace fs = std::filesystem;

fs::path temp_dir() { return beltsim::test::scratch_dir("beltsim_live_api_test"); }

// the test scene (tests/support/two_pulley.lua: 40 elements, quick); `driver`: the driver's drive
// ("": the file's)
std::string scene(const std::string& driver = "") {
  beltsim::test::TwoPulley p;
  p.driver = driver;
  return beltsim::test::two_pulley(p) +
         "local sim = s:start{ out = '" + (temp_dir() / "out").string() + "', progress = false }\n";
}

std::string run_text(const std::string& text) {
  Interpreter lua;
  return test::run_script(lua, temp_dir() / "live.lua", text);
}

TEST(LiveApi, ReadsTheStateInSIUnits) {
  EXPECT_EQ(run_text(scene() +
                     "assert(sim.t == 0)\n"
                     "local r = sim:advance(0.01)\n"
                     "assert(r.t == 0.01 and sim.t == 0.01 and r.steps > 0 and r.wall >= 0, 'advance')\n"
                     "local p = sim:pulley('driver')\n"
                     "assert(p.omega < 0 and p.angle < 0, 'the driver turns clockwise')\n"
                     "assert(math.abs(p.torque - (-70 * 0.01 / 0.3)) < 1e-9, 'applied torque of the ramp')\n"
                     "local e = sim:element(0)\n"
                     "assert(e.state == 'stick' or e.state == 'slip' or e.state == 'free', e.state)\n"
                     "assert(e.tension > 300 and e.tension < 700, 'tension near the pretension: ' .. e.tension)\n"
                     "assert(e.mu == 1)\n"
                     "local T = sim:span('driver', 'driven')\n"
                     "assert(T > 200 and T < 800, 'span tension ' .. T)\n"
                     "-- two pulleys have two spans: the one run from driver to driven, and back\n"
                     "local U = sim:span('driven', 'driver')\n"
                     "assert(math.abs(T - U) > 1, 'the two spans: ' .. T .. ' and ' .. U)\n"
                     "assert(sim:energy().kinetic > 0)\n"
                     "assert(sim:stats().steps == r.steps)\n"),
            "");
}

// a Lua law that fails while the state is read (a prescribed speed enters sim:element,
// sim:elements, sim:energy, sim:pulley and the report of sim:wet) stops with the law's message, as
// it does in a run (it escaped as a C++ exception: pcall gave false, 0)
TEST(LiveApi, ALawFailingWhileTheStateIsReadSaysSo) {
  EXPECT_EQ(run_text("broken = false\n" +
                     scene("speed = function(t) if broken then error('law broke') end return -10 end") +
                     "sim:advance(0.001)\n"
                     "broken = true\n"
                     "for _, read in ipairs({ function() return sim:element(0) end,\n"
                     "                        function() return sim:elements{ pulley = 'driver' } end,\n"
                     "                        function() return sim:energy() end,\n"
                     "                        function() return sim:pulley('driver') end,\n"
                     "                        function() return sim:wet{ from = 0, to = 0.1, mu = 0.5 } end }) do\n"
                     "  local ok, err = pcall(read)\n"
                     "  assert(not ok and type(err) == 'string' and err:find('law broke'), _ .. ': ' .. tostring(err))\n"
                     "end\n"),
            "");
}

// sim:stats().kink_restarts counts CVODE's restarts at located kinks (the dry drive's first
// 0.05 s has dozens: its wraps settle and slip begins) and is 0 for a one-step method
TEST(LiveApi, StatsCountCvodesRestartsAtKinks) {
  // CVODE's Newton iteration fails to converge at some kinks before it restarts there
  beltsim::test::expect_warnings({WarningKind::cvode_convergence});
  for (const std::string integ : {"cvode", "esdirk32"}) {
    std::string text = scene();
    const std::string from = "progress = false }", to = "progress = false, integrator = '" + integ + "' }";
    text.replace(text.find(from), from.size(), to);
    EXPECT_EQ(run_text(text + "sim:advance(0.05)\n"
                              "local k = sim:stats().kink_restarts\n"
                              "assert(sim:stats().integrator == '" + integ + "', sim:stats().integrator)\n" +
                              (integ == "cvode" ? "assert(k > 0, 'no restart at a kink')\n" : "assert(k == 0, k)\n")),
              "")
        << integ;
  }
}

// a PI controller on the driver's torque holds the driven pulley within 1 % of its set speed
TEST(LiveApi, EveryRunsAController) {
  // the controller's torque jumps every 2 ms: failed implicit steps from 0.026 s
  beltsim::test::expect_warnings({WarningKind::failed_step});
  EXPECT_EQ(run_text(scene("torque = 0") +
                     "local target, integral, dt = -30, 0, 0.002\n"
                     "sim:every(dt, function(sim)\n"
                     "  local e = target - sim:pulley('driven').omega\n"
                     "  integral = integral + e * dt\n"
                     "  sim:set_torque('driver', 3 * e + 60 * integral)\n"
                     "end)\n"
                     "local worst = 0\n"
                     "sim:every(0.01, function(sim)\n"
                     "  if sim.t >= 0.6 then\n"
                     "    worst = math.max(worst, math.abs(sim:pulley('driven').omega / target - 1))\n"
                     "  end\n"
                     "end)\n"
                     "sim:run_to(0.8)\n"
                     "if worst > 0.01 then error('the driven speed strays ' .. worst * 100 .. ' % from the set speed') end\n"),
            "");
}

// when() locates a crossing known in closed form: a driver at -10 rad/s has turned -0.5 rad at
// t = 0.05 s; its action runs there and may change the drive
TEST(LiveApi, WhenFindsTheCrossing) {
  EXPECT_EQ(run_text(scene("speed = -10") +
                     "local at\n"
                     "sim:when(function(sim) return sim:pulley('driver').angle <= -0.5 end,\n"
                     "         function(sim) at = sim.t; sim:set_speed('driver', -5) end)\n"
                     "sim:run_to(0.08)\n"
                     "assert(at, 'the condition never fired')\n"
                     "if math.abs(at - 0.05) > 1e-6 then error(string.format('crossing at %.9f s', at)) end\n"
                     "assert(sim:pulley('driver').omega == -5)\n"),
            "");
}

// A tensioner arm from Lua: sim:pulley reads its angle and rate (none on a pulley without one),
// sim:energy its spring's energy, sim:set_arm moves it, and a checkpoint carries it (the resumed run gives the same bits).
TEST(LiveApi, TensionerArmReadChangedAndCheckpointed) {
  const std::string out = (temp_dir() / "arm").string();
  EXPECT_EQ(
      run_text(
          beltsim::test::automotive_text() +
          "local s = beltsim.scene(automotive { crank = beltsim.ramp(0.3, -70.0), arm = { damping = 0.05 },\n"
          "  pump = { per_speed = -0.5 }, belt = { pretension = 280 } })\n"
          "local sim = s:start{ out = '" +
          out +
          "', progress = false }\n"
          "local p = sim:pulley('tensioner')\n"
          "assert(math.abs(p.arm_angle - math.atan(-0.12 + 0.14, 0.015 - 0.075)) < 1e-15, 'installed angle')\n"
          "assert(p.arm_rate == 0, 'at rest')\n"
          "assert(sim:pulley('pump').arm_angle == nil, 'no arm')\n"
          "sim:advance(0.002)\n"
          "-- sim:energy's parts add up to the mechanical energy, the arm's spring among them\n"
          "local e = sim:energy()\n"
          "local parts = e.kinetic + e.sde + e.bending + e.contact + e.gravity + e.arm + e.coupling\n"
          "assert(math.abs(parts - e.mechanical) <= 1e-12 * math.abs(e.mechanical), parts .. ' ' .. e.mechanical)\n"
          "assert(e.arm > 0 and e.coupling == 0, 'arm ' .. e.arm .. ', coupling ' .. e.coupling)\n"
          "local a = sim:pulley('tensioner').arm_angle + 1e-4\n"
          "sim:set_arm('tensioner', { angle = a, rate = 0.5 })\n"
          "p = sim:pulley('tensioner')\n"
          "assert(p.arm_angle == a and p.arm_rate == 0.5, 'set_arm')\n"
          "local ok, err = pcall(sim.set_arm, sim, 'pump', { angle = 0 })\n"
          "assert(not ok and err:find(\"pulley 'pump' has no tensioner arm\"), err)\n"
          "local path = sim:save('" +
          out +
          "/arm.chk')\n"
          "sim:advance(0.002)\n"
          "local later = sim:pulley('tensioner')\n"
          "assert(later.arm_angle ~= a, 'the arm moves')\n"
          "sim:close()\n"
          "local r = beltsim.resume(path, { rewind = true })  -- (the rows after it)\n"
          "r:advance(0.002)\n"
          "local again = r:pulley('tensioner')\n"
          "assert(again.arm_angle == later.arm_angle and again.arm_rate == later.arm_rate, 'resumed bits')\n"
          "r:close()\n"),
      "");
}

// A spray zone from Lua: the elements inside it at the start take its μ, sim:spray reads it and
// switches it off (the elements it held start drying; events.csv has both), bad zones and calls
// are refused naming the key.
TEST(LiveApi, SprayZoneReadSwitchedAndRefused) {
  const std::string out = (temp_dir() / "spray").string();
  beltsim::test::TwoPulley p;
  p.extra = "spray = { { centre = {0.145, 0.1}, radius = 0.03, mu = 0.2, drying_length = 1 } },";
  EXPECT_EQ(
      run_text(
          beltsim::test::two_pulley(p) + "local sim = s:start{ out = '" + out +
          "', progress = false }\n"
          "local z = sim:spray(1)\n"
          "assert(z.on and z.enabled and z.inside > 0 and z.drying == 0, 'on from the start')\n"
          "assert(math.type(z.inside) == 'integer' and math.type(z.drying) == 'integer', 'counts')\n"
          "local inside = 0\n"
          "for i = 0, 39 do\n"
          "  local e = sim:element(i)\n"
          "  local r = math.sqrt((e.x - 0.145)^2 + (e.y - 0.1)^2)\n"
          "  if r < 0.03 then inside = inside + 1; assert(e.mu == 0.2, 'wet ' .. i) else assert(e.mu == 1, 'dry ' .. "
          "i) end\n"
          "end\n"
          "assert(inside == z.inside, inside .. ' inside, the zone says ' .. z.inside)\n"
          "sim:advance(0.001)\n"
          "sim:spray(1, false)\n"
          "z = sim:spray(1)\n"
          "assert(not z.on and not z.enabled and z.inside == 0 and z.drying >= inside, 'off')\n"
          "local ok, err = pcall(sim.spray, sim, 2)\n"
          "assert(not ok and err:find('no zone 2 %(the scene has 1 spray zones'), err)\n"
          "ok, err = pcall(sim.spray, sim, 1, nil)  -- (it switched the zone off)\n"
          "assert(not ok and err:find('enabled must be true or false, got nil %(leave it out to read zone 1%)'), err)\n"
          "sim:close()\n"
          "local f = io.open('" +
          out +
          "/events.csv'):read('a')\n"
          "assert(f:find('0,spray1,on') and f:find('spray1,disabled') and f:find('spray1,off'), f)\n"),
      "");
  for (const auto& [zone, expect] : std::vector<std::pair<std::string, std::string>>{
           {"{ centre = {0, 0}, mu = 0.2, drying_length = 1 }", "spray 1: radius [m] is required"},
           {"{ centre = {0, 0}, radius = 0.1, mu = 0.2 }", "spray 1: drying_length [m] is required"},
           {"{ radius = 0.1, mu = 0.2, drying_length = 1 }", "spray 1: a centre {x, y} [m] is required"},
           {"{ centre = {0, 0}, radius = 0.1, mu = 0.2, drying_lenght = 1 }", "did you mean 'drying_length'"},
           {"{ centre = {0, 0}, radius = -0.1, mu = 0.2, drying_length = 1 }", "spray 1.radius must be > 0 (got -0.1 m)"},
           {"{ centre = {0, 0}, radius = 0.1, mu = 0.2, drying_length = 1, from = 2, to = 1 }",
            "spray 1.to must be after from (2 s) (got 1 s)"}}) {
    beltsim::test::TwoPulley q;
    q.extra = "spray = { " + zone + " },";
    const std::string err = run_text(beltsim::test::two_pulley(q));
    EXPECT_NE(err.find(expect), std::string::npos) << zone << ": " << err;
  }
}

// A one-way coupled alternator: its rotor read, set at a pause (events.csv), saved and resumed bit
// for bit; the Lua table reads one_way as a boolean.
TEST(LiveApi, CoupledRotorReadChangedAndCheckpointed) {
  const std::string out = (temp_dir() / "rotor").string();
  beltsim::test::TwoPulley coupled;
  coupled.driven = "torque = { per_speed = -0.5 },\n"
                   "      coupling = { inertia = 0.01, stiffness = 50, damping = 0.2, one_way = true }";
  EXPECT_EQ(run_text(beltsim::test::two_pulley(coupled) + "local sim = s:start{ out = '" + out +
                     "', progress = false }\n"
                     "local p = sim:pulley('driven')\n"
                     "assert(p.rotor_speed == 0 and p.windup == 0 and p.coupling_torque == 0, 'relaxed at rest')\n"
                     "assert(sim:pulley('driver').rotor_speed == nil, 'no coupling')\n"
                     "sim:advance(0.002)\n"
                     "sim:set_rotor('driven', { speed = -3.0 })\n"
                     "p = sim:pulley('driven')\n"
                     "assert(p.rotor_speed == -3.0, 'set_rotor')\n"
                     "local ok, err = pcall(sim.set_rotor, sim, 'driver', { speed = 0 })\n"
                     "assert(not ok and err:find(\"pulley 'driver' has no coupling\"), err)\n"
                     "local path = sim:save('" +
                     out +
                     "/rotor.chk')\n"
                     "sim:advance(0.002)\n"
                     "local later = sim:pulley('driven')\n"
                     "assert(later.rotor_speed ~= -3.0, 'the rotor moves')\n"
                     "sim:close()\n"
                     "local r = beltsim.resume(path, { rewind = true })  -- (the rows after it)\n"
                     "r:advance(0.002)\n"
                     "local again = r:pulley('driven')\n"
                     "assert(again.rotor_speed == later.rotor_speed and again.windup == later.windup, 'resumed bits')\n"
                     "r:close()\n"),
            "");
  std::ifstream ev(out + "/events.csv");
  const std::string events((std::istreambuf_iterator<char>(ev)), std::istreambuf_iterator<char>());
  EXPECT_NE(events.find("driven.rotor"), std::string::npos) << events;
}

// the test scene with 240 elements (a transition of 0.05 m spans several) and the driver's torque
// a constant 1 N·m
std::string wet_scene() {
  beltsim::test::TwoPulley p;
  p.driver = "torque = -1", p.elements = 240;
  return beltsim::test::two_pulley(p);
}

// sim:wet's transition (issue 27 §4): μ ramps linearly from the belt's μ to the wet one across the
// transition's length about each end of [from, to]; 0 is the sharp boundary of no transition.
TEST(LiveApi, WetTransitionRampsMuAcrossItsLength) {
  const std::string out = (temp_dir() / "transition").string();
  EXPECT_EQ(
      run_text(
          wet_scene() + "local sim = s:start{ out = '" + out +
          "', progress = false }\n"
          "local n = s:info().elements\n"
          "sim:wet{ from = 0.3, to = 0.6, mu = 0.2, transition = 0.05 }\n"
          "local ramped = 0\n"
          "for i = 0, n - 1 do\n"
          "  local e = sim:element(i)\n"
          "  local d = math.min(e.s - 0.3, 0.6 - e.s)  -- > 0 inside\n"
          "  local w = math.max(0, math.min(1, 0.5 + d / 0.05))\n"
          "  local want = 1 + w * (0.2 - 1)\n"
          "  assert(math.abs(e.mu - want) < 1e-12, ('element %d at s = %g: mu %g, want %g'):format(i, e.s, e.mu, "
          "want))\n"
          "  if w > 0 and w < 1 then ramped = ramped + 1 end\n"
          "  if d > 0.025 then assert(e.mu == 0.2) elseif d < -0.025 then assert(e.mu == 1) end\n"
          "end\n"
          "assert(ramped >= 8, 'elements on the ramps: ' .. ramped)\n"
          "sim:set_mu(1)\n"
          "sim:wet{ from = 0.3, to = 0.6, mu = 0.2, transition = 0 }\n"
          "local sharp = {}\n"
          "for i = 0, n - 1 do sharp[i] = sim:element(i).mu end\n"
          "sim:set_mu(1)\n"
          "sim:wet{ from = 0.3, to = 0.6, mu = 0.2 }\n"
          "for i = 0, n - 1 do assert(sim:element(i).mu == sharp[i], 'transition 0 is no transition') end\n"
          "local ok, err = pcall(sim.wet, sim, { from = 0.3, to = 0.6, mu = 0.2, transition = -0.01 })\n"
          "assert(not ok and err:find('sim:wet.transition: must be >= 0 and finite %(got %-0.01 m%)'), err)\n"
          "-- longer than the stretch: no element would reach mu 0.2 (it changed the whole belt a little)\n"
          "ok, err = pcall(sim.wet, sim, { from = 0.3, to = 0.6, mu = 0.2, transition = 10 })\n"
          "assert(not ok and err:find(\"sim:wet.transition: must be at most the stretch's length, 0.3 m, \" ..\n"
          "  'for its elements to reach the new mu %(it ramps across the transition about each end%) %(got 10 "
          "m%)'), err)\n"
          "ok, err = pcall(sim.wet, sim, { from = 1.1, to = 0.1, mu = 0.2, transition = 0.5 })  -- wrapping\n"
          "assert(not ok and err:find(\"stretch's length, 0.2%d* m\"), err)\n"
          "-- from and to run over [0, s_length], which info() gives (route_length, round the rims, is longer)\n"
          "local L = s:info().s_length\n"
          "assert(L > 1.2 and L < s:info().route_length, L)\n"
          "local said = sim:wet{ from = 0, to = L, mu = 0.5 }\nassert(said:find(n .. ' of ' .. n .. ' elements'), "
          "said)\n"
          "-- the whole loop with a transition: its ends meet, nothing to ramp across (a dry patch was left at s = 0)\n"
          "sim:set_mu(1)\n"
          "sim:wet{ from = 0, to = L, mu = 0.5, transition = 0.05 }\n"
          "for i = 0, n - 1 do assert(sim:element(i).mu == 0.5, 'element ' .. i .. ': ' .. sim:element(i).mu) end\n"
          "ok, err = pcall(sim.wet, sim, { from = 0, to = s:info().route_length, mu = 0.5 })\n"
          "assert(not ok and err:find(\"sim:wet.to: must be in %[0, \" .. string.format('%.6f', L):sub(1, 6) .. "
          "\"%d*%] m, the length the belt coordinate s runs \" ..\n"
          "  \"over %(scene:info%(%)'s s_length%)\"), err)\n"
          "sim:close()\n"),
      "");
}

// A wetting that changes nothing is not recorded (a user's trial: sim:wet{ from = 0.1, to = 0.1 }
// answered "no element changed" and events.csv and the plots' event lines had it): a stretch that
// holds no element is refused, as a batch run's event is; one whose elements have the μ already
// is said and not applied; only the wetting that changed μ is in events.csv.
TEST(LiveApi, AWettingThatChangesNothingIsNotRecorded) {
  const fs::path out = temp_dir() / "wet_nothing";
  EXPECT_EQ(run_text(wet_scene() + "local sim = s:start{ out = '" + out.string() +
                     "', progress = false }\n"
                     "assert(sim:wet{ from = 0.3, to = 0.6, mu = 0.2 }:find('elements'))\n"
                     "local said = sim:wet{ from = 0.3, to = 0.6, mu = 0.2 }\n"
                     "assert(said:find('wet: no element changed %(the %d+ it sets already had mu 0.2%)'), said)\n"
                     "local ok, err = pcall(sim.wet, sim, { from = 0.301, to = 0.301, mu = 0.1 })\n"
                     "assert(not ok and err:find('the stretch holds no element %(an element is in it when its start "
                     "s is%): nothing was changed'), err)\n"
                     "sim:close()\n"),
            "");
  std::ifstream events(out / "events.csv");
  std::string text((std::istreambuf_iterator<char>(events)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "t,what,value\n0,wet,\"mu = 0.2 on s in [0.3, 0.6] m\"\n");
}

// The same transition on a run's events: μ ramps from the belt's μ when the event comes (here 0.5,
// set by a first event) to the new one. Read from the states the run keeps (keep_states, frames
// 1.5e-4 s apart): after both events, and resumed from the one between them (the pending event's
// shares are in the checkpoint).
TEST(LiveApi, EventTransitionRampsMuWhenTheEventComes) {
  const std::string out = (temp_dir() / "event_transition").string();
  EXPECT_EQ(run_text(wet_scene() +
                     "local ev = { { t = 1e-4, mu = 0.5 },\n"
                     "             { t = 2e-4, mu = 0.2, from = 0.3, to = 0.6, transition = 0.05 } }\n"
                     "local function check(sim, n)\n"
                     "  local ramped = 0\n"
                     "  for i = 0, n - 1 do\n"
                     "    local e = sim:element(i)\n"
                     "    local d = math.min(e.s - 0.3, 0.6 - e.s)\n"
                     "    local w = math.max(0, math.min(1, 0.5 + d / 0.05))\n"
                     "    local want = 0.5 + w * (0.2 - 0.5)\n"
                     "    assert(math.abs(e.mu - want) < 1e-12, ('element %d at s = %g: mu %g, want %g'):format(i, "
                     "e.s, e.mu, want))\n"
                     "    if w > 0 and w < 1 then ramped = ramped + 1 end\n"
                     "  end\n"
                     "  assert(ramped >= 8, 'elements on the ramps: ' .. ramped)\n"
                     "end\n"
                     "s:run{ t_end = 3.5e-4, out = '" +
                     out +
                     "', progress = false, events = ev, keep_states = true,\n"
                     "       frames = { fps = 10, slowdown = 1 / 1.5e-3 } }\n"
                     "local after = beltsim.resume('" +
                     out +
                     "/states/state_00002.ckpt', { rewind = true })\n"
                     "check(after, 240)\n"
                     "after:close()\n"
                     "local between = beltsim.resume('" +
                     out +
                     "/states/state_00001.ckpt', { rewind = true })\n"
                     "assert(between:element(0).mu == 0.5, between:element(0).mu)\n"
                     "between:run_to(2.5e-4)\n"
                     "check(between, 240)\n"
                     "between:close()\n"
                     "local ok, err = pcall(s.run, s, { t_end = 1e-4, out = '" +
                     out +
                     "_bad', progress = false,\n"
                     "  events = { { t = 1e-4, mu = 0.2, transition = 0.05 } } })\n"
                     "assert(not ok and err:find('run.events%[1%].transition: a transition needs'), err)\n"),
            "");
}

// a timed event is written to events.csv as the same change made live is (sim:wet, sim:set_mu): a
// plot's event line then reads "wet mu = 0.2 on s in [0.3, 0.6] m", where it read "event scheduled:
// mu = ..." cut off at 40 characters
TEST(LiveApi, TimedEventsAreRecordedAsTheLiveChangesAre) {
  const std::string out = (temp_dir() / "event_record").string();
  EXPECT_EQ(run_text(wet_scene() + "s:run{ t_end = 3e-4, out = '" + out +
                     "_timed', progress = false, frames = false,\n"
                     "       events = { { t = 1e-4, mu = 0.5 }, { t = 2e-4, mu = 0.2, from = 0.3, to = 0.6 } } }\n"
                     "local sim = s:start{ out = '" +
                     out +
                     "_live', progress = false }\n"
                     "sim:set_mu(0.5)\n"
                     "sim:wet{ from = 0.3, to = 0.6, mu = 0.2 }\n"
                     "sim:close()\n"
                     "local function changes(dir)\n"
                     "  local r = {}\n"
                     "  for line in io.lines(dir .. '/events.csv') do\n"
                     "    local what, value = line:match('^[^,]*,([^,]*),(.*)$')\n"
                     "    if what ~= 'what' then r[#r + 1] = what .. ' ' .. value end\n"
                     "  end\n"
                     "  return table.concat(r, '; ')\n"
                     "end\n"
                     "local timed, live = changes('" +
                     out + "_timed'), changes('" + out +
                     "_live')\n"
                     "assert(timed == live, timed .. ' | ' .. live)\n"
                     "assert(timed == 'set_mu mu = 0.5; wet \"mu = 0.2 on s in [0.3, 0.6] m\"', timed)\n"),
            "");
}

// belt.mu_flank (issue 27 §4): the effective μ of the rib wedge is mu_flank/sin(rib_angle/2), with
// the PK belt's 40° by default (0.5/sin 20° = 1.4619); parameters.csv states both; mu and mu_flank
// together, or a rib angle of 180°, are refused with the reason and the value.
TEST(LiveApi, RibWedgeGivesTheEffectiveMu) {
  const std::string out = (temp_dir() / "wedge").string();
  // the test scene with the driver's torque a constant 1 N·m and more keys of the belt; its belt
  // table is on line 6
  const auto with_belt = [](const std::string& assign, const std::string& belt) {
    beltsim::test::TwoPulley p;
    p.assign = assign, p.driver = "torque = -1", p.belt = belt;
    return beltsim::test::two_pulley(p);
  };
  EXPECT_EQ(run_text(with_belt("local s = ", "mu_flank = 0.5") +
                     "local sim = s:start{ out = '" + out + "', progress = false }\n"
                     "local mu = sim:element(7).mu\n"
                     "assert(math.abs(mu - 0.5 / math.sin(math.rad(20))) < 1e-15, mu)\n" +
                     with_belt("local t = ", "mu_flank = 0.5, rib_angle = 60") +
                     "local u = t:start{ out = '" + out + "_60', progress = false }\n"
                     "assert(math.abs(u:element(7).mu - 1.0) < 1e-15, u:element(7).mu)\n"
                     "sim:close() u:close()\n"),
            "");
  std::ifstream f(out + "/parameters.csv");
  const std::string csv((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  EXPECT_NE(csv.find("\nbelt.rib_angle,40,°,default,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("\nbelt.mu_flank,0.5,,given,"), std::string::npos) << csv;
  // mu is derived, not given: its source and note say from what
  const size_t mu_at = csv.find("\nbelt.mu,");
  ASSERT_NE(mu_at, std::string::npos) << csv;
  const std::string mu_row = csv.substr(mu_at + 1, csv.find('\n', mu_at + 1) - mu_at - 1);
  EXPECT_EQ(mu_row.rfind("belt.mu,1.4619", 0), 0u) << mu_row;
  EXPECT_NE(mu_row.find(",,derived,\"effective friction coefficient"), std::string::npos) << mu_row;
  EXPECT_NE(mu_row.find("; derived: mu_flank/sin(rib_angle/2) from belt.mu_flank = 0.5 and belt.rib_angle = 40°\""),
            std::string::npos)
      << mu_row;
  EXPECT_NE(run_text(with_belt("", "mu = 1, mu_flank = 0.5"))
                .find(":6: belt: give mu (the effective coefficient) or mu_flank, not both"),
            std::string::npos);
  EXPECT_NE(run_text(with_belt("", "mu_flank = 0.5, rib_angle = 180"))
                .find(":6: belt.rib_angle: must be > 0 and < 180 (the ribs' included angle) (got 180 °)"),
            std::string::npos);
  EXPECT_NE(run_text(with_belt("", "rib_angle = 200"))
                .find(":6: belt.rib_angle must be < 180 (the ribs' included angle) (got 200 °)"),
            std::string::npos);
}

// values in another unit than their key's (a user trial): each error names the key given, its
// value and the line of the key, and says the unit; a derived μ out of range names what it comes
// from (it named belt.mu, never written, at the call's line); an implausible value that is no
// error warns (it was accepted silently)
TEST(LiveApi, ValuesInAnotherUnitAreToldSo) {
  const auto with = [](const std::string& assign, const std::string& belt, const std::string& driven = "") {
    beltsim::test::TwoPulley p;
    p.assign = assign, p.belt = belt, p.driven = driven;
    return beltsim::test::two_pulley(p);
  };
  // rib_angle in radians with mu_flank: mu = 0.3/sin(0.349°) = 49.25 (the belt table is on line 6)
  std::string err = run_text(with("", "mu_flank = 0.3, rib_angle = 0.698"));
  EXPECT_NE(err.find(":6: belt.mu = 49.25, derived from belt.mu_flank = 0.3 and belt.rib_angle = 0.698° (mu = "
                     "mu_flank/sin(rib_angle/2)), must be in [0, 10]: a friction coefficient"),
            std::string::npos)
      << err;
  EXPECT_NE(err.find("; belt.rib_angle = 0.698° is no V-rib's included angle (20° to 60°; PK belts: 40°): the angle "
                     "is in degrees, not radians (0.698 rad is 39.99°)"),
            std::string::npos)
      << err;
  // a flank μ too large for a plausible angle names mu_flank's line and no angle
  err = run_text(with("", "mu_flank = 4, rib_angle = 40"));
  EXPECT_NE(err.find(":6: belt.mu = 11.7, derived from belt.mu_flank = 4 and belt.rib_angle = 40°"), std::string::npos)
      << err;
  EXPECT_EQ(err.find("V-rib"), std::string::npos) << err;
  // without mu_flank the angle changes nothing, but is told; an inertia in g·cm² warns
  EXPECT_EQ(
      run_text(with("local t = ", "rib_angle = 0.698", "inertia = 2000, torque = { per_speed = -0.955 }") +
               "local w = table.concat(t:info().warnings, '\\n')\n"
               "assert(w:find(\"belt.rib_angle = 0.698° is no V-rib's included angle (20° to 60°; PK belts: 40°): "
               "the angle is in degrees, not radians (0.698 rad is 39.99°); it changes nothing here: without "
               "belt.mu_flank, belt.mu is the effective coefficient itself\", 1, true), w)\n"
               "assert(w:find(\"pulley 'driven'.inertia = 2000 kg·m² is more than a solid steel disc of its "
               "radius (0.1 m), 1 m wide, would have (1.23 kg·m²): the inertia is in kg·m² (2000 g·cm² is "
               "0.0002 kg·m², 2000 kg·cm² 0.2 kg·m²)\", 1, true), w)\n"
               "assert(not w:find('driver'), w)\n"),
      "");
  EXPECT_EQ(run_text(with("local t = ", "mu_flank = 0.3, rib_angle = 35") +
                     "local w = table.concat(t:info().warnings, '\\n')\n"
                     "assert(not w:find('rib_angle') and not w:find('inertia'), w)\n"),
            "");
  // a pretension in kN: the belt's weight over the 0.29 m span is 0.273 N
  beltsim::test::TwoPulley p;
  p.belt_lines = "  belt = { elements = 40, pretension = 0.25 },\n";
  err = run_text(beltsim::test::two_pulley(p));
  // (2 N holds it, the span sagging by 1.7 %: a warning)
  p.assign = "local t = ", p.belt_lines = "  belt = { elements = 40, pretension = 2 },\n";
  EXPECT_EQ(run_text(beltsim::test::two_pulley(p) +
                     "local w = table.concat(t:info().warnings, '\\n')\n"
                     "assert(w:find(\"belt.pretension = 2 N is tiny against the belt's weight over its longest span "
                     "(0.2731 N over 0.29 m): at 2 N that span sags by 1.71 % of its length (ρ·g·L/8T), where the "
                     "start holds the spans straight; the pretension is in N (2 kN would be 2000 N)\", 1, true), w)\n"),
            "");
  EXPECT_NE(err.find(":6: belt.pretension is less than the belt's weight over its longest span (ρ·g·L = 0.27311 N: "
                     "0.096 kg/m over 0.29 m at g = 9.81 m/s²): the belt would hang rather than span its pulleys; the "
                     "pretension is in N (0.25 kN would be 250 N; the paper's belt is mounted at 500 N) (got 0.25 N)"),
            std::string::npos)
      << err;
}

TEST(LiveApi, BadCallsNameFileLineAndWhat) {
  struct Case {
    std::string call, expect;
  };
  for (const Case& c : std::vector<Case>{
           {"sim:advance(0.1, 2)", "sim:advance(dt): expected 1 argument, got 2"},
           {"sim:advance(-1)", "dt must be >= 0 s"},
           {"sim:run_to('x')", "number expected, got string"},
           {"sim:run_to(-1)", "sim:run_to: -1 s is before now (0 s)"},  // the call named once
           {"sim:pulley('drivn')", "did you mean 'driven'"},
           {"sim:element(40)", "must be in 0..39"},
           {"sim:span('driver', 'driver')", "not joined by a span"},
           {"sim:wet{from = 0.1, mu = 0.2}", "give both from and to"},
           {"sim:wet{from = 0.1, to = 0.2, mu = -1}", "must be in [0, 10]"},
           {"sim:wet{from = 0.1, to = 0.2, mu = 1e7}", "must be in [0, 10]"},
           {"sim:set_mu({1, 2})", "one μ per element expected (40), got 2"},
           {"sim:every(0, function() end)", "the interval must be > 0 s"},
           {"sim:show{quantiy = 'mu'}", "did you mean 'quantity'"},
           {"sim:plot{'driver.omga'}", "did you mean 'driver.omega'"},
           // a picture is a PNG: another name got PNG bytes
           {"sim:plot{'driver.omega', file = 'p.jpg'}",
            "sim:plot.file: 'p.jpg': beltsim draws PNG pictures: give a name ending in .png"},
           {"sim:show{file = 's.gif'}", "sim:show.file: 's.gif': beltsim draws PNG pictures"},
           {"sim:summary{plot = 's.jpg'}", "sim:summary.plot: 's.jpg': beltsim draws PNG pictures"},
           // an empty name is refused naming its key (save took the output folder for the file, show
           // the default name)
           {"sim:save('')", "sim:save: an empty file name"},
           {"sim:show{file = ''}", "sim:show.file: an empty file name"},
           {"sim:plot{file = ''}", "sim:plot.file: an empty file name"},
           // sim:show's keys are its own (they read frames.magnify, frames.range)
           {"sim:show{magnify = -1}", "sim:show.magnify: must be in (0, 1e4] (got -1)"},
           {"sim:show{range = {1, 0}}", "sim:show.range: needs lo < hi (got {1, 0})"},
           {"sim:close(); sim:advance(0.1)", "the simulation is closed"},
           // an assignment says what to do instead (it said 'attempt to index a beltsim.Simulation value')
           {"sim.t = 5", "sim.t is read-only: the simulation's time moves by running it (sim:run_to(t)"},
           {"sim.mu = 0.3", "sim.mu cannot be set: a simulation has no fields to set but through its methods"},
           {"s:start{ t_end = 1 }", "unknown key 't_end' in start"},
           {"sim:every(0.001, function(sim) sim:advance(0.1) end); sim:run_to(0.01)", "already running"},
           // (a callback's function may save: sim_test's Live.ACheckpointACallbackAsksForResumesBitForBit)
           {"sim:when(function() sim:save('x') return false end, function() end)",
            "not inside a law or a when-condition"},
       }) {
    const std::string msg = run_text(scene() + c.call + "\n");
    EXPECT_NE(msg.find("live.lua:9:"), std::string::npos) << c.call << " -> " << msg;
    EXPECT_NE(msg.find(c.expect), std::string::npos) << c.call << " -> " << msg;
  }
}

// the summary's counts (its rows, a rotor's overruns) are Lua integers, its other figures floats
TEST(LiveApi, SummaryCountsAreIntegers) {
  beltsim::test::TwoPulley p;
  p.driven = "torque = { per_speed = -0.955 }, coupling = { inertia = 1e-3, stiffness = 50, one_way = true }";
  const std::string out = (temp_dir() / "counts").string();
  EXPECT_EQ(run_text(beltsim::test::two_pulley(p) + "local r = s:run{ t_end = 0.01, out = '" + out +
                     "', progress = false }\n"
                     "local m = r:summary{}\n"
                     "assert(math.type(m.rows) == 'integer' and m.rows == 11, tostring(m.rows))\n"
                     "local n = m.rotors.driven.overrun_count\n"
                     "assert(math.type(n) == 'integer', tostring(n))\n"
                     "assert(math.type(m.from) == 'float' and math.type(m.rotors.driven.overrun_time) == 'float')\n"),
            "");
}

// the folders of a picture's, a checkpoint's or a CSV file's path are made when missing, as
// sim:show's always were (sim:plot's said "the folder ... does not exist", sim:save's, and
// sim:summary's and sim:modes' csv, "... is missing"); a picture without a video takes an odd size
TEST(LiveApi, MissingFoldersAreMade) {
  const fs::path out = temp_dir() / "out";
  fs::remove_all(out);
  EXPECT_EQ(run_text(scene() +
                     "sim:run_to(0.004)\n"
                     "sim:show{ file = 'pics/a.png', size = {321, 181} }\n"
                     "sim:plot{ file = 'p/q.png' }\n"
                     "sim:summary{ csv = 's/t.csv' }\n"
                     "sim:modes{ csv = 'm/n.csv' }\n"
                     "sim:save('" +
                     (out / "sub" / "dir" / "x.ckpt").string() +
                     "')\n"
                     "sim:close()\n"),
            "");
  for (const char* f : {"pics/a.png", "p/q.png", "s/t.csv", "m/n.csv", "sub/dir/x.ckpt"})
    EXPECT_TRUE(fs::is_regular_file(out / f)) << f;
}

// one rule for the paths beltsim writes for a script: a relative one lies in the output folder.
// sim:save's with a folder in it was taken from the folder beltsim ran in (a console session's
// sim:save("ck/t033.ckpt") went to ./ck/, and its session.lua's replay was refused by the
// sandbox), while a bare name, sim:show's and sim:plot's went into the output folder
TEST(LiveApi, RelativePathsAreWrittenInTheOutputFolder) {
  const fs::path out = temp_dir() / "relative";
  fs::remove_all(out);
  fs::remove_all(fs::current_path() / "ck_relative");
  EXPECT_EQ(run_text(beltsim::test::two_pulley(beltsim::test::TwoPulley{}) + "local o = '" + out.string() +
                     "'\n"
                     "local sim = s:start{ out = o, progress = false }\n"
                     "sim:run_to(0.002)\n"
                     "local a, b = sim:save('ck_relative/a.ckpt'), sim:save('b.ckpt')\n"
                     "assert(a == o .. '/ck_relative/a.ckpt', a)\n"
                     "assert(b == o .. '/b.ckpt', b)\n"
                     "local c = sim:show{ file = 'ck_relative/a.png', size = {160, 90} }\n"
                     "assert(c == o .. '/ck_relative/a.png', c)\n"
                     "sim:close()\n"
                     "local r = beltsim.resume(a, { progress = false })  -- (read as returned)\n"
                     "assert(r.t == 0.002, r.t)\n"
                     "r:close()\n"),
            "");
  EXPECT_TRUE(fs::is_regular_file(out / "ck_relative" / "a.ckpt"));
  EXPECT_TRUE(fs::is_regular_file(out / "b.ckpt"));
  EXPECT_FALSE(fs::exists(fs::current_path() / "ck_relative"));
}

// two pictures at one time took one default name, the second overwriting the first without a
// word: the second show_<t>.png of a simulation is show_<t>_2.png (plot_<t>.png alike); a name
// given with file = stays as given
TEST(LiveApi, TwoPicturesAtOneTimeKeepBoth) {
  const fs::path out = temp_dir() / "out";
  fs::remove_all(out);
  testing::internal::CaptureStdout();
  EXPECT_EQ(
      run_text(scene() + "sim:run_to(0.002)\n"
                         "local a, b = sim:show{ quantity = 'tension' }, sim:show{ quantity = 'slip' }\n"
                         "assert(a:match('/show_0.002000.png$') and b:match('/show_0.002000_2.png$'), a .. ' ' .. b)\n"
                         "local c = sim:show{ file = 'show_0.002000.png' }\n"
                         "assert(c:match('/show_0.002000.png$'), c)\n"
                         "assert(sim:show{}:match('/show_0.002000_3.png$'))\n"
                         "local p, q = sim:plot{}, sim:plot{}\n"
                         "assert(p:match('/plot_0.002000.png$') and q:match('/plot_0.002000_2.png$'), p .. ' ' .. q)\n"
                         "sim:run_to(0.003)\n"
                         "assert(sim:show{}:match('/show_0.003000.png$'))\n"
                         "sim:close()\n"),
      "");
  testing::internal::GetCapturedStdout();
  for (const char* f : {"show_0.002000.png", "show_0.002000_2.png", "show_0.002000_3.png", "plot_0.002000.png",
                        "plot_0.002000_2.png", "show_0.003000.png"})
    EXPECT_TRUE(fs::is_regular_file(out / f)) << f;
}

// --t-end shortens scene:run; a live simulation runs to the times its script names, and says so
// once when --t-end was given (the script runs as it would without it)
TEST(LiveApi, TEndSaysItDoesNotShortenALiveSimulation) {
  Interpreter lua;
  Overrides o;
  o.run.t_end = 0.001, o.give("t_end");
  lua.set_overrides(o);
  testing::internal::CaptureStderr();
  const std::string msg = test::run_script(lua, temp_dir() / "live.lua",
                                           scene() + "sim:run_to(0.004)\nassert(sim.t == 0.004, sim.t)\nsim:close()\n" +
                                               "local again = s:start{ out = '" + (temp_dir() / "again").string() +
                                               "', progress = false }\nagain:close()\n");
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(msg, "");
  const std::string warning = "--t-end 0.001 s shortens scene:run only; ";
  ASSERT_NE(err.find(warning), std::string::npos) << err;
  EXPECT_EQ(err.find(warning, err.find(warning) + 1), std::string::npos) << "said twice: " << err;
}

}  // namespace live_api_test
}  // namespace beltsim::script

namespace beltsim::script {
namespace live_api_test {

// sim:when fires when its condition turns true: one already true when registered fires only after
// it has been false (the driver speeds up from rest, so omega > -1 holds at first, fails, then a
// condition set to hold again once |omega| > 2 turns true once)
TEST(LiveApi, WhenAlreadyTrueFiresOnlyAfterItHasBeenFalse) {
  EXPECT_EQ(run_text(scene() +
                     "local always, later = 0, 0\n"
                     "sim:when(function(sim) return true end, function() always = always + 1 end)\n"
                     "sim:when(function(sim) local w = sim:pulley('driver').omega return w > -1e-9 or w < -2 end,\n"
                     "         function() later = later + 1 end)\n"
                     "sim:run_to(0.1)\n"
                     "assert(always == 0, 'a condition true from the start fired ' .. always .. ' times')\n"
                     "assert(sim:pulley('driver').omega < -2, 'the driver reached ' .. sim:pulley('driver').omega)\n"
                     "assert(later == 1, 'the condition that was false in between fired ' .. later .. ' times')\n"),
            "");
}

// { once = true } removes the callback after its first action: a condition true in every odd
// millisecond fires five times over 10 ms, once with it (and its id is gone: cancel says false);
// a misspelt key is refused with its name
TEST(LiveApi, WhenOnceFiresOnce) {
  EXPECT_EQ(run_text(scene() + "local n, m = 0, 0\n"
                               "local function odd(sim) return math.floor(sim.t * 1000 + 1e-9) % 2 == 1 end\n"
                               "sim:when(odd, function() n = n + 1 end)\n"
                               "local id = sim:when(odd, function() m = m + 1 end, { once = true })\n"
                               "sim:run_to(0.0105)\n"
                               "assert(n == 5, 'the repeating callback fired ' .. n .. ' times')\n"
                               "assert(m == 1, 'the once callback fired ' .. m .. ' times')\n"
                               "assert(sim:cancel(id) == false, 'the once callback was still there')\n"),
            "");
  const std::string err =
      run_text(scene() + "sim:when(function() return false end, function() end, { onse = true })\n");
  EXPECT_NE(err.find("sim:when"), std::string::npos) << err;
  EXPECT_NE(err.find("onse"), std::string::npos) << err;
}

// a condition must return a boolean: 0 is true in Lua, so one returning 1 or 0 fired at once or
// never, without a word (a user trial); nil and strings alike. Refused naming the value
TEST(LiveApi, WhenConditionsReturnBooleans) {
  for (const auto& [cond, got] : std::vector<std::pair<std::string, std::string>>{
           {"return sim.t > 0.002 and 1 or 0", "number 0"}, {"", "nil"}, {"return 'no'", "string 'no'"}}) {
    const std::string err = run_text(scene() + "sim:when(function(sim) " + cond +
                                     " end, function() end)\n"
                                     "sim:run_to(0.004)\n");
    // (checked when sim:when is called, at t = 0)
    EXPECT_NE(err.find("live.lua:9: sim:when's condition (function at "), std::string::npos) << cond << ": " << err;
    EXPECT_NE(err.find(" at t = 0 s: it returned " + got + "; it must return true or false"), std::string::npos)
        << cond << ": " << err;
  }
}

// an error in a callback's code names the callback, its function's place and the simulated time
// before the error's own place, as a Lua law's does (it named neither); parameters.csv ends
// "failed" with it, also for a when-condition that fails where sim:when checks it (it said "ok");
// the tables sim:pulley, sim:element and sim:energy return refuse a field they do not have with
// a suggestion (s:pulley('b').omgea was "attempt to perform arithmetic on a nil value")
TEST(LiveApi, CallbackErrorsNameTheCallbackAndTheTime) {
  const fs::path params = temp_dir() / "out" / "parameters.csv";
  const auto status = [&] {
    std::ifstream f(params);
    std::string line, last;
    while (std::getline(f, line))
      if (line.rfind("end.status,", 0) == 0) last = line;
    return last;
  };
  std::string err = run_text(scene() +
                             "sim:every(0.005, function(s)\n"
                             "  local w = s:pulley('driven').omgea * 2\n"
                             "end)\n"
                             "sim:run_to(0.02)\n");
  EXPECT_NE(err.find("live.lua:12: sim:run_to: sim:every's function (function at "), std::string::npos) << err;
  EXPECT_NE(err.find("live.lua:9) at t = 0.005 s: "), std::string::npos) << err;
  EXPECT_NE(err.find("live.lua:10: sim:pulley's table has no field 'omgea' (did you mean 'omega'?); its fields: "
                     "angle, belt_torque, contact_arc, "),
            std::string::npos)
      << err;
  EXPECT_EQ(status().rfind("end.status,failed,,derived,\"sim:every's function (function at ", 0), 0u) << status();
  // at the registration: sim:when checks its condition at once
  err = run_text(scene() + "sim:when(function(s) return s:element(3).tensoin > 0 end, function() end)\n");
  EXPECT_NE(err.find("live.lua:9: sim:when's condition (function at "), std::string::npos) << err;
  EXPECT_NE(err.find(" at t = 0 s: "), std::string::npos) << err;
  EXPECT_NE(err.find("live.lua:9: sim:element's table has no field 'tensoin' (did you mean 'tension'?)"),
            std::string::npos)
      << err;
  EXPECT_EQ(status().rfind("end.status,failed,", 0), 0u) << status();
  err = run_text(scene() + "sim:when(function(s) return 1 end, function() end)\n");
  EXPECT_NE(err.find("it returned number 1; it must return true or false"), std::string::npos) << err;
  EXPECT_EQ(status().rfind("end.status,failed,", 0), 0u) << status();
  // caught, the simulation goes on; a field only some pulleys have reads nil; an action's error
  EXPECT_EQ(run_text(scene() +
                     "assert(sim:pulley('driver').arm_angle == nil and sim:element(0).state)\n"
                     "assert(sim:energy().work_torques == nil)\n"
                     "local id = sim:when(function(s) return s.t > 0.002 end, function(s) error('boom') end)\n"
                     "local ok, e = pcall(sim.run_to, sim, 0.01)\n"
                     "assert(not ok and e:find('sim:when.s action %(function at [^)]*live.lua:11%) at t = 0.002') and "
                     "e:find('live.lua:11: boom$'), e)\n"
                     "sim:cancel(id)\n"
                     "sim:run_to(0.004)\n"
                     "local ok2, e2 = pcall(function() return sim:energy().kinetik end)\n"
                     "assert(not ok2 and e2:find(\"has no field 'kinetik' %(did you mean 'kinetic'%?%)\"), e2)\n"
                     "sim:close()\n"),
            "");
  EXPECT_EQ(status(), "end.status,ok,,derived,\"how the run ended: ok, interrupted, wall_limit, diverged or failed\"");
}

}  // namespace live_api_test
}  // namespace beltsim::script
