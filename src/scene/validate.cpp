// Parameter checks: the helpers (validate.hpp), the laws' and the whole SceneDef's (scene.hpp).
#include "scene/validate.hpp"

#include <cmath>
#include <set>
#include <sstream>

#include "scene/scene.hpp"

namespace beltsim {

void reject(const std::string& what, const std::string& rule, double value, const std::string& unit) {
  std::ostringstream s;
  s.precision(6);
  s << what << ' ' << rule << " (got " << value << (unit.empty() ? "" : " ") << unit << ")";
  throw ParameterError(s.str());
}

void require_finite(const std::string& what, double value, const std::string& unit) {
  if (!std::isfinite(value)) reject(what, "must be a finite number", value, unit);
}

void require_positive(const std::string& what, double value, const std::string& unit) {
  require_finite(what, value, unit);
  if (!(value > 0)) reject(what, "must be > 0", value, unit);
}

void require_non_negative(const std::string& what, double value, const std::string& unit) {
  require_finite(what, value, unit);
  if (!(value >= 0)) reject(what, "must be >= 0", value, unit);
}

namespace {

std::string pulley_label(const PulleyDef& p) { return "pulley '" + p.name + "'"; }

}  // namespace

void validate_law(const std::string& what, const TimeSpeedLaw& law, bool speed) {
  const std::string unit = speed ? "rad/s" : "N·m";
  require_finite(what + ".constant", law.constant, unit);
  require_finite(what + ".per_speed", law.per_speed, unit + "·s/rad");
  auto table = [&](const std::string& name, const std::vector<double>& x, const std::vector<double>& y,
                   const char* xunit) {
    if (x.size() != y.size()) throw ParameterError(what + "." + name + ": the two columns differ in length");
    for (size_t k = 0; k < x.size(); ++k) {
      require_finite(what + "." + name + " entry " + std::to_string(k + 1) + " (first)", x[k], xunit);
      require_finite(what + "." + name + " entry " + std::to_string(k + 1) + " (second)", y[k], unit);
      if (k > 0 && !(x[k] > x[k - 1]))
        reject(what + "." + name + " entry " + std::to_string(k + 1), "must be larger than the entry before it", x[k],
               xunit);
    }
  };
  table("table", law.t, law.value, "s");
  table("per_speed_table", law.omega, law.omega_value, "rad/s");
  for (const Ramp& r : law.ramps) {
    const std::string w = what + (r.is_step() ? " step" : " ramp");
    require_finite(w + ".t0", r.t0, "s");
    require_finite(w + ".t1", r.t1, "s");
    require_finite(w + ".from", r.from, unit);
    require_finite(w + ".to", r.to, unit);
    if (r.t1 < r.t0) reject(w + ".t1", "must not be before t0", r.t1, "s");
  }
  for (const Sine& s : law.sines) {
    require_finite(what + " sine.mean", s.mean, unit);
    require_finite(what + " sine.amplitude", s.amplitude, unit);
    require_non_negative(what + " sine.frequency", s.frequency, "Hz");
    require_finite(what + " sine.frequency", s.frequency, "Hz");
    require_finite(what + " sine.phase", s.phase, "rad");
  }
  for (const Harmonic& h : law.harmonics) {
    require_positive(what + " harmonics order", h.order, "");
    require_finite(what + " harmonics order", h.order, "");
    require_finite(what + " harmonics amplitude", h.amplitude, unit);
    require_finite(what + " harmonics phase", h.phase, "rad");
    require_finite(what + ".mean_speed", h.mean_speed, "rad/s");
  }
  if (speed && (law.per_speed != 0 || !law.omega.empty()))
    throw ParameterError(what + ": a prescribed speed cannot depend on the speed (per_speed, per_speed_table)");
}

void validate(const SceneDef& d) {
  if (d.pulleys.size() < 2)
    reject("scene", "needs at least 2 pulleys", static_cast<double>(d.pulleys.size()), "pulleys");
  std::set<std::string> names;
  for (const PulleyDef& p : d.pulleys) {
    if (p.name.empty()) throw ParameterError("every pulley needs a name");
    if (!names.insert(p.name).second) throw ParameterError("two pulleys are named '" + p.name + "'");
    const std::string w = pulley_label(p);
    require_finite(w + " centre x", p.centre.x(), "m");
    require_finite(w + " centre y", p.centre.y(), "m");
    require_positive(w + " radius", p.radius, "m");
    require_positive(w + " inertia", p.inertia, "kg·m²");
    if (p.kinematic) {
      validate_law(w + " speed", p.speed, true);
      if (!p.torque.is_zero()) throw ParameterError(w + ": give either a torque or a prescribed speed, not both");
    } else {
      validate_law(w + " torque", p.torque, false);
    }
  }
  for (size_t a = 0; a < d.pulleys.size(); ++a)
    for (size_t b = a + 1; b < d.pulleys.size(); ++b) {
      const PulleyDef &p = d.pulleys[a], &q = d.pulleys[b];
      const double dist = (p.centre - q.centre).norm();
      if (dist <= p.radius + q.radius) {
        std::ostringstream s;
        s << "pulleys '" << p.name << "' and '" << q.name << "' overlap: centres " << dist
          << " m apart, radii add up to " << p.radius + q.radius << " m";
        throw ParameterError(s.str());
      }
    }
  const BeltDef& b = d.belt;
  if (b.elements < 3) reject("belt.elements", "must be >= 3", b.elements, "");
  // the cost of a simulated second grows faster than the element count (docs/performance.md:
  // 2400 elements take minutes per simulated second); past this a scene is surely a mistake
  constexpr int kMaxElements = 20000;
  if (b.elements > kMaxElements && !d.allow_large) {
    std::ostringstream s;
    s << "belt.elements: " << b.elements << " elements are more than the limit of " << kMaxElements
      << " (about " << static_cast<long>(b.elements) * 2 / 1000 << " MB of state and Jacobian, and hours per simulated"
      << " second); set allow_large = true in the scene to go past";
    throw ParameterError(s.str());
  }
  switch (b.tensioning) {
    case Tensioning::pretension: require_positive("belt.pretension", b.pretension, "N"); break;
    case Tensioning::rest_length: require_positive("belt.rest_length", b.rest_length, "m"); break;
    case Tensioning::strain: require_positive("belt.strain", b.strain, ""); break;
  }
  if (b.loop_sense != 1 && b.loop_sense != -1) throw ParameterError("belt.direction must be 'cw' or 'ccw'");
  if (b.reading == StiffnessReading::rigidity) {
    require_positive("belt.EA", b.EA, "N");
    require_positive("belt.EI", b.EI, "N·m²");
    require_non_negative("belt.axial_damping", b.axial_damping, "N·s");
    require_non_negative("belt.bending_damping", b.bending_damping, "N·m·s/rad");
    if (b.bending_viscosity) require_non_negative("belt.bending_viscosity", *b.bending_viscosity, "N·m²·s");
  } else {
    if (b.bending_viscosity) throw ParameterError("belt.bending_viscosity: a rigidity; with per-SDE values (sde) give ct");
    require_positive("belt.sde.k", b.k, "N/m");
    require_positive("belt.sde.kt", b.kt, "N·m/rad");
    require_non_negative("belt.sde.c", b.c, "N·s/m");
    require_non_negative("belt.sde.ct", b.ct, "N·m·s/rad");
  }
  if (!(b.e_tra >= 1)) reject("belt.e_tra", "must be >= 1 (below 1 the stiffness is infinite at zero)", b.e_tra, "");
  if (!(b.e_tor >= 1)) reject("belt.e_tor", "must be >= 1 (below 1 the stiffness is infinite at zero)", b.e_tor, "");
  require_positive("belt.mass_per_length", b.mass_per_length, "kg/m");
  require_non_negative("belt.mu", b.mu, "");
  if (!b.mu_per_element.empty()) {
    if (static_cast<int>(b.mu_per_element.size()) != b.elements)
      reject("belt.mu per element", "needs one value per element", static_cast<double>(b.mu_per_element.size()),
             "values");
    for (double mu : b.mu_per_element) require_non_negative("belt.mu of an element", mu, "");
  }
  if (!b.route.empty()) {
    std::set<std::string> seen;
    for (const std::string& nm : b.route) {
      if (!names.count(nm)) throw ParameterError("belt.route names an unknown pulley '" + nm + "'");
      if (!seen.insert(nm).second) throw ParameterError("belt.route visits pulley '" + nm + "' twice");
    }
    if (seen.size() != names.size()) throw ParameterError("belt.route must visit every pulley once");
  }
  const ContactPerLength& cl = d.contact_per_length;
  if (cl.c1) require_non_negative("contact.c1_per_length", *cl.c1, "N/m³");
  else require_non_negative("contact.c1", d.contact.c1, "N/m²");
  if (cl.c2) require_positive("contact.c2_per_length", *cl.c2, "N/m²");
  else require_positive("contact.c2", d.contact.c2, "N/m");
  if (cl.b) require_non_negative("contact.damping_per_length", *cl.b, "N·s/m²");
  else require_non_negative("contact.damping", d.contact.b, "N·s/m");
  require_positive("contact.p_max", d.contact.p_max, "m");
  require_positive("friction.dv", d.friction.dv, "m/s");
  require_finite("gravity", d.gravity, "m/s²");
}

}  // namespace beltsim
