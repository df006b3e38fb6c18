// The scene build's checks (scene/build.hpp): the wraps' element counts, the pulleys' inertias
// against the belt on them, the per-SDE values, the spans' sag and the static state the build
// found. Each rejects with the key the scene gave, its value and what to give instead
// (docs/model.md, Limits the scene build enforces).
#include <cmath>
#include <optional>
#include <tuple>

#include "io/number_text.hpp"
#include "scene/build.hpp"
#include "scene/parameters.hpp"
#include "scene/scene.hpp"
#include "scene/validate.hpp"

namespace beltsim {

namespace build {

void check_wraps(const Route& route, const std::vector<std::string>& names, int elements) {
  const double pitch = route.length / elements;
  for (size_t k = 0; k < route.arcs.size(); ++k) {
    const double on_wrap = route.arcs[k].length() / pitch;
    if (on_wrap < 3.0) {
      throw ParameterError("belt.elements", "too few elements for the wrap on pulley '" + names[k] + "' (" +
                                                rounded_text(route.arcs[k].angle * 180 / M_PI, 6) + " deg holds " +
                                                rounded_text(on_wrap, 6) + " elements, at least 3 needed; got " +
                                                std::to_string(elements) + " elements)");
    }
  }
}

// A free pulley much lighter than the belt on it follows the belt's speed within a time far below
// any step the error test accepts, and the embedded error estimate misses that fast mode: the
// paper's driven pulley at a tenth of a percent of the belt's inertia on it ended at a wrong speed
// at rtol 1e-3 without a word (docs/model.md, light pulleys). A kinematic pulley has no such mode.
void check_speeds(const std::vector<Pulley>& pulleys, const Drive& dr) {
  for (size_t j = 0; j < pulleys.size(); ++j) {
    if (!dr.pulleys[j].kinematic) continue;
    const std::optional<double> peak = peak_speed(dr.pulleys[j].speed);
    if (peak && std::abs(*peak) > kPulleySpeedMax)
      throw ParameterError("pulley '" + pulleys[j].name + "'.speed",
                           rounded_text(*peak, 6) + " rad/s once its ramps and tables have ended, beyond the " +
                               rounded_text(kPulleySpeedMax, 6) +
                               " rad/s at which every run stops (no belt drive turns so fast); speeds are in rad/s: " +
                               "beltsim.rpm(n) converts from rpm");
  }
}

void check_inertias(const Route& route, const RouteOrder& order, const std::vector<Pulley>& pulleys, const Drive& dr,
                    double mass_per_length) {
  for (size_t k = 0; k < route.arcs.size(); ++k) {
    const int j = order.pulleys[k];
    if (dr.kinematic(j)) continue;
    const double r = route.arcs[k].radius;
    const double on_wrap = mass_per_length * route.arcs[k].length() * r * r;  // [kg·m²]
    if (pulleys[j].inertia < kWrapInertiaMin * on_wrap) {
      throw ParameterError(
          "pulley '" + order.names[k] + "'.inertia",
          rounded_text(pulleys[j].inertia, 3) + " kg·m² is below 1 % of the belt's inertia on its wrap (" +
              rounded_text(on_wrap, 3) + " kg·m²: " + rounded_text(mass_per_length * route.arcs[k].length(), 3) +
              " kg at r = " + rounded_text(r, 3) +
              " m); the step-size control cannot follow so light a pulley and its speed comes out wrong: give at "
              "least " +
              rounded_text(kWrapInertiaMin * on_wrap, 3) + " kg·m² (docs/model.md, light pulleys)");
    }
  }
}

void check_sde_values(const Belt& b, const BeltDef& bd) {
  // per-SDE values that overflow (EA = 1e308 over a pitch of centimetres) make every force NaN
  // named by the key the scene gave (its unit from the parameter table)
  const bool rigid = bd.reading == StiffnessReading::rigidity;
  for (const auto& [key, sde_key, per_sde, v, given] :
       {std::tuple{rigid ? "belt.EA" : "belt.sde.k", "belt.sde.k", " (per SDE: EA / l0)", b.k, rigid ? bd.EA : bd.k},
        std::tuple{rigid ? "belt.EI" : "belt.sde.kt", "belt.sde.kt", " (per SDE: EI / l0)", b.kt,
                   rigid ? bd.EI : bd.kt},
        std::tuple{rigid ? "belt.axial_damping" : "belt.sde.c", "belt.sde.c", " (per SDE: axial_damping / l0)", b.c,
                   rigid ? bd.axial_damping : bd.c}})
    if (!std::isfinite(v) || v > 1e15) {
      const std::string sde_unit(find_parameter(sde_key)->unit);
      // the per-SDE value and, read as a rigidity, the largest the belt's element length allows
      // (a user's trial: the bound was given per SDE, the value per belt, and neither per the other)
      std::string why = "is beyond what double precision integrates (> 1e15 per SDE";
      if (rigid && std::isfinite(v)) why += ": " + rounded_text(v, 4) + " " + sde_unit + " here";
      const std::string unit(find_parameter(key)->unit);
      if (rigid && std::isfinite(v) && v > 0)
        why += "; at most " + rounded_text(1e15 * (given / v), 3) + " " + unit + " at this element length";
      reject(std::string(key) + (rigid ? per_sde : ""), why + ")", given, unit);
    }
}

void check_sag(const Route& route, const SceneDef& d, const TensionAtRest& t) {
  // The static start holds straight spans at the tension at rest: a belt whose weight over its
  // longest span passes that tension (ρ·|g|·L > T: a sag above L/8, δ = ρgL²/8T) hangs instead
  // (on the paper's drive from gravity = 1.8e4 m/s²; at 1e4 the spans already carry 554 N, not 500)
  const BeltDef& bd = d.belt;
  double longest = 0;
  for (const Route::Span& sp : route.spans) longest = std::max(longest, sp.length);
  const double weight = bd.mass_per_length * std::abs(d.gravity) * longest;
  if (weight <= t.tension) return;
  const std::string over = "the belt's weight over its longest span (ρ·g·L = " + rounded_text(weight, 6) +
                           " N: " + rounded_text(bd.mass_per_length, 6) + " kg/m over " + rounded_text(longest, 6) +
                           " m at g = " + rounded_text(d.gravity, 6) + " m/s²)";
  constexpr double kEarth = 9.81;                            // [m/s²]
  if (bd.mass_per_length * kEarth * longest <= t.tension) {  // a tension that holds it on Earth: gravity's fault
    reject("gravity",
           "makes the belt's weight over its longest span (ρ·g·L = " + rounded_text(weight, 6) + " N over " +
               rounded_text(longest, 6) + " m) larger than its tension at rest (" + rounded_text(t.tension, 6) +
               " N): the belt would hang rather than span its pulleys; lower gravity or belt.mass_per_length, or "
               "tension the belt more",
           d.gravity);
  }
  const std::string hang = ": the belt would hang rather than span its pulleys; ";
  for (const PulleyDef& p : d.pulleys) {
    if (!p.tensioner || !p.tensioner->sets_tension()) continue;
    const bool preload = p.tensioner->preload.has_value();
    reject("pulley '" + p.name + "'.tensioner." + (preload ? "preload" : "angle0"),
           "gives the belt a tension at rest of " + rounded_text(t.tension, 6) + " N, less than " + over + hang +
               (preload ? "raise the preload (in N·m)" : "move the free angle further from the installed one (in rad)"),
           preload ? *p.tensioner->preload : *p.tensioner->angle0, preload ? "N·m" : "rad");
  }
  const std::string key = t.key;
  if (key == "belt.pretension") {
    // (a value below 10 may be kilonewtons: a belt is mounted at some hundreds of N)
    const std::string kn =
        t.value < 10 ? rounded_text(t.value, 6) + " kN would be " + rounded_text(1000 * t.value, 6) + " N; " : "";
    reject(key,
           "is less than " + over + hang + "the pretension is in N (" + kn + "the paper's belt is mounted at 500 N)",
           t.value);
  }
  reject(key,
         "gives the spans a tension at rest of " + rounded_text(t.tension, 6) + " N, less than " + over + hang +
             (key == "belt.strain" ? "raise it (strain is a fraction: 0.005 = 0.5 %)"
                                   : "shorten it (the route is " + rounded_text(route.length, 6) + " m)"),
         t.value);
}

void check_static_state(const Scene& sc, const SceneDef& d, const std::string& lost, double tension) {
  const bool converged = sc.static_residual < kStaticConverged;
  if (lost.empty() && converged) return;
  const Model& m = sc.model;
  const Belt& b = m.belt;
  // the belt's SDE: its axial stiffness at the tension at rest (k for e_tra = 1), as the scene gives
  // it (EA over the pitch; the rest length the failed solve left is no measure)
  const double sde_k = d.belt.reading == StiffnessReading::rigidity ? d.belt.EA / b.pitch : d.belt.k;
  const double belt_k = b.e_tra * tension / std::pow(tension / sde_k, 1.0 / b.e_tra);
  // the stiffest contact on a wrap: dN/dp = 2·c1·p0 + c2 per element at the static penetration
  double contact_k = 0, c1_share = 0;
  std::string on;
  for (size_t k = 0; k < sc.route_pulleys.size(); ++k) {
    const double p0 = sc.penetration[sc.route_pulleys[k]];
    if (2 * m.contact.c1 * p0 + m.contact.c2 > contact_k)
      contact_k = 2 * m.contact.c1 * p0 + m.contact.c2, c1_share = 2 * m.contact.c1 * p0, on = sc.route_names[k];
  }
  const std::string what = lost.empty()
                               ? "the iteration stopped " + rounded_text(sc.static_residual, 3) +
                                     " m/s² from equilibrium, the spans at " + rounded_text(sc.static_tension, 6) + " N"
                               : "the iteration left pulley '" + lost + "' untouched";
  if (contact_k > kStiffContact * belt_k) {
    // the contact's term that makes it so stiff, as the scene gave it (per element or per length)
    const bool c1 = c1_share > contact_k - c1_share;
    const bool per_length = c1 ? d.contact_per_length.c1.has_value() : d.contact_per_length.c2.has_value();
    const std::string key = std::string("contact.") + (c1 ? "c1" : "c2") + (per_length ? "_per_length" : "");
    const double value = c1 ? (per_length ? *d.contact_per_length.c1 : d.contact.c1)
                            : (per_length ? *d.contact_per_length.c2 : d.contact.c2);
    // the paper's contact on this belt, for scale
    Contact paper = m.contact;
    paper.c1 = parameter_default("contact.c1"), paper.c2 = parameter_default("contact.c2");
    const double r = sc.route.arcs[0].radius;
    const double paper_k = 2 * paper.c1 * static_penetration(paper, b.pitch, r, tension) + paper.c2;
    const double most = c1 ? 0 : (per_length ? belt_k / b.pitch : belt_k);
    reject(key,
           "makes the contact " + rounded_text(contact_k / belt_k, 3) +
               " times as stiff as the belt: an element's contact on pulley '" + on + "' is " +
               rounded_text(contact_k, 3) + " N/m at its static penetration (c2 + 2·c1·p0), the belt's SDE " +
               rounded_text(belt_k, 3) + " N/m (EA over the pitch); the belt's static initial state was not found (" +
               what + "). Give a contact softer than the belt" +
               (most > 0 ? ", below " + rounded_text(most, 3) + " " + std::string(find_parameter(key)->unit) + " here"
                         : "") +
               " (the paper's c1 = " + rounded_text(paper.c1, 6) + " N/m², c2 = " + rounded_text(paper.c2, 6) +
               " N/m per element make it " + rounded_text(paper_k / belt_k, 2) +
               " times as stiff; docs/model.md, Limits the scene build enforces)",
           value);
  }
  if (!lost.empty())
    throw ParameterError("belt.elements", "could not find the belt's static initial state with " + std::to_string(b.n) +
                                              " elements (" + what + "); a few elements more or fewer usually works");
}

void check_finite(const Scene& sc, const SceneDef& d, double tension) {
  // parameters far beyond a belt's (each finite, and each within its own rule) can still overflow
  // the static solve
  const Belt& b = sc.model.belt;
  const int n = b.n;
  std::string bad;
  for (Eigen::Index k = 0; k < sc.y0.size() && bad.empty(); ++k)
    if (!std::isfinite(sc.y0[k]))
      bad = (k < 3 * n ? "element " + std::to_string(k / 3) + "'s " + (k % 3 == 2 ? "angle" : "position")
                       : "a pulley's state") +
            " is " + (std::isnan(sc.y0[k]) ? "NaN" : "infinite");
  for (const auto& [name, v] : {std::pair{"the rigid length", b.rigid_length},
                                {"the static tension", sc.static_tension},
                                {"the static residual", sc.static_residual}})
    if (bad.empty() && !std::isfinite(v)) bad = std::string(name) + " is " + (std::isnan(v) ? "NaN" : "infinite");
  if (!bad.empty()) {
    throw ParameterError(
        "scene", "the belt's static initial state is not finite (" + bad +
                     "): the parameters are beyond what double precision resolves (the values that "
                     "scale it: gravity = " +
                     rounded_text(d.gravity, 6) + " m/s², the tension at rest = " + rounded_text(tension, 6) +
                     " N, per-SDE k = " + rounded_text(b.k, 6) + " N/m, contact.c1 = " + rounded_text(d.contact.c1, 6) +
                     " N/m², belt.mass_per_length = " + rounded_text(d.belt.mass_per_length, 6) + " kg/m)");
  }
}

}  // namespace build

}  // namespace beltsim
