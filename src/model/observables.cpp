#include "model/observables.hpp"

#include <cmath>
#include <limits>

#include "model/forces.hpp"

namespace beltsim {

const char* contact_state_name(ContactState s) {
  switch (s) {
    case ContactState::stick: return "stick";
    case ContactState::slip: return "slip";
    default: return "free";
  }
}

ElementObs observe_element(const Model& m, const std::vector<int>& sense, double t, const double* y, int i) {
  const int n = m.n_el();
  const double* q = y;
  const double* v = y + m.n_coord();
  ElementObs o;
  o.x = q[3 * i], o.y = q[3 * i + 1], o.phi = q[3 * i + 2];
  o.sde_force = sde_axial_force(m, q, v, i);
  o.tension = 0.5 * (o.sde_force + sde_axial_force(m, q, v, (i + 1) % n));
  o.mu = m.mu[i];
  const ElementContact c = element_contact(m, t, q, v, i);
  o.normal = c.normal;
  o.pulley = c.pulley;
  if (c.pulley < 0 || !(c.normal > 0)) {
    o.friction = o.slip = std::numeric_limits<double>::quiet_NaN();
    o.state = ContactState::free;
    return o;
  }
  // t̂ is anticlockwise; the belt travels along sense·t̂ on this pulley
  const int s = sense[c.pulley];
  o.friction = s * c.friction;
  o.slip = s * c.slip;
  o.state = std::abs(c.slip) > m.friction.dv ? ContactState::slip : ContactState::stick;
  return o;
}

PulleyObs observe_pulley(const Model& m, double t, const double* y, int j) {
  const double* q = y;
  const double* v = y + m.n_coord();
  const Pulley& p = m.pulleys[j];
  PulleyObs o;
  o.omega = m.omega(j, t, v);
  o.angle = q[m.pulley_coord(j)];
  o.belt_torque = belt_torque(m, t, q, v, j, &o.hub);
  o.hub_load = o.hub.norm();
  o.torque = p.kinematic ? p.inertia * m.speed_rate(j, t) - o.belt_torque : applied_torque(m, t, v, j);
  return o;
}

void observe(const Model& m, const std::vector<int>& sense, double t, const double* y, Observation& out) {
  out.t = t;
  out.elements.resize(m.n_el());
  out.pulleys.resize(m.n_p());
  for (int i = 0; i < m.n_el(); ++i) out.elements[i] = observe_element(m, sense, t, y, i);
  for (int j = 0; j < m.n_p(); ++j) out.pulleys[j] = observe_pulley(m, t, y, j);
}

void blend_contact(const Model& m, double theta, const Observation& a, const Observation& b, Observation& at) {
  auto mix = [theta](double u, double v) { return (1 - theta) * u + theta * v; };
  for (size_t i = 0; i < at.elements.size(); ++i) {
    const ElementObs &ea = a.elements[i], &eb = b.elements[i];
    ElementObs& e = at.elements[i];
    // contact made or lost inside the step: what the interpolated state gives
    if (ea.pulley != eb.pulley || ea.state == ContactState::free || eb.state == ContactState::free) continue;
    e.pulley = ea.pulley;
    e.normal = mix(ea.normal, eb.normal);
    e.friction = mix(ea.friction, eb.friction);
    e.slip = mix(ea.slip, eb.slip);
    e.state = std::abs(e.slip) > m.friction.dv ? ContactState::slip : ContactState::stick;
  }
  for (size_t j = 0; j < at.pulleys.size(); ++j) {
    const PulleyObs &pa = a.pulleys[j], &pb = b.pulleys[j];
    PulleyObs& p = at.pulleys[j];
    p.belt_torque = mix(pa.belt_torque, pb.belt_torque);
    p.hub = (1 - theta) * pa.hub + theta * pb.hub;
    p.hub_load = p.hub.norm();
    const Pulley& pl = m.pulleys[j];
    if (pl.kinematic) p.torque = pl.inertia * m.speed_rate(static_cast<int>(j), at.t) - p.belt_torque;
  }
}

}  // namespace beltsim
