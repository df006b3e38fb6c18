// Modes of a drive (sim/modes.hpp, docs/modes.md) against known answers: a span's transverse
// modes against the string at rest and against the axially moving string (Wickert & Mote) at
// speed, the two pulleys' torsional mode against two inertias joined by the spans, and the
// tensioner arm's mode against its spring, the belt's stiffness and its inertia.
#include "sim/modes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "model/forces.hpp"
#include "physics/helpers.hpp"
#include "scene/presets.hpp"
#include "scene/route.hpp"
#include "support/warning_guard.hpp"

namespace beltsim {
namespace {

constexpr double kRho = 0.096;  // the paper's belt [kg/m]

// the lowest modes whose kinetic energy lies mostly (> 60 %) in the spans and that are lightly
// damped (ζ < 0.02: the string's; at speed, the belt on the wraps' slip arcs adds modes damped
// by friction, ζ ≈ 0.03-0.1, that move the spans too)
std::vector<double> span_modes(const ModeAnalysis& a) {
  std::vector<double> f;
  for (const Mode& md : a.modes) {
    double spans = 0;
    for (size_t g = 0; g < a.groups.size(); ++g)
      if (a.groups[g].rfind("span_", 0) == 0) spans += md.participation[g];
    if (spans > 0.6 && md.damping < 0.02) f.push_back(md.frequency);
  }
  return f;
}

// the paper's drive with a flexible belt (EI → 1e-6 N·m², no bending damper: the string) and
// no gravity (straight spans), both pulleys held still
SceneDef held_string() {
  SceneDef d = presets::paper_dry();
  d.gravity = 0;
  d.belt.EI = 1e-6;
  d.belt.bending_damping = 0;
  for (PulleyDef& p : d.pulleys) {
    p.torque = TimeSpeedLaw{};
    p.kinematic = true;
  }
  return d;
}

// the mean axial force of the SDEs joining two elements on the spans [N]
double mean_span_tension(const Scene& sc, const Drive& d, double t, const Eigen::VectorXd& y, int only = -1) {
  std::vector<std::string> names;
  const std::vector<int> g = coordinate_groups(sc, d, t, y, names);
  const Model& m = sc.model;
  const int n = m.n_el(), spans = static_cast<int>(sc.route.spans.size());
  double T = 0;
  int count = 0;
  for (int i = 0; i < n; ++i)
    if (g[3 * i] < spans && g[3 * ((i + 1) % n)] == g[3 * i] && (only < 0 || g[3 * i] == only))
      T += sde_axial_force(m, y.data(), y.data() + m.n_coord(), i), ++count;
  return T / count;
}

// 1. At rest a span is the string: f_k = k·c/(2L), c² = T/ρ. Its ends are where the belt leaves
// the pulleys' contact, within a pitch l of the tangent points (the last stuck element's centre
// sits on the wrap): f_1 between c/(2L) and c/(2(L − l)). The chain of F ≈ 14 elements departs
// from the continuum by (kπ/F)²/24 (0.8 % for k = 2): f_2/f_1 = 2 within 1.5 %.
// Moving, the span is the axially moving string, f_k = k·(c² − v²)/(2L·c): at v = 0.4·c (v²/c² =
// 0.16) the belt of the rest state in rigid motion along its path (sliding over the held pulleys:
// its span tension and its span ends are those of the rest state, so that L and c drop out of f_1(v)/f_1(0) = 1 −
// v²/c²). Measured: 1.2 % above with 60 elements, 0.7 % with 120 (the central difference along the ring, D, on a span
// of F elements); bound 2 %. Without the transport term (the Jacobian alone, the material frame: the belt's points held
// where they are) the frequency stays the fixed string's, 16 % off.
TEST(Modes, SpanFollowsTheAxiallyMovingString) {
  const Scene sc = build_scene(held_string());
  const ModeAnalysis a0 = analyze_modes(sc, sc.drive, 0.0, sc.y0);
  const std::vector<double> f0 = span_modes(a0);
  ASSERT_GE(f0.size(), 3u);
  const double T = mean_span_tension(sc, sc.drive, 0.0, sc.y0), c = std::sqrt(T / kRho);
  const double L = 0.29, l = sc.model.belt.pitch;
  std::printf("rest: T %.1f N, f1 %.3f Hz in [%.3f, %.3f], f2/f1 %.4f\n", T, f0[0], c / (2 * L), c / (2 * (L - l)),
              f0[2] / f0[0]);
  EXPECT_GT(f0[0], c / (2 * L));
  EXPECT_LT(f0[0], c / (2 * (L - l)));
  // f0[0] and f0[1]: the first mode of each span (equal tensions: a pair); f0[2] the second
  EXPECT_NEAR(f0[2] / f0[0], 2.0, 0.015 * 2.0);

  for (const double v : {0.4 * c, -0.4 * c}) {  // either way round the ring
    const Eigen::VectorXd y = testing::rigid_motion(sc, v);
    const ModeAnalysis av = analyze_modes(sc, sc.drive, 0.0, y);
    const std::vector<double> fv = span_modes(av);
    ASSERT_GE(fv.size(), 1u);
    const double expected = 1 - v * v / (c * c);
    std::printf("v %.2f m/s: f1 %.3f Hz, ratio %.4f against %.4f\n", av.belt_speed, fv[0], fv[0] / f0[0], expected);
    EXPECT_NEAR(std::abs(av.belt_speed), std::abs(v), 1e-6 * c);
    EXPECT_NEAR(fv[0] / f0[0], expected, 0.02 * expected);
    ModeSettings frozen;
    frozen.transport = false;
    const std::vector<double> ff = span_modes(analyze_modes(sc, sc.drive, 0.0, y, frozen));
    ASSERT_GE(ff.size(), 1u);
    EXPECT_GT(std::abs(ff[0] / f0[0] - expected), 0.1 * expected) << "material frame: " << ff[0] << " Hz";
  }
}

// 2. The two free pulleys of the paper's drive at rest (J = 0.025 kg·m² each, r = 0.1 m) turn
// against each other on the two spans, each a spring EA/L: K = 2·r²·EA/L, ω² = K·(1/J1 + 1/J2).
// The belt adds to each pulley's inertia its wrap (ρ·π·r·r²) and a third of each half span's mass
// (a linear velocity profile with the node at mid-span): 1.6 %. The spans' springs reach from the
// last stuck element on one pulley to the first on the other, between L (the tangent points) and
// L + l (half a pitch onto each wrap): the lumped model's frequency lies between the two.
// (Measured: 140.6 Hz, between 139.9 and 144.6 Hz.)
TEST(Modes, TwoPulleyTorsionalModeIsTheLumpedModel) {
  SceneDef d = presets::paper_dry();  // both pulleys free
  d.gravity = 0;
  d.belt.EI = 1e-6;  // the spans' transverse modes (126 Hz) then stay apart from the torsional one
  d.belt.bending_damping = 0;
  const Scene sc = build_scene(d);
  const ModeAnalysis a = analyze_modes(sc, sc.drive, 0.0, sc.y0);
  const int driver = static_cast<int>(std::find(a.groups.begin(), a.groups.end(), "pulley_driver") - a.groups.begin());
  const int driven = static_cast<int>(std::find(a.groups.begin(), a.groups.end(), "pulley_driven") - a.groups.begin());
  const Mode* torsion = nullptr;
  for (const Mode& md : a.modes)
    if (md.participation[driver] + md.participation[driven] > 0.8) {
      torsion = &md;
      break;
    }
  ASSERT_NE(torsion, nullptr);
  const double r = 0.1, J = 0.025, EA = 1.52e5, L = 0.29, l = sc.model.belt.pitch;
  const double Je = J + kRho * M_PI * r * r * r + 2 * (kRho * L / 2) / 3 * r * r;
  auto lumped = [&](double span) { return std::sqrt(2 * r * r * EA / span * 2 / Je) / (2 * M_PI); };
  std::printf("torsional %.3f Hz (zeta %.4f) between %.3f and %.3f Hz\n", torsion->frequency, torsion->damping,
              lumped(L + l), lumped(L));
  EXPECT_GT(torsion->frequency, lumped(L + l));
  EXPECT_LT(torsion->frequency, lumped(L));
  // the pulleys turn against each other: opposite phases, equal amplitudes (equal inertias)
  const std::complex<double> a1 = torsion->shape[sc.model.pulley_coord(0)],
                             a2 = torsion->shape[sc.model.pulley_coord(1)];
  EXPECT_LT(std::real(a1 * std::conj(a2)), 0);
  EXPECT_NEAR(std::abs(a1), std::abs(a2), 0.05 * std::abs(a1));
}

// 3. The tensioner arm of the automotive drive (J = 1e-3 kg·m² about the pivot, k = 30 N·m/rad)
// turns on its spring and on the belt: the belt's length ℓ(ψ) round the route changes with the arm's
// angle ψ, so the tension T adds T·ℓ'' and the belt's stretch EA·ℓ'²/L_s, L_s the length of belt
// that takes it: K = k + T·ℓ'' + EA·ℓ'²/L_s, ω² = K/J. ℓ(ψ) from the route (scene/route.hpp) by
// central differences. L_s lies between the belt on either side of the idler up to the next
// pulleys (their inertia holds the belt there) and the whole belt less the crankshaft's wrap (the
// crankshaft is held, the others turn freely): the mode lies between the two. (Measured: 70.3 Hz,
// ζ 0.12, between 67.5 and 106.9 Hz; the spring alone would give 35.7 Hz.)
TEST(Modes, TensionerArmModeIsItsSpringAndTheBelt) {
  // without the pivot's friction: at rest its tanh law is a damper of T_f/w_f that holds the arm
  // (the linearization of dry friction at zero speed: the mode is overdamped, there is none)
  SceneDef d = presets::automotive_tensioner();
  d.pulleys[1].tensioner->friction_torque = 0;
  const Scene sc = build_scene(d);
  const Model& m = sc.model;
  const ModeAnalysis a = analyze_modes(sc, sc.drive, 0.0, sc.y0);
  const int arm = static_cast<int>(std::find(a.groups.begin(), a.groups.end(), "arm_tensioner") - a.groups.begin());
  ASSERT_LT(arm, static_cast<int>(a.groups.size()));
  const Mode* mode = nullptr;
  for (const Mode& md : a.modes)
    if (!mode || md.participation[arm] > mode->participation[arm]) mode = &md;
  ASSERT_NE(mode, nullptr);
  const Arm& ar = m.arms[0];
  const double psi = sc.y0[m.arm_coord(0)];
  auto length = [&](double at) {
    std::vector<RouteCircle> c;
    for (size_t k = 0; k < sc.route_pulleys.size(); ++k) {
      const int j = sc.route_pulleys[k];
      const Vec2 centre =
          m.pulleys[j].arm < 0 ? m.pulleys[j].centre : ar.pivot + ar.length * Vec2(std::cos(at), std::sin(at));
      c.push_back({centre, m.pulleys[j].radius, sc.route.arcs[k].sense});
    }
    return make_route(c, -1, sc.route_names).length;
  };
  const double h = 1e-4;
  const double d1 = (length(psi + h) - length(psi - h)) / (2 * h);
  const double d2 = (length(psi + h) - 2 * length(psi) + length(psi - h)) / (h * h);
  const double T = sc.static_tension, EA = m.belt.k * m.belt.rigid_length;
  // the idler's route entry k: its two spans and its wrap; the whole belt less the crankshaft's wrap
  size_t k = 0;
  while (sc.route_pulleys[k] != ar.pulley) ++k;
  const size_t nk = sc.route.spans.size();
  const double near = sc.route.spans[(k + nk - 1) % nk].length + sc.route.arcs[k].length() + sc.route.spans[k].length;
  const double whole = sc.route.length - sc.route.arcs[0].length();
  auto f = [&](double Ls) { return std::sqrt((ar.stiffness + T * d2 + EA * d1 * d1 / Ls) / ar.inertia) / (2 * M_PI); };
  std::printf("arm mode %.3f Hz (zeta %.3f, share %.2f); spring alone %.3f Hz; lumped %.3f to %.3f Hz\n",
              mode->frequency, mode->damping, mode->participation[arm], f(INFINITY), f(whole), f(near));
  EXPECT_GT(mode->participation[arm], 0.5);
  EXPECT_GT(mode->frequency, f(whole));
  EXPECT_LT(mode->frequency, f(near));
}

}  // namespace
}  // namespace beltsim
