// A scene's inputs as a run reports them: every parameter the scenario could give, its value after
// defaults, and whether it was given (SceneDef::given) or a default was taken, with where the
// default comes from. parameters.csv lists them all and a run's first lines name the defaults, so
// a user who gave EA, EI and the axial damping sees that the bending damping is the paper's.

#include "scene/scene.hpp"

namespace beltsim {

std::vector<SceneInput> scene_inputs(const SceneDef& d) {
  std::vector<SceneInput> in;
  auto num = [&](const std::string& key, double v, const std::string& unit, const std::string& note) {
    in.push_back({key, v, "", unit, d.given.count(key) > 0, note});
  };
  auto word = [&](const std::string& key, const std::string& v, const std::string& note) {
    in.push_back({key, 0, v, "", d.given.count(key) > 0, note});
  };
  const BeltDef& b = d.belt;
  num("belt.elements", b.elements, "", "the paper's 60");
  switch (b.tensioning) {
    case Tensioning::pretension: num("belt.pretension", b.pretension, "N", "the paper's 500 N"); break;
    case Tensioning::rest_length: num("belt.rest_length", b.rest_length, "m", "stress-free length"); break;
    case Tensioning::strain: num("belt.strain", b.strain, "", "route length / rest length - 1"); break;
  }
  word("belt.direction", b.loop_sense < 0 ? "cw" : "ccw", "ours: clockwise, as the paper's driver turns");
  if (b.reading == StiffnessReading::rigidity) {
    num("belt.EA", b.EA, "N", "the paper's c_tra; per SDE k = EA/l0, l0 the rest length of an element");
    num("belt.EI", b.EI, "N·m²", "the paper's c_tor; per SDE k_t = EI/l0");
    num("belt.axial_damping", b.axial_damping, "N·s", "the paper's b_tra, per length; per SDE c = axial_damping/l0");
    if (b.bending_viscosity)
      num("belt.bending_viscosity", *b.bending_viscosity, "N·m²·s", "per length; per SDE c_t = bending_viscosity/l0");
    else
      num("belt.bending_damping", b.bending_damping, "N·m·s/rad",
          "the paper's b_tor, per SDE (belt.bending_viscosity gives it per length)");
  } else {
    num("belt.sde.k", b.k, "N/m", "per SDE");
    num("belt.sde.c", b.c, "N·s/m", "per SDE");
    num("belt.sde.kt", b.kt, "N·m/rad", "per SDE");
    num("belt.sde.ct", b.ct, "N·m·s/rad", "per SDE");
  }
  num("belt.e_tra", b.e_tra, "", "ours: 1 (docs/model.md)");
  num("belt.e_tor", b.e_tor, "", "ours: 1 (docs/model.md)");
  num("belt.mass_per_length", b.mass_per_length, "kg/m", "the paper's rho, per metre of unstretched belt");
  if (b.mu_at)
    word("belt.mu", "function of where each element starts", "");
  else if (!b.mu_per_element.empty())
    word("belt.mu", "one value per element", "");
  else
    num("belt.mu", b.mu, "", "the paper's dry 1");
  const ContactPerLength& cl = d.contact_per_length;
  if (cl.c1) num("contact.c1_per_length", *cl.c1, "N/m³", "per metre of pitch; per element c1 = c1_per_length·l");
  else num("contact.c1", d.contact.c1, "N/m²", "the paper's c1, per element");
  if (cl.c2) num("contact.c2_per_length", *cl.c2, "N/m²", "per metre of pitch; per element c2 = c2_per_length·l");
  else num("contact.c2", d.contact.c2, "N/m", "the paper's c2, per element");
  if (cl.b) num("contact.damping_per_length", *cl.b, "N·s/m²", "per metre of pitch; per element b = damping_per_length·l");
  else num("contact.damping", d.contact.b, "N·s/m", "the paper's b, per element");
  num("contact.p_max", d.contact.p_max, "m", "the paper's p_max");
  num("friction.dv", d.friction.dv, "m/s", "the paper's Δv");
  num("gravity", d.gravity, "m/s²", "ours: 9.81 along -y");
  for (const PulleyDef& p : d.pulleys) {
    const std::string pre = "pulley." + p.name + ".";
    num(pre + "radius", p.radius, "m", "the paper's r_p = 0.1 m");
    num(pre + "inertia", p.inertia, "kg·m²", "ours: a steel disc of r = 0.1 m, 20 mm wide (docs/model.md)");
    word(pre + "wrap", p.wrap == WrapSide::inside ? "inside" : "back", "the pulley inside the loop");
    if (!p.tensioner) continue;
    const TensionerDef& t = *p.tensioner;
    const std::string tp = pre + "tensioner.";
    num(tp + "inertia", t.inertia, "kg·m²", "");
    num(tp + "stiffness", t.stiffness, "N·m/rad", "");
    if (t.preload) num(tp + "preload", *t.preload, "N·m", "sets the belt's tension at rest");
    if (t.angle0) num(tp + "angle0", *t.angle0, "rad", "sets the belt's tension at rest");
    num(tp + "damping", t.damping, "N·m·s/rad", "ours: none");
    num(tp + "friction_torque", t.friction_torque, "N·m", "ours: none");
    num(tp + "friction_speed", t.friction_speed, "rad/s", "ours: the width of the friction torque's tanh");
    num(tp + "asymmetric", t.asymmetric, "", "ours: symmetric");
  }
  return in;
}

}  // namespace beltsim
