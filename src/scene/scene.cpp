// The Scene's warnings and build_scene: the stages of scene/build.hpp (build.cpp) in
// order, with the static solve's retry.
#include "scene/scene.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "io/number_text.hpp"
#include "model/contacts.hpp"
#include "model/forces.hpp"
#include "scene/bending_loss.hpp"
#include "scene/build.hpp"
#include "scene/parameters.hpp"
#include "scene/validate.hpp"

namespace beltsim {

std::vector<std::string> coarse_wraps(const Scene& sc) {
  std::vector<std::string> out;
  const int n = sc.model.n_el();
  // a contact constant given per element (its input is listed as contact.c1, contact.c2 or
  // contact.damping, not *_per_length) makes a finer belt a stiffer contact: refining changes the answer
  bool per_element = false;
  for (const SceneInput& in : sc.inputs)
    per_element = per_element || in.name == "contact.c1" || in.name == "contact.c2" || in.name == "contact.damping";
  // one warning for every coarse wrap: each named with its figures, the advice given once, with the
  // element count that puts kWrapElementsWarn on the coarsest
  std::ostringstream m;
  m.precision(3);
  int coarse = 0, needed = 0;
  for (size_t k = 0; k < sc.route_names.size(); ++k) {
    const double on = sc.wrap_elements(k);
    if (on >= kWrapElementsWarn) continue;
    needed = std::max(needed, static_cast<int>(std::ceil(kWrapElementsWarn / on * n)));
    m << (coarse++ ? "; pulley '" : "pulley '") << sc.route_names[k] << "': its wrap ("
      << sc.route.arcs[k].angle * 180 / M_PI << "° of r = " << sc.route.arcs[k].radius << " m) holds " << on
      << " elements of " << 1e3 * sc.model.belt.pitch << " mm, each " << 100 / on << " % of the wrap";
  }
  if (coarse == 0) return out;
  // what the coarse wrap costs, measured (docs/model.md, element count: automotive_tensioner.lua
  // over 0.3-0.6 s at 150, 386 and 770 elements, the contact per length): the figures that sum
  // the wrap's contact forces hold, those that depend on where it slips do not. On fixed centres
  // (scripts/fixed_centres.lua at 10 m/s, 60 to 480 elements) the running tension itself falls
  // with the element count: the hub load 5.5 % low at 31 elements a wrap, 0.8 % at 62
  m << (coarse == 1 ? ". On so coarse a wrap" : ". On wraps so coarse")
    << " the hub load and arm angle hold but what the slip decides does not (measured on a 51° idler at 3.9 "
    << "elements against 20: a slip arc twice as long, the belt's power loss 20 % high). belt.elements = " << needed
    << " or more puts " << kWrapElementsWarn << (coarse == 1 ? " on it" : " on each")
    << ": the loads and the loss within 2 %, the slip arc within 20 %, where a tensioner arm sets the tension "
    << "(on fixed centres the running tension falls with a coarse belt: 5 % low at 31 elements a wrap, within 1 % "
    << "at 62)";
  if (per_element)
    m << ", with the contact given per length (contact.c1_per_length, ...) so that refining keeps the answer";
  m << " (docs/model.md, element count)";
  out.push_back(m.str());
  return out;
}

std::vector<std::string> wrong_side_maps(const Scene& sc) {
  std::vector<std::string> out;
  // the sense each pulley turns in: at the drive's steady speeds when they can be found, else as
  // the belt travels the way belt.direction says (the sense a one-way clutch drives in)
  const std::optional<double> v = steady_belt_speed(sc);
  const bool steady = v && *v != 0 && std::isfinite(*v);
  const std::vector<int> sense = sc.senses();
  for (int j = 0; j < sc.model.n_p(); ++j) {
    const TimeSpeedLaw& law = sc.drive.pulleys[j].torque;
    if (sc.drive.pulleys[j].kinematic || law.omega.empty()) continue;
    const int turns = steady && *v < 0 ? -sense[j] : sense[j];  // +1: anticlockwise, Ω > 0
    const bool first = turns < 0;                               // the value it holds: M_1 below Ω_1
    if (first ? law.omega.front() < 0 : law.omega.back() > 0) continue;
    std::ostringstream m;
    m.precision(6);
    const char* way = turns < 0 ? "clockwise (Ω < 0)" : "anticlockwise (Ω > 0)";
    m << "pulley '" << sc.model.pulleys[j].name << "'.torque: per_speed_table's speeds lie in [" << law.omega.front()
      << ", " << law.omega.back() << "] rad/s, but the pulley turns " << way
      << (steady ? " at the drive's steady speeds" : " as the belt travels the way belt.direction gives")
      << ": the table gives its " << (first ? "first" : "last") << " torque, "
      << (first ? law.omega_value.front() : law.omega_value.back())
      << " N·m, at every speed on that side of zero (the speeds are signed: " << (turns < 0 ? "a " : "an anti")
      << "clockwise pulley's are " << (turns < 0 ? "negative" : "positive") << "; docs/lua-api.md, Laws)";
    out.push_back(m.str());
  }
  return out;
}

std::string gap_rotation_warning(const Scene& sc) {
  // the SDE's damper acts on its gap vector d (F = k·d + c·ḋ, the paper's eq. 5), which turns at
  // Ω = v/R round a wrap: |ḋ| = |d|·Ω with no stretching, a force c·|d|·Ω against the spring's k·|d|,
  // their ratio the damper's time c/k times Ω (the paper's 1.35e-4 s at 73 rad/s: 1 %)
  const Belt& b = sc.model.belt;
  if (!(b.c > 0) || b.e_tra != 1) return "";
  const std::optional<double> v = steady_belt_speed(sc);
  if (!v || !std::isfinite(*v) || sc.route.arcs.empty()) return "";
  size_t tightest = 0;
  for (size_t k = 1; k < sc.route.arcs.size(); ++k)
    if (sc.route.arcs[k].radius < sc.route.arcs[tightest].radius) tightest = k;
  const double R = sc.route.arcs[tightest].radius, tau = b.c / b.k, ratio = tau * std::abs(*v) / R;
  if (!(ratio > kGapRotationWarn)) return "";
  std::string key = "belt.axial_damping";
  for (const SceneInput& in : sc.inputs)
    if (in.name == "belt.axial_damping" || in.name == "belt.sde.c")
      key = in.name + " = " + rounded_text(in.value, 6) + " " + in.unit;
  std::ostringstream m;
  m.precision(3);
  m << key << ": the SDE's damper acts on its gap vector, which turns with the belt round a wrap: at the drive's "
    << "steady speeds (belt " << std::abs(*v) << " m/s) on pulley '" << sc.route_names[tightest] << "' (r = " << R
    << " m) its force from that turning alone is " << ratio << " times the gap's spring force, a tension no "
    << "strain gives that the spans and hub loads carry. The damper's time c/k is " << tau
    << " s, where a PK belt's is about 1.4e-4 s (the paper's; docs/belts.md): give the belt's own axial damping "
    << "(docs/model.md, the laws)";
  return m.str();
}

std::string static_state_warning(const Scene& sc) {
  // the tension asked at rest, when a pretension gave it (a rest length or a strain gives what it gives)
  double asked = 0;
  for (const SceneInput& in : sc.inputs)
    if (in.name == "belt.pretension" && in.given) asked = in.value;
  std::ostringstream m;
  m.precision(6);
  if (!(sc.static_residual < build::kStaticConverged)) {
    m << "the belt's static initial state was not found: the iteration stopped " << rounded_text(sc.static_residual, 3)
      << " m/s² from equilibrium (scene:info().static_residual), the spans at " << rounded_text(sc.static_tension, 6)
      << " N";
    if (asked > 0) m << " for the " << rounded_text(asked, 6) << " N asked";
    m << ": the run starts out of equilibrium, with a jolt the drive did not ask for; a belt far stiffer than its "
      << "contact (belt.EA against contact.c2), or a few elements more or fewer, may let it be found (docs/model.md, "
         "Limits the scene build enforces)";
    return m.str();
  }
  if (asked > 0 && std::abs(sc.static_tension - asked) > 1e-3 * asked)
    m << "the belt at rest carries " << rounded_text(sc.static_tension, 6)
      << " N, not the belt.pretension = " << rounded_text(asked, 6) << " N asked ("
      << rounded_text(100 * (sc.static_tension / asked - 1), 2)
      << " %): the rest length that gives it was not found; the run starts from that tension";
  return m.str();
}

std::vector<std::string> aiding_loads(const Scene& sc) {
  std::vector<std::string> out;
  // only where a prescribed speed drives the belt: without one, a torque that turns its pulley
  // the way it runs is how a driver is given (the paper's)
  bool speed_driven = false;
  for (const PulleyDrive& p : sc.drive.pulleys) speed_driven = speed_driven || p.kinematic;
  const std::optional<double> v = steady_belt_speed(sc);
  if (!speed_driven || !v || *v == 0 || !std::isfinite(*v)) return out;
  const std::vector<int> sense = sc.senses();
  for (int j = 0; j < sc.model.n_p(); ++j) {
    const TimeSpeedLaw& law = sc.drive.pulleys[j].torque;
    // a law of time alone that settles (constant, steps, ramps, a table): its value once settled
    if (sc.drive.pulleys[j].kinematic || sc.model.pulleys[j].coupling >= 0 || law.fn || !law.omega.empty() ||
        law.per_speed != 0 || !law.sines.empty() || !law.harmonics.empty())
      continue;
    double settled = 0;
    for (double k : law.kinks()) settled = std::max(settled, k);
    for (double k : law.jumps()) settled = std::max(settled, k);
    const double M = law.eval(settled + 1, 0, true);
    const int turns = *v < 0 ? -sense[j] : sense[j];  // +1: anticlockwise, Ω > 0
    if (M == 0 || (M > 0) != (turns > 0)) continue;
    std::ostringstream m;
    m.precision(6);
    m << "pulley '" << sc.model.pulleys[j].name << "'.torque: " << M << " N·m"
      << (settled > 0 ? " once its law has settled" : "") << " turns the pulley the way it runs ("
      << (turns < 0 ? "clockwise, Ω < 0" : "anticlockwise, Ω > 0")
      << ", at the drive's steady speeds): it drives the belt with the prescribed speed instead of loading it; "
      << "a load's torque has the sign opposite to its speed, here " << -M
      << " N·m (counter-clockwise is positive; docs/lua-api.md, Laws)";
    out.push_back(m.str());
  }
  return out;
}

namespace {

// the input that sets the belt's tension at rest: its pretension, rest length or strain, else a
// tensioner's preload or free angle; nullptr when none (a scene read without its inputs)
const SceneInput* tension_input(const Scene& sc) {
  for (const SceneInput& in : sc.inputs)
    if (in.name == "belt.pretension" || in.name == "belt.rest_length" || in.name == "belt.strain") return &in;
  for (const SceneInput& in : sc.inputs)
    if (in.name.ends_with(".tensioner.preload") || in.name.ends_with(".tensioner.angle0")) return &in;
  return nullptr;
}

}  // namespace

std::string strain_warning(const Scene& sc) {
  StrainAtRest s;
  const SceneInput* in = tension_input(sc);
  if (!in) return "";
  s.key = in->name, s.value = in->value, s.unit = in->unit;
  const Belt& b = sc.model.belt;
  s.strain = b.pitch / b.rigid_length - 1;
  s.tension = sc.static_tension;
  s.EA = b.k * b.rigid_length;
  s.route = sc.route.length;
  return strain_at_rest_warning(s);
}

namespace {
// [m] the radius at which the belt runs on pulley j (its arc of the route; a pulley off the route
// has none: 0)
double pitch_radius(const Scene& sc, int j) {
  for (size_t k = 0; k < sc.route_pulleys.size(); ++k)
    if (sc.route_pulleys[k] == j) return sc.route.arcs[k].radius;
  return 0;
}
}  // namespace

std::optional<double> peak_speed(const TimeSpeedLaw& speed) {
  const std::optional<double> steady = steady_value(speed, 0.0);
  if (!steady) return std::nullopt;
  double peak = std::abs(*steady);
  for (const Sine& x : speed.sines) peak += std::abs(x.amplitude);
  for (const Harmonic& h : speed.harmonics) peak += std::abs(h.amplitude);
  return *steady < 0 ? -peak : peak;
}

std::string belt_speed_text(const Scene& sc, int pulley, double omega, const std::string& when, bool prescribed) {
  const Model& m = sc.model;
  const double radius = pitch_radius(sc, pulley);
  const double v = std::abs(omega) * radius;
  if (!(v > kBeltSpeedWarn)) return "";
  const Belt& b = m.belt;
  const double per_length = b.mass / b.rigid_length;  // [kg/m]
  const double centrifugal = per_length * v * v;
  const auto num = [](double x) { return rounded_text(x, 5); };
  const std::string name = "pulley '" + m.pulleys[pulley].name + "'";
  std::string w = (prescribed ? name + ".speed: " : name + " turns at ") + num(omega) + " rad/s " + when +
                  ", which moves the belt at " + num(v) + " m/s (pitch radius " + num(radius) +
                  " m), past what PK belts are rated for (about 50-60 m/s; warned above " + num(kBeltSpeedWarn) +
                  " m/s): its centrifugal tension m'·v² would be " + num(centrifugal) + " N (m' = " + num(per_length) +
                  " kg/m), " + num(centrifugal / sc.static_tension) + " times its " + num(sc.static_tension) +
                  " N at rest";
  if (prescribed)
    w += ". Speeds are in rad/s: if " + num(std::abs(omega)) + " rpm was meant, beltsim.rpm(" + num(std::abs(omega)) +
         ") is " + num(std::abs(omega) * 2 * M_PI / 60) + " rad/s";
  else
    w += ". Check the torques: a load too light for the driving torque lets the drive run so fast";
  return w + " (docs/model.md, limits the scene build enforces)";
}

std::string belt_speed_warning(const Scene& sc) {
  const Model& m = sc.model;
  // the fastest: its pulley, speed [rad/s] and when it turns so
  int pulley = -1;
  double omega = 0;
  std::string when;
  const auto consider = [&](int j, double w, const std::string& at) {
    if (std::isfinite(w) &&
        (pulley < 0 || std::abs(w) * pitch_radius(sc, j) > std::abs(omega) * pitch_radius(sc, pulley)))
      pulley = j, omega = w, when = at;
  };
  bool kinematic = false;
  for (const int j : sc.route_pulleys) {
    const PulleyDrive& p = sc.drive.pulleys[j];
    if (!p.kinematic) continue;
    kinematic = true;
    consider(j, sc.y0[m.n_coord() + m.pulley_coord(j)], "at the start");
    if (const std::optional<double> peak = peak_speed(p.speed))
      consider(j, *peak, "once its ramps and tables have ended");
  }
  if (!kinematic)
    if (const std::optional<double> v = steady_belt_speed(sc)) {
      // the belt at the free pulleys' balance of torques: the smallest pulley turns fastest
      size_t fastest = 0;
      for (size_t k = 1; k < sc.route_pulleys.size(); ++k)
        if (sc.route.arcs[k].radius < sc.route.arcs[fastest].radius) fastest = k;
      const double r = sc.route.arcs[fastest].radius;
      consider(sc.route_pulleys[fastest], sc.route.arcs[fastest].sense * *v / r,
               "at the drive's steady speeds (the free pulleys' torques balanced)");
    }
  if (!kinematic && pulley < 0 && drives_past_fastest(sc)) {
    std::ostringstream w;
    w << "the free pulleys' torques find no steady speed below " << kFastestBeltSpeed
      << " m/s of belt: they drive it on faster than any belt runs, until it slips on a pulley or a pulley runs "
         "away (a run stops past 1e5 rad/s). Check the torques: a load too light for the driving torque lets the "
         "drive run so fast (docs/model.md, limits the scene build enforces)";
    return w.str();
  }
  return pulley < 0 ? "" : belt_speed_text(sc, pulley, omega, when, kinematic);
}

std::string sag_warning(const Scene& sc) {
  const SceneInput* in = tension_input(sc);
  if (!in) return "";
  const Belt& b = sc.model.belt;
  double longest = 0;
  for (const Route::Span& sp : sc.route.spans) longest = std::max(longest, sp.length);
  const double weight = b.mass / b.rigid_length * std::abs(sc.model.gravity) * longest;  // ρ·g·L [N]
  // the tension the input gives: a pretension's own value (the static state may hold the spans at
  // more: the belt's bending stiffness round the wraps), else the static state's
  const bool pretension = in->name == "belt.pretension";
  const double T = pretension ? in->value : sc.static_tension;
  const double sag = weight / (8 * T);  // δ/L = ρgL/8T
  if (!(sag > kSagWarn)) return "";
  const std::string N = rounded_text(T, 4) + " N";
  std::string m = in->name + " = " + rounded_text(in->value, 6) + (in->unit.empty() ? "" : " " + in->unit) +
                  (pretension ? " is" : " gives the spans " + N + " at rest,") +
                  " tiny against the belt's weight over its longest span (" + rounded_text(weight, 4) + " N over " +
                  rounded_text(longest, 4) + " m): at " + N + " that span sags by " + rounded_text(100 * sag, 3) +
                  " % of its length (ρ·g·L/8T), where the start holds the spans straight";
  if (pretension && in->value < 10)
    m += "; the pretension is in N (" + rounded_text(in->value, 6) + " kN would be " +
         rounded_text(1000 * in->value, 6) + " N)";
  return m;
}

std::vector<std::string> spray_warnings(const Scene& sc) {
  std::vector<std::string> out;
  const int n = sc.model.belt.n;
  for (size_t k = 0; k < sc.drive.spray.zones.size(); ++k) {
    const SprayZone& z = sc.drive.spray.zones[k];
    // the distance from the circle's centre to the belt's path at rest: the polygon of its
    // elements' centres, along which they travel
    double nearest = INFINITY;
    for (int i = 0; i < n; ++i) {
      const int j = (i + 1) % n;
      const Vec2 a(sc.y0[3 * i], sc.y0[3 * i + 1]), b(sc.y0[3 * j], sc.y0[3 * j + 1]);
      const Vec2 ab = b - a;
      const double u = ab.squaredNorm() > 0 ? std::clamp((z.centre - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0) : 0.0;
      nearest = std::min(nearest, (a + u * ab - z.centre).norm());
    }
    if (nearest <= z.radius) continue;
    out.push_back("spray " + std::to_string(k + 1) + ": its circle (centre {" + rounded_text(z.centre.x(), 4) + ", " +
                  rounded_text(z.centre.y(), 4) + "} m, radius " + rounded_text(z.radius, 4) +
                  " m) does not reach the belt at rest, whose path passes " + rounded_text(nearest, 4) +
                  " m from its centre: it wets nothing unless the belt moves there (docs/spray.md)");
  }
  return out;
}

std::vector<std::string> unit_warnings(const Scene& sc) {
  std::vector<std::string> out;
  const auto input = [&](const std::string& name) -> const SceneInput* {
    for (const SceneInput& in : sc.inputs)
      if (in.name == name) return &in;
    return nullptr;
  };
  // a rib angle no V-rib has (in radians?): with mu_flank it sets μ, without it changes nothing
  if (const SceneInput* angle = input("belt.rib_angle"); angle && angle->given) {
    if (std::string m = rib_angle_problem(angle->value); !m.empty()) {
      const SceneInput* mu = input("belt.mu");
      if (input("belt.mu_flank") && mu)
        m += "; it makes belt.mu = mu_flank/sin(rib_angle/2) = " + rounded_text(mu->value, 4);
      else
        m += "; it changes nothing here: without belt.mu_flank, belt.mu is the effective coefficient itself";
      out.push_back(m);
    }
  }
  // a pulley inertia in g·cm² or kg·cm² written as kg·m²
  for (const Pulley& p : sc.model.pulleys) {
    const SceneInput* in = input("pulley." + p.name + ".inertia");
    const double solid = 0.5 * kSteelDensity * M_PI * kSolidWidth * std::pow(p.radius, 4);
    if (!in || !in->given || !(p.inertia > solid)) continue;
    const std::string J = rounded_text(p.inertia, 6);
    out.push_back("pulley '" + p.name + "'.inertia = " + J + " kg·m² is more than a solid steel disc of its radius (" +
                  rounded_text(p.radius, 6) + " m), " + rounded_text(kSolidWidth) + " m wide, would have (" +
                  rounded_text(solid, 3) + " kg·m²): the inertia is in kg·m² (" + J + " g·cm² is " +
                  rounded_text(p.inertia * 1e-7, 6) + " kg·m², " + J + " kg·cm² " + rounded_text(p.inertia * 1e-4, 6) +
                  " kg·m²); a rotor lumped into the pulley (an engine's, a motor's) may have so much");
  }
  // a tensioner arm's inertia about its pivot, likewise: against a solid steel disc reaching to the
  // pulley's rim (radius: the arm's length plus the pulley's), kSolidWidth wide
  for (const Arm& a : sc.model.arms) {
    const Pulley& p = sc.model.pulleys[a.pulley];
    const SceneInput* in = input("pulley." + p.name + ".tensioner.inertia");
    const double reach = a.length + p.radius;
    const double solid = 0.5 * kSteelDensity * M_PI * kSolidWidth * std::pow(reach, 4);
    if (!in || !in->given || !(a.inertia > solid)) continue;
    const std::string J = rounded_text(a.inertia, 6);
    out.push_back("pulley '" + p.name + "'.tensioner.inertia = " + J +
                  " kg·m² is more than a solid steel disc reaching from the pivot to the pulley's rim (radius " +
                  rounded_text(reach, 6) + " m), " + rounded_text(kSolidWidth) + " m wide, would have about it (" +
                  rounded_text(solid, 3) + " kg·m²): the inertia is in kg·m² (" + J + " g·cm² is " +
                  rounded_text(a.inertia * 1e-7, 6) + " kg·m², " + J + " kg·cm² " + rounded_text(a.inertia * 1e-4, 6) +
                  " kg·m²)");
  }
  return out;
}

std::vector<std::string> scene_warnings(const Scene& sc) {
  std::vector<std::string> out;
  for (std::string& w : unit_warnings(sc)) out.push_back(std::move(w));
  if (std::string rest = static_state_warning(sc); !rest.empty()) out.push_back(std::move(rest));
  if (std::string gap = gap_rotation_warning(sc); !gap.empty()) out.push_back(std::move(gap));
  if (std::string strain = strain_warning(sc); !strain.empty()) out.push_back(std::move(strain));
  if (std::string speed = belt_speed_warning(sc); !speed.empty()) out.push_back(std::move(speed));
  if (std::string sag = sag_warning(sc); !sag.empty()) out.push_back(std::move(sag));
  for (std::string& w : spray_warnings(sc)) out.push_back(std::move(w));
  for (std::string& w : coarse_wraps(sc)) out.push_back(std::move(w));
  for (std::string& w : wrong_side_maps(sc)) out.push_back(std::move(w));
  for (std::string& w : aiding_loads(sc)) out.push_back(std::move(w));
  // μ = 0 is in its range (the frictionless tests of the laws use it) but a drive that transmits
  // nothing: said, as a user's belt.mu = 0 went silent while the driver spun alone (trial 16)
  if (!sc.drive.mu.empty() && std::all_of(sc.drive.mu.begin(), sc.drive.mu.end(), [](double mu) { return mu == 0; }))
    out.push_back(
        "belt.mu = 0 on every element: the belt transmits no torque between the pulleys (each turns "
        "under its own law alone) until an event or sim:set_mu gives it friction");
  for (int j = 0; j < sc.model.n_p(); ++j) {
    const PulleyDrive& p = sc.drive.pulleys[j];
    if (p.kinematic || !(p.torque.per_speed > 0)) continue;
    std::ostringstream m;
    m.precision(3);
    m << "pulley '" << sc.model.pulleys[j].name << "'.torque: per_speed = " << p.torque.per_speed
      << " N·m·s/rad > 0 feeds energy in (the torque grows with the speed in its own sense): the speed runs away "
         "unless the belt holds it; a load opposing the rotation has per_speed < 0";
    out.push_back(m.str());
  }
  if (std::string bending = bending_loss_warning(sc); !bending.empty()) out.push_back(std::move(bending));
  return out;
}

namespace {
Scene build_at(const SceneDef& d, BuildWatch& watch) {
  const BeltDef& bd = d.belt;
  const int n = bd.elements;
  Scene sc;
  Model& m = sc.model;
  sc.inputs = scene_inputs(d);
  sc.reading = bd.reading;

  m.pulleys = build::make_pulleys(d);
  build::make_arms(d, m);
  build::make_couplings(d, m);
  sc.drive = build::make_drive(d);
  const build::RouteOrder order = build::route_order(d, m.pulleys);
  sc.route_names = order.names;
  sc.route_pulleys = order.pulleys;
  sc.route = make_route(order.circles, bd.loop_sense, order.names);
  build::check_wraps(sc.route, order.names, n);

  Belt& b = m.belt;
  b.n = n;
  b.pitch = sc.route.length / n;
  b.e_tra = bd.e_tra;
  b.e_tor = bd.e_tor;
  build::set_rest_length(b, bd, b.pitch);
  build::check_speeds(m.pulleys, sc.drive);
  build::check_inertias(sc.route, order, m.pulleys, sc.drive, b.mass / b.rigid_length);
  build::check_sde_values(b, bd);
  const build::TensionAtRest tension = build::tension_at_rest(bd, sc.route.length, b);
  build::check_sag(sc.route, d, tension);
  m.contact = build::element_contact(d, b.pitch);
  m.friction = d.friction;
  m.gravity = d.gravity;
  m.track_energy = d.track_energy;

  const std::vector<double> p0 = build::penetrations(order, m.contact, b.pitch, tension.tension, d);
  sc.penetration.assign(m.n_p(), 0.0);
  for (size_t k = 0; k < p0.size(); ++k) sc.penetration[order.pulleys[k]] = p0[k];
  const Route path = build::centre_path(order, p0, bd.loop_sense);
  const double gap = build::close_loop(path, n, bd, tension, b, watch);
  std::vector<double> s;
  build::walk(path, n, 0.5 * b.rigid_length, gap, &s);
  build::set_segment_laws(m, d, s);  // before the state is sized: a LuGre segment adds deflections

  sc.y0 = build::place(m, path, s);
  build::set_arm_angles(m, sc.y0);
  sc.sites = build::element_sites(path, order.names, sc.y0, s);
  sc.drive.mu = build::element_mu(bd, sc.sites);
  build::set_start_speeds(m, sc.drive, sc.y0);

  const std::string lost = build::settle(sc, bd, tension.rest > 0, watch);
  build::check_finite(sc, d, tension.tension);
  build::check_static_state(sc, d, lost, tension.tension);
  build::balance_arms(sc);
  // spray zones: those spraying at t = 0 wet the elements inside them
  if (!d.spray.empty()) {
    Spray& sp = sc.drive.spray;
    sp.zones = d.spray;
    sp.el.assign(static_cast<size_t>(n), ElementSpray{});
    spray_switch(sp, 0.0);
    spray_update(sp, n, 0.0, sc.y0.data(), sc.y0.data() + m.n_coord());
  }
  build::start_couplings(m, sc.y0);
  return sc;
}
}  // namespace

Scene build_scene(const SceneDef& d, const std::atomic<bool>* stop) {
  BuildWatch watch;
  watch.stop = stop;
  return build_scene(d, watch);
}

Scene build_scene(const SceneDef& d, BuildWatch& watch) {
  validate(d);
  watch.elements = d.belt.elements;
  for (const PulleyDef& p : d.pulleys) build::validate_tensioner(p), build::validate_coupling(p);
  const std::optional<double> preload = build::tensioner_preload(d);
  if (!preload) return build_at(d, watch);
  // the preload sets the belt's tension: the belt's moment about the pivot is proportional to it
  // (to a part in 1e3 over a doubling: the wrap angle changes little), so the ratio converges in a
  // few builds
  int arm = -1;
  for (size_t j = 0; j < d.pulleys.size(); ++j)
    if (d.pulleys[j].tensioner && d.pulleys[j].tensioner->sets_tension()) arm = static_cast<int>(j);
  SceneDef e = d;
  constexpr double kAgree = 1e-6;  // relative: far below the static state's own residual tension error
  for (int it = 0;; ++it) {
    Scene sc = build_at(e, watch);
    if (it == 0) build::check_angle0_side(sc, d, arm);
    ContactRecords contacts;
    fill_contacts(sc.model, sc.drive, 0.0, sc.y0.data(), contacts);
    const double Mb = std::abs(build::arm_belt_moment(sc, contacts, sc.model.pulleys[arm].arm));
    if (std::abs(Mb - *preload) <= kAgree * *preload || it == 8) return sc;
    e.belt.pretension *= *preload / Mb;
  }
}

}  // namespace beltsim
