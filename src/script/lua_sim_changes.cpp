// Lua bindings of the live simulation's changes (see lua_sim.hpp and docs/lua-api.md, "Live
// simulation"): sim:set_torque, sim:set_speed, sim:set_arm, sim:set_rotor, sim:spray, sim:wet,
// sim:set_mu and sim:log. Each returns (or says) what it changed; the running, callbacks and the
// metatable are lua_sim.cpp's.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "io/number_text.hpp"
#include "io/suggest.hpp"
#include "scene/law_text.hpp"
#include "scene/scene.hpp"
#include "script/context.hpp"
#include "script/lua_check.hpp"
#include "script/lua_law.hpp"
#include "script/lua_run.hpp"
#include "script/progress.hpp"
#include "script/sim_box.hpp"

namespace beltsim::script {

namespace {

// sim:set_torque(name, law) and sim:set_speed(name, law): laws as in the scene
int set_law(lua_State* L, bool speed) {
  const char* what = speed ? "set_speed" : "set_torque";
  Simulation& s = live(L, what, {{"name", kString}, {"law", kNumber | kTable | kFunction}});
  const int j = pulley_index(L, s, 2, (std::string("sim:") + what).c_str());
  SimBox* box = static_cast<SimBox*>(lua_touserdata(L, 1));
  const TimeSpeedLaw law = to_law(L, 3, std::string("sim:") + what, speed, box->ctx);
  const PulleyDrive& p = s.drive().pulleys.at(j);
  const std::string before = p.kinematic ? "speed " + law_text(p.speed) : "torque " + law_text(p.torque);
  double omega_before = 0;
  guarded(L, "sim:set_speed", [&] { omega_before = speed ? s.pulley(j).omega : 0.0; });  // a Lua law may fail
  guarded(L, (std::string("sim:") + what).c_str(), [&] {
    if (speed)
      s.set_speed(j, law, law_text(law));
    else
      s.set_torque(j, law, law_text(law));
  });
  // a belt speed past a PK belt's rating, as the scene build warns of a scene's speeds
  if (const std::optional<double> peak = speed ? peak_speed(law) : std::nullopt)
    if (const std::string w = belt_speed_text(s.scene(), j, *peak, "once its ramps and tables have ended", true);
        !w.empty())
      say("beltsim: warning: sim:set_speed: %s\n", w.c_str());
  // a speed the other way round: the pulley reverses at once, and the belt with it (a user's trial
  // set +50 rad/s on a pulley turning at -45, a sign mistake the drive took without a word); below
  // 1 rad/s either way is a start or a stop, not a reversal
  if (speed) {
    double omega_after = 0;
    guarded(L, "sim:set_speed", [&] { omega_after = s.pulley(j).omega; });
    if (std::abs(omega_before) >= 1 && std::abs(omega_after) >= 1 && (omega_before > 0) != (omega_after > 0))
      say("beltsim: warning: sim:set_speed: %s turned at %s rad/s and now at %s rad/s: it reverses at once, and the "
          "belt with it (a pulley's speed is positive counter-clockwise)\n",
          s.model().pulleys[j].name.c_str(), rounded_text(omega_before, 4).c_str(),
          rounded_text(omega_after, 4).c_str());
  }
  // law times are absolute: a law whose ramps, steps and table all lie before now holds its last
  // value from now on (a ramp typed at the prompt as if from now jumps there at once)
  if (std::vector<double> when = law.kinks(), steps = law.jumps(); s.now() > 0 && (!when.empty() || !steps.empty())) {
    when.insert(when.end(), steps.begin(), steps.end());
    if (const double last = *std::max_element(when.begin(), when.end()); last <= s.now())
      say("beltsim: warning: sim:%s: every change of this law in time lies before now (its last at t = %s s, now "
          "t = %s s): %s holds its final value from here, at once; law times are absolute (a ramp from now: "
          "beltsim.ramp{ t0 = sim.t, t1 = sim.t + T, from = ..., to = ... })\n",
          what, rounded_text(last, 6).c_str(), rounded_text(s.now(), 6).c_str(), s.model().pulleys[j].name.c_str());
  }
  const std::string message = s.model().pulleys[j].name + ": " + before + " -> " + (speed ? "speed " : "torque ") +
                              law_text(law) + " from t = " + rounded_text(s.now(), 6) + " s";
  lua_pushstring(L, message.c_str());
  return 1;
}

// applies μ (NaN: unchanged) and pushes what changed as one line (mu_change_text); when nothing
// changes, nothing is applied and nothing recorded in events.csv. A wet stretch that holds no element is refused, as a
// batch run's event is (lua_run.cpp): a user's trial found sim:wet{ from = 0.1, to = 0.1 } recorded as a wetting
void apply_mu(lua_State* L, Simulation& s, const std::vector<double>& mu, const std::string& what,
              const std::string& text) {
  const std::vector<double> before = s.drive().mu;
  const bool none = std::all_of(mu.begin(), mu.end(), [](double x) { return std::isnan(x); });
  if (none && what == "wet")
    fail(L, "sim:wet: " + text +
                ": the stretch holds no element (an element is in it when its start s is): nothing was changed; "
                "widen it, or give from > to for a stretch across s = 0");
  if (changes_mu(before, mu)) guarded(L, what.c_str(), [&] { s.set_mu(mu, what, text); });
  std::string m;
  guarded(L, what.c_str(), [&] { m = mu_change_text(s, before, mu, what); });  // a Lua law may fail
  lua_pushstring(L, m.c_str());
}

// sim:set_arm and sim:set_rotor: the angle [rad] and/or the rate [rad/s] (its key `rate`) of a
// pulley's arm or rotor set now, by set(s, pulley, angle, rate); a refusal named by the call
template <class Set>
int set_state(lua_State* L, const char* what, const char* rate, Set&& set) {
  const std::string call = std::string("sim:") + what, keys = std::string("{ angle, ") + rate + " }";
  Simulation& s = live(L, what, {{"name", kString}, {keys.c_str(), kTable}});
  const int j = pulley_index(L, s, 2, call.c_str());
  check_keys(L, 3, call.c_str(), {"angle", rate});
  const std::optional<double> a = opt_number(L, 3, "angle", call.c_str());
  const std::optional<double> r = opt_number(L, 3, rate, call.c_str());
  if (!a && !r) fail(L, call + ": give angle [rad] or " + rate + " [rad/s]");
  std::string error;
  try {
    set(s, j, a, r);
  } catch (const std::invalid_argument& e) {
    error = e.what();
  }
  if (!error.empty()) fail(L, call + ": " + error);
  return 0;
}

}  // namespace

// sim:set_arm(name, { angle [rad], rate [rad/s] }): the tensioner arm's state from now
int l_set_arm(lua_State* L) {
  return set_state(L, "set_arm", "rate",
                   [](Simulation& s, int j, auto angle, auto rate) { s.set_arm(j, angle, rate); });
}

// sim:spray(k) -> { enabled, on, inside, drying }; sim:spray(k, enabled): switches spray zone k
// (1-based) on or off from now (its from..to window still applies)
int l_spray(lua_State* L) {
  Simulation& s = live(L, "spray", {{"k", kNumber}, {"enabled", kBoolean, true}});
  const Spray& sp = s.drive().spray;
  const lua_Integer k = lua_isinteger(L, 2) ? lua_tointeger(L, 2) : 0;
  if (k < 1 || k > static_cast<lua_Integer>(sp.zones.size()))
    fail(L, "sim:spray: no zone " + std::string(lua_tostring(L, 2)) + " (the scene has " +
                std::to_string(sp.zones.size()) + " spray zones, numbered from 1)");
  const int z = static_cast<int>(k - 1);
  if (lua_gettop(L) >= 3) {
    // an explicit nil (sim:spray(1, beltsim.args.on) with the argument unset) switched the zone off
    if (lua_isnil(L, 3))
      fail(L,
           "sim:spray: enabled must be true or false, got nil (leave it out to read zone " + std::to_string(k) + ")");
    const bool on = lua_toboolean(L, 3);
    guarded(L, "sim:spray", [&] { s.set_spray(z, on); });
    return 0;
  }
  int inside = 0, drying = 0;
  for (const ElementSpray& e : sp.el) inside += e.zone == z, drying += e.drying;
  lua_createtable(L, 0, 4);
  lua_pushboolean(L, sp.zones[z].enabled), lua_setfield(L, -2, "enabled");
  lua_pushboolean(L, sp.zones[z].on), lua_setfield(L, -2, "on");
  lua_pushinteger(L, inside), lua_setfield(L, -2, "inside");
  lua_pushinteger(L, drying), lua_setfield(L, -2, "drying");
  return 1;
}

// sim:set_rotor(name, { angle [rad], speed [rad/s] }): the coupled rotor's state from now
int l_set_rotor(lua_State* L) {
  return set_state(L, "set_rotor", "speed",
                   [](Simulation& s, int j, auto angle, auto speed) { s.set_rotor(j, angle, speed); });
}

int l_set_torque(lua_State* L) {
  return set_law(L, false);
}

int l_set_speed(lua_State* L) {
  return set_law(L, true);
}

// sim:wet{ from = s0 [m], to = s1 [m], mu = 0.2 | function(site), transition = 0.02 [m] } (no
// from/to: the whole belt; transition: μ ramps linearly across that length about each end)
int l_wet(lua_State* L) {
  Simulation& s = live(L, "wet", {{"{from, to, mu, transition}", kTable}});
  require_table(L, 2, "sim:wet");
  check_keys(L, 2, "sim:wet", {"from", "to", "mu", "transition"});
  const auto from = opt_number(L, 2, "from", "sim:wet"), to = opt_number(L, 2, "to", "sim:wet");
  const auto transition = read_transition(L, 2, from.has_value(), "sim:wet");
  if (!field(L, 2, "mu")) fail(L, "sim:wet: mu (the wet friction coefficient) is required");
  std::vector<double> mu;
  if (transition && *transition > 0) {
    // μ ramps linearly from the belt's μ now to the wet one across `transition` about each end
    check_range(L, s.scene(), from, to, "sim:wet");
    check_transition(L, s.scene(), *from, *to, *transition, "sim:wet");
    mu = mu_over(L, lua_gettop(L), s.scene(), std::nullopt, std::nullopt, "sim:wet");
    const std::vector<double> share = wet_shares(s.scene(), *from, *to, *transition);
    for (size_t i = 0; i < mu.size(); ++i) {
      const double w = share[i], old = s.drive().mu[i];
      mu[i] = w == 0 ? std::nan("") : w == 1 ? mu[i] : old + w * (mu[i] - old);
    }
  } else {
    mu = mu_over(L, lua_gettop(L), s.scene(), from, to, "sim:wet");
  }
  const std::string text = wet_text(
      lua_type(L, -1) == LUA_TNUMBER ? std::optional<double>(lua_tonumber(L, -1)) : std::nullopt, from, to, transition);
  lua_pop(L, 1);
  apply_mu(L, s, mu, "wet", text);
  return 1;
}

// sim:set_mu(number | {mu_0, ..., mu_n-1} | function(site)) on every element
int l_set_mu(lua_State* L) {
  Simulation& s = live(L, "set_mu", {{"mu", kNumber | kTable | kFunction}});
  std::vector<double> mu;
  std::string text;
  if (lua_istable(L, 2)) {
    const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, 2));
    if (n != s.model().n_el())
      fail(L, "sim:set_mu: a list of one μ per element expected (" + std::to_string(s.model().n_el()) + "), got " +
                  std::to_string(n));
    for (lua_Integer k = 1; k <= n; ++k) {
      lua_rawgeti(L, 2, k);
      mu.push_back(to_number(L, -1, "sim:set_mu entry " + std::to_string(k)));
      lua_pop(L, 1);
    }
    text = "list";
  } else {
    mu = mu_over(L, 2, s.scene(), std::nullopt, std::nullopt, "sim:set_mu");
    text = wet_text(lua_type(L, 2) == LUA_TNUMBER ? std::optional<double>(lua_tonumber(L, 2)) : std::nullopt,
                    std::nullopt, std::nullopt, std::nullopt);
  }
  apply_mu(L, s, mu, "set_mu", text);
  return 1;
}

// sim:log(text): a line in events.csv
int l_log(lua_State* L) {
  Simulation& s = live(L, "log", {{"text", kString}});
  if (lua_type(L, 2) != LUA_TSTRING) fail(L, std::string("sim:log: string expected, got ") + type_name(L, 2));
  const std::string text = lua_tostring(L, 2);
  guarded(L, "sim:log", [&] { s.log_event("note", text); });
  return 0;
}

}  // namespace beltsim::script
