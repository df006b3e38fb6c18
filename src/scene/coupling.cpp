// The coupled rotors of a scene (CouplingDef in scene_types.hpp; the coupling's law at the top of
// model/coupling.cpp). Each rotor's coordinates follow the arms'; a one-way coupling's clutch hub
// follows its rotor. A one-way clutch drives the rotor in the sense its pulley turns as the belt
// travels (the belt's direction of travel, reversed on a pulley wrapped on the belt's back). At
// t = 0 the spring is relaxed and the rotor and hub turn with the pulley.
#include "scene/build.hpp"
#include "scene/validate.hpp"

namespace beltsim::build {

void validate_coupling(const PulleyDef& p) {
  if (!p.coupling) return;
  const CouplingDef& c = *p.coupling;
  const std::string w = "pulley '" + p.name + "'.coupling.";
  require_positive(w + "inertia", c.inertia, "kg·m²");
  require_positive(w + "stiffness", c.stiffness, "N·m/rad");
  require_non_negative(w + "damping", c.damping, "N·m·s/rad");
  if (!c.one_way) return;
  require_positive(w + "hub_inertia", c.hub_inertia, "kg·m²");
  require_positive(w + "lock_damping", c.lock_damping, "N·m·s/rad");
  require_positive(w + "drag_torque", c.drag_torque, "N·m");
}

void make_couplings(const SceneDef& d, Model& m) {
  m.couplings.clear();
  int coord = 0;
  for (size_t j = 0; j < d.pulleys.size(); ++j) {
    const PulleyDef& p = d.pulleys[j];
    if (!p.coupling) continue;
    const CouplingDef& cd = *p.coupling;
    Coupling c;
    c.pulley = static_cast<int>(j);
    c.inertia = cd.inertia;
    c.stiffness = cd.stiffness;
    c.damping = cd.damping;
    c.one_way = cd.one_way;
    c.sense = p.wrap == WrapSide::inside ? d.belt.loop_sense : -d.belt.loop_sense;
    if (c.one_way) c.hub_inertia = cd.hub_inertia, c.lock_damping = cd.lock_damping, c.drag_torque = cd.drag_torque;
    c.coord = coord;
    coord += c.one_way ? 2 : 1;
    m.pulleys[j].coupling = m.n_coupling();
    m.couplings.push_back(c);
  }
}

void start_couplings(const Model& m, Eigen::VectorXd& y) {
  const int N = m.n_coord();
  for (int c = 0; c < m.n_coupling(); ++c) {
    const int kp = m.pulley_coord(m.couplings[c].pulley), kr = m.rotor_coord(c);
    for (int k = kr; k < kr + (m.couplings[c].one_way ? 2 : 1); ++k) y[k] = y[kp], y[N + k] = y[N + kp];
  }
}

}  // namespace beltsim::build
