// The bending dampers' power estimated before a run (bending_loss.hpp gives the formulas).
#include "scene/bending_loss.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "scene/parameters.hpp"
#include "scene/scene_types.hpp"

namespace beltsim {

std::optional<double> steady_value(const TimeSpeedLaw& law, double omega) {
  if (law.fn) return std::nullopt;
  double v = law.constant + law.per_speed * omega;
  if (!law.value.empty()) v += law.value.back();
  if (!law.omega.empty()) v += interpolate(law.omega, law.omega_value, omega);
  for (const Ramp& r : law.ramps) v += r.to;
  for (const Sine& s : law.sines) v += s.mean;
  return v;
}

namespace {

// one pulley of the route as the estimate sees it
struct WrapSeen {
  int pulley;     // index in the model
  double radius;  // [m] pitch radius
  int sense;      // +1: the belt turns it anticlockwise
};

std::vector<WrapSeen> wraps_of(const Scene& sc) {
  std::vector<WrapSeen> w;
  for (size_t k = 0; k < sc.route_pulleys.size(); ++k)
    w.push_back({sc.route_pulleys[k], sc.route.arcs[k].radius, sc.route.arcs[k].sense});
  return w;
}

// the free pulleys' torques as a force along the belt at belt speed v (> 0 drives it on)
std::optional<double> belt_force(const Scene& sc, const std::vector<WrapSeen>& wraps, double v) {
  double f = 0;
  for (const WrapSeen& w : wraps) {
    const PulleyDrive& p = sc.drive.pulleys[w.pulley];
    if (p.kinematic) continue;
    const std::optional<double> m = steady_value(p.torque, w.sense * v / w.radius);
    if (!m) return std::nullopt;
    f += *m * w.sense / w.radius;
  }
  return f;
}

// the belt's steady speed along its travel (signed): a kinematic pulley's, else the balance of
// the free pulleys' torques; past_fastest (when given) is set when they still drive the belt on
// at kFastestBeltSpeed
std::optional<double> belt_speed(const Scene& sc, const std::vector<WrapSeen>& wraps, bool* past_fastest = nullptr) {
  for (const WrapSeen& w : wraps) {
    const PulleyDrive& p = sc.drive.pulleys[w.pulley];
    if (!p.kinematic) continue;
    const std::optional<double> omega = steady_value(p.speed, 0.0);
    if (omega && *omega != 0 && std::isfinite(*omega)) return *omega * w.radius / w.sense;
  }
  const std::optional<double> f0 = belt_force(sc, wraps, 0.0);
  if (!f0 || *f0 == 0 || !std::isfinite(*f0)) return std::nullopt;
  const double dir = *f0 > 0 ? 1.0 : -1.0;
  double lo = 0, hi = 0.01;
  for (;;) {
    const std::optional<double> f = belt_force(sc, wraps, dir * hi);
    if (!f) return std::nullopt;
    if (*f * dir <= 0) break;
    if (hi >= kFastestBeltSpeed) {  // no balance below it, no speed to speak of
      if (past_fastest) *past_fastest = true;
      return std::nullopt;
    }
    lo = hi, hi = std::min(2 * hi, kFastestBeltSpeed);
  }
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    (*belt_force(sc, wraps, dir * mid) * dir > 0 ? lo : hi) = mid;
  }
  return dir * 0.5 * (lo + hi);
}

// the length over which a bend decays on a span: 1/λ, λ > 0 the root of η·v·λ³ + EI·λ² = T
double bend_length(double eta_v, double EI, double T) {
  auto f = [&](double x) { return (eta_v * x + EI) * x * x - T; };
  double lo = 0, hi = 1;
  while (f(hi) < 0) lo = hi, hi *= 2;
  for (int it = 0; it < 200 && hi - lo > 1e-12 * hi; ++it) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) < 0 ? lo : hi) = mid;
  }
  return 2 / (lo + hi);
}

std::string power_text(double watts) {
  std::ostringstream s;
  s.precision(3);
  if (std::abs(watts) >= 1e3)
    s << watts / 1e3 << " kW";
  else
    s << watts << " W";
  return s.str();
}

}  // namespace

std::optional<double> steady_belt_speed(const Scene& sc) {
  return belt_speed(sc, wraps_of(sc));
}

bool drives_past_fastest(const Scene& sc) {
  bool past = false;
  belt_speed(sc, wraps_of(sc), &past);
  return past;
}

std::optional<BendingLoss> estimate_bending_loss(const Scene& sc) {
  const Belt& b = sc.model.belt;
  const std::vector<WrapSeen> wraps = wraps_of(sc);
  const std::optional<double> v = belt_speed(sc, wraps);
  if (!v || !(sc.static_tension > 0)) return std::nullopt;
  BendingLoss out;
  out.belt_speed = std::abs(*v);
  double in = 0, taken = 0;
  for (const WrapSeen& w : wraps) {
    const PulleyDrive& p = sc.drive.pulleys[w.pulley];
    if (p.kinematic) continue;
    const double omega = w.sense * *v / w.radius;
    const std::optional<double> m = steady_value(p.torque, omega);
    if (!m) continue;  // a law given as code: its power is not known here
    const double power = *m * omega;
    (power > 0 ? in : taken) += std::abs(power);
  }
  out.transmitted = std::max(in, taken);
  if (!(out.transmitted > 0)) return std::nullopt;
  const double p = b.pitch, vv = out.belt_speed * out.belt_speed;
  const double ell = bend_length(b.ct * p * out.belt_speed, b.kt * p, sc.static_tension);
  for (const WrapSeen& w : wraps)
    out.dissipated += 2 * b.ct * vv / (w.radius * w.radius * p) * (p - ell * (1 - std::exp(-p / ell)));
  return out;
}

std::string bending_loss_warning(const Scene& sc) {
  const std::optional<BendingLoss> e = estimate_bending_loss(sc);
  if (!e || !(e->share() > kBendingLossWarn)) return "";
  // the key that sets the bending damping, as the scene's inputs name it, and the belt's preset
  std::string key = "belt.bending_damping", value, preset;
  for (const SceneInput& in : sc.inputs)
    if (in.name == "belt.preset") {
      preset = in.text;
    } else if (in.name == "belt.bending_damping" || in.name == "belt.bending_viscosity" || in.name == "belt.sde.ct") {
      std::ostringstream s;
      s.precision(3);
      const Parameter* par = find_parameter(in.name);
      const bool papers = par && par->fallback && *par->fallback == in.value;
      s << " = " << in.value << " " << in.unit
        << (!in.given ? " (the paper's default)" : papers ? " (the paper's value)" : "");
      key = in.name, value = s.str();
    }
  std::ostringstream m;
  m.precision(3);
  m << key << value << ": the belt's bending dampers will take about " << power_text(e->dissipated)
    << " at the drive's steady speeds (belt " << e->belt_speed << " m/s), " << 100 * e->share() << " % of the "
    << power_text(e->transmitted) << " its pulleys transmit, where a PK belt loses a few per cent in all: ";
  // the preset's own bending loss: the belt is what it is, the drive transmits little (a light load,
  // or a load law the pulley's speed never reaches); advising the preset it uses was no help
  if (!preset.empty() && key == "belt.bending_viscosity")
    m << "the " << preset << " preset's own bending loss on a drive that transmits little; check the pulleys' "
      << "loads (a load table on the other side of zero speed gives none) (docs/belts.md)";
  else
    m << "give the belt's own bending loss, e.g. belt = beltsim.belts[\"6PK\"] (docs/belts.md), or a smaller " << key
      << " (docs/model.md, bending loss)";
  return m.str();
}

}  // namespace beltsim
