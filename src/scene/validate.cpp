// Parameter checks (validate.hpp): the helpers, the laws' and the whole SceneDef's:
// each number's range from the parameter table (scene/parameters.hpp), what relates several here.
#include "scene/validate.hpp"

#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "io/number_text.hpp"
#include "io/suggest.hpp"
#include "scene/law_text.hpp"
#include "scene/parameters.hpp"
#include "scene/scene_types.hpp"

namespace beltsim {

void reject(const std::string& what, const std::string& rule, double value, const std::string& unit) {
  throw ParameterError(what, rule, value, unit);
}

void reject(std::string_view dotted, const std::string& rule, double value) {
  const Parameter* p = find_parameter(dotted);
  if (!p) throw std::logic_error("reject: '" + std::string(dotted) + "' is not in the parameter table");
  reject(std::string(dotted), rule, value, std::string(p->unit));
}

void require_finite(const std::string& what, double value, const std::string& unit) {
  if (!std::isfinite(value)) reject(what, "must be a finite number", value, unit);
}

void require_positive(const std::string& what, double value, const std::string& unit) {
  require_finite(what, value, unit);
  if (!(value > 0)) reject(what, "must be > 0", value, unit);
}

std::string mu_problem(double mu) {
  if (!std::isfinite(mu)) return std::string(rule_text(Rule::finite));
  return mu >= 0 && mu <= kMuMax ? "" : std::string(rule_text(Rule::friction_coefficient));
}

std::string mu_problem(double mu, int element) {
  const std::string bad = mu_problem(mu);
  return bad.empty() ? "" : bad + " (got " + rounded_text(mu) + " for element " + std::to_string(element) + ")";
}

void require_mu(const std::string& what, double mu) {
  if (const std::string bad = mu_problem(mu); !bad.empty()) reject(what, bad, mu, "");
}

void require_non_negative(const std::string& what, double value, const std::string& unit) {
  require_finite(what, value, unit);
  if (!(value >= 0)) reject(what, "must be >= 0", value, unit);
}

std::string rib_angle_problem(double degrees) {
  if (degrees >= kRibAngleMin && degrees <= kRibAngleMax) return "";
  std::string m = "belt.rib_angle = " + rounded_text(degrees, 6) + "° is no V-rib's included angle (" +
                  rounded_text(kRibAngleMin) + "° to " + rounded_text(kRibAngleMax) + "°; PK belts: 40°)";
  if (degrees > 0 && degrees < kRadiansBelow)
    m += ": the angle is in degrees, not radians (" + rounded_text(degrees, 6) + " rad is " +
         rounded_text(degrees * 180 / M_PI, 4) + "°)";
  return m;
}

void check_rule(const Parameter& par, const std::string& what, double v) {
  const std::string unit(par.unit);
  require_finite(what, v, unit);
  const bool ok = par.rule == Rule::positive               ? v > 0
                  : par.rule == Rule::non_negative         ? v >= 0
                  : par.rule == Rule::exponent             ? v >= 1
                  : par.rule == Rule::at_least_three       ? v >= 3
                  : par.rule == Rule::friction_coefficient ? v >= 0 && v <= kMuMax
                  : par.rule == Rule::slip_band            ? v > 0 && v <= kDvMax
                  : par.rule == Rule::pulley_radius        ? v > 0 && v <= kRadiusMax
                  : par.rule == Rule::strain               ? v > 0 && v < kStrainMax
                                                           : true;
  // (a radius or strain at or below zero is told so; the rule's text is for one too large: written
  // in mm, or as a percentage)
  const bool too_large_rule = par.rule == Rule::pulley_radius || par.rule == Rule::strain;
  if (!ok)
    reject(what, std::string(too_large_rule && v <= 0 ? rule_text(Rule::positive) : rule_text(par.rule)), v, unit);
}

namespace {

std::string pulley_label(const PulleyDef& p) { return "pulley '" + p.name + "'"; }

// the rule of every number of `table` (a pulley's: p's) the scene uses, from the parameter table;
// the message names the key as the scenario gives it ("belt.EA", "pulley 'driver' inertia")
// (label: instead of the table's name, "friction.segments[2]")
void check_rules(const SceneDef& d, std::string_view table, const PulleyDef* p, const std::string& label = {}) {
  for (const Parameter* par : parameters_of(table)) {
    if (par->rule == Rule::none || (par->applies && !par->applies(d))) continue;
    const std::optional<double> v = value_of(*par, d, p);
    if (!v) continue;
    // a pulley's key after its label: "pulley 'a'.radius", "pulley 'a'.tensioner.stiffness"
    const std::string what = p                ? pulley_label(*p) + "." + par->dotted().substr(std::string_view("pulley.").size())
                             : !label.empty() ? label + "." + std::string(par->key)
                                              : par->dotted();
    check_rule(*par, what, *v);
  }
}

// the spray zones' numbers by the rules of the table's "spray" entries, named "spray 2.radius";
// a zone stops after it starts
void check_spray(const SceneDef& d) {
  for (size_t k = 0; k < d.spray.size(); ++k) {
    const SprayZone& z = d.spray[k];
    const std::string w = "spray " + std::to_string(k + 1);
    require_finite(w + ".centre x", z.centre.x(), "m");
    require_finite(w + ".centre y", z.centre.y(), "m");
    const std::pair<const char*, double> numbers[] = {
        {"radius", z.radius}, {"mu", z.mu}, {"from", z.from}, {"to", z.to}, {"drying_length", z.drying_length}};
    for (const auto& [key, v] : numbers) {
      if (std::string_view(key) == "to" && v == std::numeric_limits<double>::infinity()) continue;  // never stops
      check_rule(*find_parameter(std::string("spray.") + key), w + "." + key, v);
    }
    if (!(z.to > z.from)) {
      reject(w + ".to", "must be after from (" + rounded_text(z.from, 6) + " s)", z.to, "s");
    }
  }
}

}  // namespace

void validate_law(const std::string& what, const TimeSpeedLaw& law, bool speed) {
  const std::string unit = speed ? "rad/s" : "N·m";
  require_finite(what + ".constant", law.constant, unit);
  require_finite(what + ".per_speed", law.per_speed, unit + "·s/rad");
  auto table = [&](const std::string& name, const std::vector<double>& x, const std::vector<double>& y,
                   const char* xunit) {
    if (x.size() != y.size()) throw ParameterError(what + "." + name, "the two columns differ in length");
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
    throw ParameterError(what, "a prescribed speed cannot depend on the speed (per_speed, per_speed_table)");
}

void validate_helper_law(const std::string& helper, const TimeSpeedLaw& law) {
  for (const Ramp& r : law.ramps) {
    require_finite(helper + (r.is_step() ? ".t" : ".t0"), r.t0, "s");
    if (!r.is_step()) require_finite(helper + ".t1", r.t1, "s");
  }
  for (const Sine& s : law.sines) {
    require_non_negative(helper + ".frequency", s.frequency, "Hz");
    require_finite(helper + ".frequency", s.frequency, "Hz");
    require_finite(helper + ".phase", s.phase, "rad");
  }
}

void validate(const SceneDef& d) {
  if (d.pulleys.size() < 2)
    reject("scene", "needs at least 2 pulleys", static_cast<double>(d.pulleys.size()),
           d.pulleys.size() == 1 ? "pulley" : "pulleys");
  // The errors about a pulley as a whole carry the path of its key (the name, the centre, the
  // speed) or of its entry in `pulleys`, so that a script's error names that pulley's line
  // (script/key_line.hpp), not the call's.
  std::map<std::string, size_t> names;  // each name's first pulley
  for (size_t k = 0; k < d.pulleys.size(); ++k) {
    const PulleyDef& p = d.pulleys[k];
    const std::string entry = std::to_string(k + 1);  // its place in the list `pulleys`
    if (p.name.empty())
      throw ParameterError(KeyPath{"", {"pulleys", entry, "name"}},
                           "pulley " + entry + ".name: every pulley needs a name (name = \"idler\")");
    // a control character (a newline, a tab) would break the lines of stderr, parameters.csv's rows
    // and the CSV headers that carry the name (a user's trial: name = "b\nc" was taken)
    if (std::any_of(p.name.begin(), p.name.end(), [](char c) { return (c >= 0 && c < 0x20) || c == 0x7f; }))
      throw ParameterError(KeyPath{"", {"pulleys", entry, "name"}},
                           "pulley " + entry + ".name: a name may not hold a control character (a newline, a tab): " +
                               "it names the pulley's columns and lines of the outputs");
    if (const auto [first, added] = names.emplace(p.name, k); !added)
      throw ParameterError(KeyPath{"", {"pulleys", entry, "name"}},
                           "pulley " + entry + ".name: pulleys " + std::to_string(first->second + 1) + " and " + entry +
                               " are both named '" + p.name +
                               "': each needs a name of its own (it names the pulley's columns and its place in "
                               "belt.route)");
    const std::string w = pulley_label(p);
    require_finite(w + " centre x", p.centre.x(), "m");
    require_finite(w + " centre y", p.centre.y(), "m");
    check_rules(d, "pulley", &p);
    if (p.tensioner) check_rules(d, "pulley.tensioner", &p);
    if (p.coupling) check_rules(d, "pulley.coupling", &p);
    if (p.kinematic) {
      validate_law(w + ".speed", p.speed, true);
      if (!p.torque.is_zero())
        throw ParameterError(KeyPath{p.name, {"speed"}},
                             w + ".speed: give either a torque or a prescribed speed, not both (got torque = " +
                                 law_text(p.torque) + " and speed = " + law_text(p.speed) +
                                 "): a pulley with a prescribed speed takes whatever torque that speed needs; leave "
                                 "out torque, or speed to let the pulley turn under its torque");
    } else {
      validate_law(w + ".torque", p.torque, false);
    }
  }
  for (size_t a = 0; a < d.pulleys.size(); ++a)
    for (size_t b = a + 1; b < d.pulleys.size(); ++b) {
      const PulleyDef &p = d.pulleys[a], &q = d.pulleys[b];
      const double dist = (p.centre - q.centre).norm();
      if (dist <= p.radius + q.radius) {
        // the later pulley's centre (or center, as it was given): where the overlap was made
        const bool center = d.given.count("pulley." + q.name + ".center") > 0;
        throw ParameterError(KeyPath{q.name, {center ? "center" : "centre"}},
                             pulley_label(q) + "." + (center ? "center" : "centre") + ": pulleys '" + p.name +
                                 "' and '" + q.name + "' overlap: centres " + rounded_text(dist, 6) +
                                 " m apart, radii add up to " + rounded_text(p.radius + q.radius, 6) +
                                 " m; move them apart or make them smaller (lengths are in metres)");
      }
    }
  const BeltDef& b = d.belt;
  if (b.mu_flank) {
    // mu = mu_flank/sin(rib_angle/2) (script/lua_scene_parts.cpp): out of range, it is named with
    // the two it comes from, at the line of the one more likely wrong (a rib angle no V-rib has)
    if (const std::string bad = mu_problem(b.mu); !bad.empty()) {
      const std::string angle = rib_angle_problem(b.rib_angle);
      throw ParameterError(KeyPath{"", {"belt", angle.empty() ? "mu_flank" : "rib_angle"}},
                           "belt.mu = " + rounded_text(b.mu, 4) + ", derived from belt.mu_flank = " +
                               rounded_text(*b.mu_flank, 6) + " and belt.rib_angle = " + rounded_text(b.rib_angle, 6) +
                               "° (mu = mu_flank/sin(rib_angle/2)), " + bad + (angle.empty() ? "" : "; " + angle));
    }
  }
  check_rules(d, "belt", nullptr);
  // the cost of a simulated second grows faster than the element count (docs/performance.md:
  // 2400 elements take minutes per simulated second); past this a scene is surely a mistake
  constexpr int kMaxElements = 20000;
  if (b.elements > kMaxElements && !d.allow_large) {
    throw ParameterError("belt.elements", std::to_string(b.elements) + " elements are more than the limit of " +
                                              std::to_string(kMaxElements) + " (about " +
                                              std::to_string(static_cast<long>(b.elements) * 2 / 1000) +
                                              " MB of state and Jacobian, and hours per simulated second); set "
                                              "allow_large = true in the scene to go past");
  }
  // allow_large or not: the sparse Jacobian's entries are counted in int (Eigen's index type)
  constexpr int kMostElements = 1000000;
  if (b.elements > kMostElements)
    throw ParameterError("belt.elements", std::to_string(b.elements) + " elements are more than beltsim can hold (" +
                                              std::to_string(kMostElements) + ", allow_large or not)");
  if (b.loop_sense != 1 && b.loop_sense != -1)
    throw ParameterError(KeyPath{"", {"belt", "direction"}}, "belt.direction must be 'cw' or 'ccw'");
  if (b.reading == StiffnessReading::per_sde && b.bending_viscosity)
    throw ParameterError("belt.bending_viscosity", "a rigidity; with per-SDE values (sde) give ct");
  check_rules(d, "belt.sde", nullptr);
  if (!(b.rib_angle < 180)) reject("belt.rib_angle", "must be < 180 (the ribs' included angle)", b.rib_angle, "°");
  if (!b.mu_per_element.empty()) {
    if (static_cast<int>(b.mu_per_element.size()) != b.elements)
      reject("belt.mu per element", "needs one value per element (" + std::to_string(b.elements) + ")",
             static_cast<double>(b.mu_per_element.size()), "values");
    for (double mu : b.mu_per_element) require_mu("belt.mu of an element", mu);
  }
  if (!b.route.empty()) {
    std::vector<std::string> pulley_names;
    for (const auto& [name, k] : names) pulley_names.push_back(name);
    std::set<std::string> seen;
    for (const std::string& nm : b.route) {
      if (!names.count(nm))
        throw ParameterError(KeyPath{"", {"belt", "route"}},
                             "belt.route names an unknown pulley '" + nm + "'" + did_you_mean(nm, pulley_names));
      if (!seen.insert(nm).second)
        throw ParameterError(KeyPath{"", {"belt", "route"}}, "belt.route visits pulley '" + nm + "' twice");
    }
    if (seen.size() != names.size())
      throw ParameterError(KeyPath{"", {"belt", "route"}}, "belt.route must visit every pulley once");
  }
  check_rules(d, "contact", nullptr);
  check_rules(d, "friction", nullptr);
  check_rules(d, "scene", nullptr);
  check_spray(d);
  if (d.friction_segments.size() > kMaxFrictionSegments)
    throw ParameterError("friction.segments", std::to_string(d.friction_segments.size()) +
                                                  " segments are more than the limit of " +
                                                  std::to_string(kMaxFrictionSegments));
  for (size_t k = 0; k < d.friction_segments.size(); ++k) {
    const FrictionSegment& g = d.friction_segments[k];
    const std::string w = "friction.segments[" + std::to_string(k + 1) + "]";
    require_non_negative(w + ".from", g.from, "m");
    require_non_negative(w + ".to", g.to, "m");
    check_friction_law(g.law, w);
  }
}

namespace {

std::string percent(double fraction) {
  return rounded_text(100 * fraction, 3) + " %";
}

// what a belt takes (kStrainWarn's sources)
constexpr const char* kBeltStrains =
    "a PK belt is mounted at a few tenths of a per cent (the paper's 500 N on its EA of 1.52e5 N: 0.33 %) and its "
    "tight span stays well under 1-2 % in service";

// the rest length that strains the belt by a PK belt's mounting strain, as a hint
std::string typical_rest_length(double route) {
  constexpr double kTypical = 0.005;
  return rounded_text(route / (1 + kTypical), 6) + " m is a strain of " + percent(kTypical);
}

// "strain is a fraction: 0.009 = 0.9 %" for the value v
std::string fraction_hint(double v) {
  return "strain is a fraction: " + rounded_text(v / 100, 6) + " = " + rounded_text(v, 6) + " %";
}

}  // namespace

void check_strain_at_rest(const StrainAtRest& s, bool past_half_pitch) {
  const bool too_large = s.strain >= kStrainMax;
  if (!too_large && !past_half_pitch) return;
  const std::string limit = too_large ? "where " + percent(kStrainMax) + " or more is refused"
                                      : "more than the model takes (an SDE stretched by more than half a pitch)";
  std::string reason;
  if (s.key == "belt.rest_length") {
    reason = "is too short for the route: the route is " + rounded_text(s.route, 6) + " m; " +
             rounded_text(s.value, 6) + " m is a strain of " + percent(s.strain) + " (route / rest length - 1), " +
             limit + ": raise it towards the route's length (" + typical_rest_length(s.route) + ")";
  } else if (s.key == "belt.strain") {
    reason = "is a strain of " + percent(s.strain) + ", " + limit + ": lower it; " + fraction_hint(s.value);
  } else {
    reason = "is " + percent(s.strain) + " of the belt's EA (" + rounded_text(s.EA, 6) + " N), a strain at rest of " +
             percent(s.strain) + ", " + limit + ": lower it (it is in N), or give the belt's own EA";
  }
  reject(s.key, reason + "; " + kBeltStrains, s.value);
}

std::string strain_at_rest_warning(const StrainAtRest& s) {
  if (!(s.strain > kStrainWarn)) return "";
  std::string w = s.key + " = " + rounded_text(s.value, 6) + (s.unit.empty() ? "" : " ") + s.unit;
  if (s.key == "belt.rest_length") w += " on the " + rounded_text(s.route, 6) + " m route";
  if (s.key == "belt.pretension")
    w += " is " + percent(s.tension / s.EA) + " of the belt's EA (" + rounded_text(s.EA, 6) + " N): it";
  w += " stretches the belt " + percent(s.strain) + " at rest (route / rest length - 1)";
  if (s.key != "belt.pretension")
    w += ", the spans carrying " + rounded_text(s.tension, 6) + " N (EA = " + rounded_text(s.EA, 6) + " N)";
  w += std::string(", where ") + kBeltStrains;
  if (s.key == "belt.strain")
    w += "; if " + rounded_text(s.value, 6) + " % was meant, " + fraction_hint(s.value);
  else if (s.key == "belt.rest_length")
    w += "; check the rest length against the route's (" + typical_rest_length(s.route) + ")";
  else if (s.key == "belt.pretension")
    w += "; check the pretension (in N) and EA";
  return w + " (docs/model.md, limits the scene build enforces)";
}

void check_friction_law(const Friction& f, const std::string& label) {
  SceneDef d;
  d.friction = f;
  check_rules(d, "friction", nullptr, label);
}

}  // namespace beltsim
