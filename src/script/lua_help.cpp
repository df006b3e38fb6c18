// help() and the table it prints (lua_help.hpp).
#include "script/lua_help.hpp"

#include <cstdio>
#include <string>

#include "io/suggest.hpp"
#include "script/lua_check.hpp"

namespace beltsim::script {

namespace {

// help() lists the API; help("advance") prints one entry
int l_help(lua_State* L) {
  check_args(L, "help", {{"name", kString, true}});
  if (lua_isnoneornil(L, 1)) {
    std::printf("beltsim API (help(\"name\") for one entry; SI units, but belt.rib_angle in degrees):\n");
    for (const HelpEntry& h : api_help()) {
      // padded to 48 characters, not bytes: "N·m" is one character more in UTF-8
      const std::string call = h.call;
      size_t chars = 0;
      for (const char c : call) chars += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
      std::printf("  %s%s %s\n", call.c_str(), std::string(chars < 48 ? 48 - chars : 0, ' ').c_str(), h.text);
    }
    std::fflush(stdout);
    return 0;
  }
  if (lua_type(L, 1) != LUA_TSTRING) fail(L, std::string("help: a name expected, got ") + type_name(L, 1));
  const std::string name = lua_tostring(L, 1);
  std::vector<std::string> names;
  for (const HelpEntry& h : api_help()) {
    names.push_back(h.name);
    if (name == h.name) {
      std::printf("%s\n  %s\n", h.call, h.text);
      std::fflush(stdout);
      return 0;
    }
  }
  fail_on(L, "help", std::string("nothing is called '") + name + "'" + did_you_mean(name, names));
}

}  // namespace

const std::vector<HelpEntry>& api_help() {
  static const std::vector<HelpEntry> h = {
      {"scene", "beltsim.scene{ pulleys, belt, contact, friction, gravity, energy, spray, allow_large }",
       "builds a drive (docs/lua-api.md)"},
      {"run",
       "scene:run{ t_end [s], integrator, rtol, atol, sample [s], out, probe, snapshots, progress, events, frames, "
       "keep_states, allow_large, max_wall [s], check }",
       "a batch run: start, run_to(t_end), close"},
      {"start",
       "scene:start{ integrator, rtol, atol, sample [s], out, probe, snapshots, progress, frames, keep_states, "
       "allow_large, max_wall [s], check }",
       "a live simulation at t = 0 (the static state)"},
      {"info", "scene:info() -> { elements, pitch, rest_length, strain, static_tension, wrap_deg, warnings, ... }",
       "the scene as built: element sizes, stiffnesses, the tension at rest, each pulley's wrap"},
      {"element_near", "scene:element_near{ x [m], y [m] } -> i", "the element that starts nearest the point"},
      {"run_to", "sim:run_to(t [s]) -> { t [s], steps, wall [s], interrupted }", "integrates to time t"},
      {"advance", "sim:advance(dt [s]) -> { t [s], steps, wall [s], interrupted }", "integrates dt further"},
      {"t", "sim.t", "the current simulated time [s]"},
      {"pulley", "sim:pulley(name)",
       "{ omega [rad/s], angle [rad], torque, belt_torque [N·m], hub_load [N], contact_arc, slip_arc, "
       "stick_arc [m], creep, slip_speed [m/s], creep_pitch, slip_pitch [m/s], mu (of the elements on it); arm_angle "
       "[rad], arm_rate "
       "[rad/s] on a tensioner arm; rotor_angle [rad], "
       "rotor_speed [rad/s], windup [rad], coupling_torque [N·m] with a coupling }"},
      {"element", "sim:element(i)",
       "{ x, y [m], phi [rad], s [m], tension, normal, friction [N], slip [m/s], mu, pulley, state } of element i "
       "(0-based)"},
      {"elements", "sim:elements{ pulley = name } -> { i... }",
       "the elements (0-based) in contact with the pulley now"},
      {"span", "sim:span(a, b) -> [N]", "tension of the span between pulleys a and b"},
      {"energy", "sim:energy() -> { ... [J] }", "kinetic, spring, contact, gravity energy (and tracked work)"},
      {"stats", "sim:stats()", "steps, rejected, rhs, jacobians, factorizations, wall [s], frames, ..."},
      {"set_torque", "sim:set_torque(name, law [N·m])", "a new torque law on a pulley from now (events.csv)"},
      {"set_speed", "sim:set_speed(name, law [rad/s])", "a prescribed speed on a pulley from now"},
      {"set_arm", "sim:set_arm(name, { angle [rad], rate [rad/s] })", "moves a tensioner arm now (events.csv)"},
      {"set_rotor", "sim:set_rotor(name, { angle [rad], speed [rad/s] })",
       "sets a coupled rotor's angle or speed now (events.csv)"},
      {"wet", "sim:wet{ from [m], to [m], mu, transition [m] }",
       "μ on the belt between s = from and to (belt coordinate) from now, ramped across transition at each end"},
      {"spray", "sim:spray(k [, enabled]) -> { enabled, on, inside, drying }",
       "reads spray zone k, or switches it on or off from now (events.csv)"},
      {"set_mu", "sim:set_mu(mu | {mu...} | function(site))", "μ of every element from now"},
      {"log", "sim:log(text)", "a note in events.csv at the current time"},
      {"every", "sim:every(dt [s], function(sim) end) -> id", "calls the function at now + k·dt exactly"},
      {"when", "sim:when(function(sim) return cond end, function(sim) end, { once }) -> id",
       "runs the action where the condition turns true (located to 1e-10 s); once = true: the first time only"},
      {"cancel", "sim:cancel(id)", "removes an every or when callback"},
      {"show", "sim:show{ quantity, range, levels, magnify, view, size, file } -> png",
       "renders the belt as it is now (tension, normal, friction, slip, mu)"},
      {"plot", "sim:plot{ \"driver.omega\", ..., from = t0 [s], file } -> png", "time histories sampled so far"},
      {"summary", "sim:summary{ from [s], to [s], csv, plot } -> { spans, pulleys, wraps, hubs, ... }",
       "review figures over a window: tensions, slip, capstan margins, hub loads, arm, overruns; also r:summary{...} "
       "on scene:run's results (docs/summary.md)"},
      {"modes",
       "sim:modes{ fmin [Hz], fmax [Hz], transport, csv, shapes, video } -> { [k] = { frequency, damping, where, "
       "share }, ... }",
       "natural frequencies, damping ratios and where each mode's energy is, about the state now (a running belt: "
       "of its motion over one element passing, m.period); shapes = N draws the first N (docs/modes.md)"},
      {"save", "sim:save(path) -> path",
       "a checkpoint: state, integrator, laws, μ, pending events, output positions (not a law given as a Lua "
       "function, nor cvode's history: refused, naming it); a relative path lies in the output folder, as "
       "sim:show's and sim:plot's files"},
      {"resume", "beltsim.resume(path, { progress, rewind, max_wall [s], out }) -> sim",
       "continues a checkpoint (bit for bit); callbacks must be added again; results written after it are cut only "
       "with rewind = true; max_wall [s] as scene:start's (a checkpoint does not keep it); out: a folder of its own, "
       "given a copy of the outputs up to the checkpoint (the checkpoint's folder is only read)"},
      {"serve", "sim:serve{ port = 0, host = \"127.0.0.1\" } -> url",
       "the live view of this simulation in a browser, until it closes; a port in use is refused, naming it "
       "(docs/live-view.md)"},
      {"close", "sim:close()",
       "flushes the CSV files and finalises the video; a simulation that ran says where it ended, as scene:run does"},
      {"rpm", "beltsim.rpm(n) -> [rad/s]", "revolutions per minute to rad/s"},
      {"belts", "beltsim.belts[\"6PK\"] -> { preset, mass_per_length, EA, EI, ... }",
       "a PK belt's values (3PK … 8PK) for the belt table, a new table each time (docs/belts.md)"},
      {"ramp", "beltsim.ramp{ t0 [s], t1 [s], from, to, shape = \"linear\"|\"cosine\" }",
       "a law going from `from` at t0 to `to` at t1 (beltsim.ramp(t1, to): from 0 at t = 0)"},
      {"step", "beltsim.step{ t [s], from, to }",
       "a law jumping from `from` to `to` at t (beltsim.step(t, from, to) too)"},
      {"sine", "beltsim.sine{ mean, amplitude, frequency [Hz], phase [rad] }",
       "mean + amplitude·sin(2π·frequency·t + phase)"},
      {"args", "beltsim.args.KEY", "a script parameter given as --set KEY=VALUE (nil when not given)"},
      {"integrators", "beltsim.integrators()", "the integrators' names"},
      {"version", "beltsim.version", "the program's version number, a string (`beltsim --version` prints it)"},
      {"stop_at", "beltsim.stop_at([t [s]])",
       "the next run that would pass t stops there as Ctrl-C stops it, and later runs are refused as after "
       "Ctrl-C until beltsim.stop_at() (a console's session.lua replays a stopped scene:run with it)"},
      {"replay_of", "beltsim.replay_of(dir)",
       "this script replays the console session whose folder is dir (a session.lua that resumed a checkpoint "
       "begins with it): a beltsim.resume of a checkpoint in dir reads the replay's own copy (the same path in its "
       "output folder), and a resume that would write into dir is refused"},
      {"print", "beltsim.print(...)",
       "prints its values as the console shows them (tables as readable Lua, units after numbers); session.lua "
       "replays with it what the prompt printed"},
      {"sweep", "beltsim.sweep{ grid | samples, run = function(p) end } -> sweep",
       "what a sweep file returns for `beltsim sweep`: its points and the run of one point (docs/sweeps.md)"},
      {"help", "help([name])", "this list, or one entry"},
  };
  return h;
}

void open_help(lua_State* L) {
  lua_pushcfunction(L, l_help);
  lua_setglobal(L, "help");
}

}  // namespace beltsim::script
