#include "scene/law_io.hpp"

#include <stdexcept>

namespace beltsim {

// ---- friction laws: "friction.dv 1e-05", "friction.law lugre", ... ------------------------------

void write_friction(CheckpointWriter& w, const std::string& pre, const Friction& f) {
  w.line(pre + "dv", f.dv);
  w.word(pre + "law", friction_law_name(f.law));
  w.line(pre + "static_ratio", f.static_ratio);
  w.line(pre + "stribeck_speed", f.stribeck_speed);
  w.line(pre + "exponent", f.exponent);
  w.line(pre + "viscous", f.viscous);
  w.line(pre + "bristle_stiffness", f.bristle_stiffness);
  w.line(pre + "bristle_damping", f.bristle_damping);
  w.line(pre + "release_time", f.release_time);
}
Friction read_friction(CheckpointReader& r, const std::string& pre) {
  Friction f;
  f.dv = r.line_num(pre + "dv");
  // the words in FrictionKind's order
  f.law = static_cast<FrictionKind>(r.line_choice(pre + "law", {"threlfall", "stribeck", "lugre"}));
  f.static_ratio = r.line_num(pre + "static_ratio");
  f.stribeck_speed = r.line_num(pre + "stribeck_speed");
  f.exponent = r.line_num(pre + "exponent");
  f.viscous = r.line_num(pre + "viscous");
  f.bristle_stiffness = r.line_num(pre + "bristle_stiffness");
  f.bristle_damping = r.line_num(pre + "bristle_damping");
  f.release_time = r.line_num(pre + "release_time");
  return f;
}

// ---- laws: "pulley.torque.constant 2", ... ---------------------------------------------------

void write_law(CheckpointWriter& w, const TimeSpeedLaw& law, const std::string& k) {
  if (law.fn)
    throw std::runtime_error("checkpoint: the " + k + " law " + law.fn->describe() +
                             " is Lua code, which a checkpoint cannot hold");
  w.line(k + ".constant", law.constant);
  w.line(k + ".per_speed", law.per_speed);
  w.pairs(k + ".table", law.t, law.value);
  w.pairs(k + ".per_speed_table", law.omega, law.omega_value);
  w.line(k + ".ramps", static_cast<long>(law.ramps.size()));
  for (const Ramp& a : law.ramps) {
    w.fixed(k + ".ramp", {a.t0, a.t1, a.from, a.to});
    w.word(k + ".ramp.shape", a.cosine ? "cosine" : "linear");
  }
  w.line(k + ".sines", static_cast<long>(law.sines.size()));
  for (const Sine& a : law.sines) w.fixed(k + ".sine", {a.mean, a.amplitude, a.frequency, a.phase});
  w.line(k + ".harmonics", static_cast<long>(law.harmonics.size()));
  for (const Harmonic& a : law.harmonics) w.fixed(k + ".harmonic", {a.order, a.amplitude, a.phase, a.mean_speed});
}

TimeSpeedLaw read_law(CheckpointReader& r, const std::string& k) {
  TimeSpeedLaw law;
  law.constant = r.line_num(k + ".constant");
  law.per_speed = r.line_num(k + ".per_speed");
  r.line_pairs(k + ".table", law.t, law.value);
  r.line_pairs(k + ".per_speed_table", law.omega, law.omega_value);
  auto groups = [&](const std::string& key, size_t lines_each) {
    r.open(key);
    const size_t n = r.group_count(lines_each);
    r.close();
    return n;
  };
  for (size_t i = 0, n = groups(k + ".ramps", 2); i < n; ++i) {
    const std::vector<double> a = r.line_fixed(k + ".ramp", 4);
    const bool cosine = r.line_choice(k + ".ramp.shape", {"linear", "cosine"}) == 1;
    law.ramps.push_back({a[0], a[1], a[2], a[3], cosine});
  }
  for (size_t i = 0, n = groups(k + ".sines", 1); i < n; ++i) {
    const std::vector<double> a = r.line_fixed(k + ".sine", 4);
    law.sines.push_back({a[0], a[1], a[2], a[3]});
  }
  for (size_t i = 0, n = groups(k + ".harmonics", 1); i < n; ++i) {
    const std::vector<double> a = r.line_fixed(k + ".harmonic", 4);
    law.harmonics.push_back({a[0], a[1], a[2], a[3]});
  }
  return law;
}

}  // namespace beltsim
