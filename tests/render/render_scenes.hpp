// Small deterministic states for the render tests: the paper's layouts at their static initial
// state, set in motion and deformed by formulas (no integration, so the pictures depend on the
// renderer only, not on the integrator's last bits).
#pragma once

#include <cmath>

#include "model/contacts.hpp"
#include "model/forces.hpp"
#include "model/observables.hpp"
#include "scene/scene.hpp"
#include "support/presets.hpp"

namespace beltsim::test {

// The belt running at v_belt (m/s) along its axes, ±3 % speed ripple round the loop; the
// driver's rim 1 % faster than v_belt, the driven's 1 % slower; a longitudinal wave of the
// element positions that makes the belt tension vary by about ±300 N round the loop; on the
// free spans a transverse wave of 0.3 mm (a job for `magnify`). Δv = 5 mm/s so that the friction
// law has a stick zone at these slip speeds.
inline Scene moving_scene(SceneDef def) {
  def.friction.dv = 5e-3;
  return build_scene(def);
}

inline Eigen::VectorXd moving_state(const Scene& sc, double v_belt = 6.0) {
  const Model& m = sc.model;
  const int n = m.n_el(), N = m.n_coord();
  Eigen::VectorXd y = sc.y0;
  ContactRecords at_rest;
  fill_contacts(m, sc.drive, 0.0, sc.y0.data(), at_rest);
  for (int i = 0; i < n; ++i) {
    const Vec2 e = axis(y[3 * i + 2]);
    const double s = 2 * M_PI * i / n;
    const ElementContact c = element_contact(at_rest, i);
    Vec2 shift = 3.8e-4 * std::sin(s) * e;
    if (c.pulley < 0) shift += 3e-4 * std::sin(5 * s) * perp(e);
    y[3 * i] += shift.x(), y[3 * i + 1] += shift.y();
    const Vec2 vel = v_belt * (1 + 0.03 * std::sin(3 * s)) * e;
    y[N + 3 * i] = vel.x(), y[N + 3 * i + 1] = vel.y();
  }
  for (size_t k = 0; k < sc.route_pulleys.size(); ++k) {
    const int j = sc.route_pulleys[k];
    const double rim = (j == 0 ? 1.01 : 0.99) * v_belt;
    y[N + m.pulley_coord(j)] = sc.route.arcs[k].sense * rim / m.pulleys[j].radius;
    y[m.pulley_coord(j)] = 0.3 + 0.7 * j;  // turned a little, so the marker spokes differ
  }
  return y;
}

}  // namespace beltsim::test
