// Reading a live simulation's state from Lua (sim_box.hpp): sim:pulley, sim:element,
// sim:elements, sim:span, sim:energy, sim:stats, in SI units. A prescribed speed's Lua law is
// evaluated while the state is read, so each reading goes through guarded.
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "io/units.hpp"
#include "model/observables.hpp"
#include "script/lua_check.hpp"
#include "script/lua_run.hpp"
#include "script/sim_box.hpp"

namespace beltsim::script {

// sim:pulley(name) -> { omega [rad/s], angle [rad], torque [N·m], belt_torque [N·m], hub_load [N],
// contact_arc, slip_arc, stick_arc [m], creep, slip_speed [m/s], creep_pitch,
// slip_pitch [m/s], mu; on a tensioner arm
// arm_angle [rad], arm_rate [rad/s]; with a coupling rotor_angle [rad], rotor_speed [rad/s],
// windup [rad], coupling_torque [N·m] }
int l_pulley(lua_State* L) {
  Simulation& s = live(L, "pulley", {{"name", kString}});
  const int j = pulley_index(L, s, 2, "sim:pulley");
  PulleyObs p;
  guarded(L, "sim:pulley", [&] { p = s.pulley(j); });  // a Lua law may fail
  lua_createtable(L, 0, 9);
  set_number(L, "omega", p.omega);
  set_number(L, "angle", p.angle);
  set_number(L, "torque", p.torque);
  set_number(L, "belt_torque", p.belt_torque);
  set_number(L, "hub_load", p.hub_load);
  set_number(L, "contact_arc", p.contact_arc);
  set_number(L, "slip_arc", p.slip_arc);
  set_number(L, "stick_arc", p.stick_arc);
  set_number(L, "creep", p.creep);
  set_number(L, "slip_speed", p.slip_speed);
  set_number(L, "creep_pitch", p.creep_pitch);
  set_number(L, "slip_pitch", p.slip_pitch);
  set_number(L, "mu", p.mu);
  if (!std::isnan(p.arm_angle)) set_number(L, "arm_angle", p.arm_angle), set_number(L, "arm_rate", p.arm_rate);
  if (!std::isnan(p.rotor_speed)) {
    set_number(L, "rotor_angle", p.rotor_angle), set_number(L, "rotor_speed", p.rotor_speed);
    set_number(L, "windup", p.windup), set_number(L, "coupling_torque", p.coupling_torque);
  }
  strict_fields(L, "sim:pulley's table",
                {"omega", "angle", "torque", "belt_torque", "hub_load", "contact_arc", "slip_arc", "stick_arc", "creep",
                 "slip_speed", "creep_pitch", "slip_pitch", "mu", "arm_angle", "arm_rate", "rotor_angle", "rotor_speed",
                 "windup", "coupling_torque"});
  return 1;
}

// sim:element(i) -> { x, y [m], phi [rad], s [m], tension, normal, friction [N], slip [m/s], mu,
// pulley (name or nil), state ("stick", "slip" or "free") }
int l_element(lua_State* L) {
  Simulation& s = live(L, "element", {{"i", kNumber}});
  const int i = to_integer(L, 2, "sim:element(i)");
  if (i < 0 || i >= s.model().n_el())
    fail(L, "sim:element: the element number must be in 0.." + std::to_string(s.model().n_el() - 1) + " (got " +
                std::to_string(i) + ")");
  ElementObs e;
  guarded(L, "sim:element", [&] { e = s.element(i); });  // a Lua law may fail
  lua_createtable(L, 0, 11);
  set_number(L, "x", e.x);
  set_number(L, "y", e.y);
  set_number(L, "phi", e.phi);
  set_number(L, "s", s.scene().sites[i].s);
  set_number(L, "tension", e.tension);
  set_number(L, "normal", e.normal);
  set_number(L, "friction", e.friction);
  set_number(L, "slip", e.slip);
  set_number(L, "mu", e.mu);
  if (e.pulley >= 0) lua_pushstring(L, s.model().pulleys[e.pulley].name.c_str()), lua_setfield(L, -2, "pulley");
  lua_pushstring(L, contact_state_name(e.state)), lua_setfield(L, -2, "state");
  strict_fields(L, "sim:element's table",
                {"x", "y", "phi", "s", "tension", "normal", "friction", "slip", "mu", "pulley", "state"});
  return 1;
}

// sim:elements{ pulley = name } -> the numbers (0-based) of the elements in contact with the pulley now
int l_elements(lua_State* L) {
  Simulation& s = live(L, "elements", {{"{ pulley }", kTable}});
  check_keys(L, 2, "sim:elements", {"pulley"});
  if (lua_getfield(L, 2, "pulley") != LUA_TSTRING) fail(L, "sim:elements: pulley (a pulley's name) is required");
  const int j = pulley_index(L, s, lua_gettop(L), "sim:elements");
  lua_pop(L, 1);
  std::vector<int> on;
  guarded(L, "sim:elements", [&] {  // a Lua law may fail
    for (int i = 0; i < s.model().n_el(); ++i)
      if (s.element(i).pulley == j) on.push_back(i);
  });
  lua_createtable(L, static_cast<int>(on.size()), 0);
  for (size_t k = 0; k < on.size(); ++k) lua_pushinteger(L, on[k]), lua_rawseti(L, -2, static_cast<lua_Integer>(k + 1));
  return 1;
}

// sim:span(a, b) -> tension [N] of the span between pulleys a and b
int l_span(lua_State* L) {
  Simulation& s = live(L, "span", {{"a", kString}, {"b", kString}});
  const int a = pulley_index(L, s, 2, "sim:span"), b = pulley_index(L, s, 3, "sim:span");
  const Model& m = s.model();
  const int k = s.scene().find_span(m.pulleys[a].name, m.pulleys[b].name);
  if (k < 0) fail(L, "sim:span: '" + m.pulleys[a].name + "' and '" + m.pulleys[b].name + "' are not joined by a span");
  lua_pushnumber(L, s.span_tension(k));
  return 1;
}

// sim:energy() -> { kinetic, sde, bending, contact, gravity, arm, coupling, mechanical (their sum)
// [J], and with energy
// tracking work_torques, dissipated_axial, dissipated_bending, dissipated_contact,
// dissipated_friction, dissipated_arms, dissipated_couplings [J] }
int l_energy(lua_State* L) {
  Simulation& s = live(L, "energy", {});
  Energy e;
  guarded(L, "sim:energy", [&] { e = s.energy(); });  // a Lua law may fail
  lua_createtable(L, 0, 15);
  set_number(L, "kinetic", e.kinetic);
  set_number(L, "sde", e.sde);
  set_number(L, "bending", e.bending);
  set_number(L, "contact", e.contact);
  set_number(L, "gravity", e.gravity);
  set_number(L, "arm", e.arm);
  set_number(L, "coupling", e.coupling);
  set_number(L, "mechanical", e.total());
  const std::vector<double> w = s.energy_integrals();
  static const char* names[] = {"work_torques",        "dissipated_axial", "dissipated_bending",  "dissipated_contact",
                                "dissipated_friction", "dissipated_arms",  "dissipated_couplings"};
  static_assert(std::size(names) == kEnergyCount);
  for (size_t k = 0; k < w.size(); ++k) set_number(L, names[k], w[k]);
  strict_fields(L, "sim:energy's table",
                {"kinetic", "sde", "bending", "contact", "gravity", "arm", "coupling", "mechanical", names[0], names[1],
                 names[2], names[3], names[4], names[5], names[6]});
  return 1;
}

// sim:stats() -> { t, integrator, steps, rejected, rhs, jacobians, factorizations, solves,
// kink_restarts, wall [s], frames, callbacks, out, check (a checked run's estimate so far) }
int l_stats(lua_State* L) {
  Simulation& s = live(L, "stats", {});
  const WorkCounters w = s.stats();
  lua_createtable(L, 0, 13);
  set_number(L, "t", s.now());
  lua_pushstring(L, s.integrator_name().c_str()), lua_setfield(L, -2, "integrator");
  for (const auto& [k, v] : {std::pair{"steps", w.steps}, std::pair{"rejected", w.rejected}, std::pair{"rhs", w.rhs},
                             std::pair{"jacobians", w.jacobians}, std::pair{"factorizations", w.factorizations},
                             std::pair{"solves", w.solves}, std::pair{"kink_restarts", w.kink_restarts}})
    lua_pushinteger(L, v), lua_setfield(L, -2, k);
  set_number(L, "wall", s.wall());
  lua_pushinteger(L, s.frames_written()), lua_setfield(L, -2, "frames");
  lua_pushinteger(L, s.callbacks()), lua_setfield(L, -2, "callbacks");
  lua_pushstring(L, s.out_dir().c_str()), lua_setfield(L, -2, "out");
  for (const char* f : {"t", "wall"}) set_unit(L, -1, f, run_result_unit(f).value_or(""));
  if (const CheckEstimate c = s.check_estimate(); c.on) push_check(L, c), lua_setfield(L, -2, "check");
  return 1;
}

}  // namespace beltsim::script
