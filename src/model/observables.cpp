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
  o.torque = p.kinematic ? p.inertia * p.speed.table_slope(t) - o.belt_torque : applied_torque(m, t, v, j);
  return o;
}

}  // namespace beltsim
