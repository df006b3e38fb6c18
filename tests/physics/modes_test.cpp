// Modes of a drive (sim/modes.hpp, docs/modes.md) against known answers: a span's transverse
// modes against the string at rest and against the axially moving string (Wickert & Mote) at
// speed, the two pulleys' torsional mode against two inertias joined by the spans, and the
// tensioner arm's mode against its spring, the belt's stiffness and its inertia.
#include "sim/modes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numeric>

#include "model/forces.hpp"
#include "physics/helpers.hpp"
#include "support/presets.hpp"
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

  ModeSettings instant;  // (a belt set running on held pulleys is not a steady motion: see below)
  instant.floquet = false;
  for (const double v : {0.4 * c, -0.4 * c}) {  // either way round the ring
    const Eigen::VectorXd y = testing::rigid_motion(sc, v);
    const ModeAnalysis av = analyze_modes(sc, sc.drive, 0.0, y, instant);
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
  // The Floquet analysis (the default at speed) runs the drive over one element passing: the belt
  // of the rest state set running on held pulleys does not repeat its motion (measured: 27 % of a
  // pitch, 52 % of its speed; a steady drive 0.3 % and 0.06 %), and the analysis says so
  const ModeAnalysis af = analyze_modes(sc, sc.drive, 0.0, testing::rigid_motion(sc, 0.4 * c));
  EXPECT_GT(af.period, 0);
  EXPECT_GT(af.velocity_defect, kSteadyVelocity);
  EXPECT_GT(af.position_defect, kSteadyPosition);
}

// 1b. A RUNNING drive in its steady state: the driver held at v = 0.4·c (c² = T/ρ at the
// pretension; a cosine ramp over 0.1 s, then 0.1 s at speed), the driven pulley free (no load: no
// slip arcs, both spans at one tension: steady). Wickert & Mote, f_k = k·(c² − v²)/(2L·c), is the
// fixed string's k·c/(2L) times 1 − v²/c². The fixed string of the running state itself (its span
// tension T and its span ends) is J's own first span mode (the material frame, transport = false:
// the belt's points held, checked against the string in 1.), so f(v) = f_material·(1 − v²/c²) with
// c² = T/ρ from the running spans' measured tension, v the belt speed.
// Measured (120 elements, 28.86 m/s, T 497.8 N): the Floquet modes of the motion over one passing
// (the default at speed, sim/floquet.hpp) give 103.85 Hz against 121.95·0.8393 = 102.36 Hz (+1.5 %;
// the state's Jacobian with the transport term gave +0.5 %, and +0.8 % 0.12 ms later). The expected
// value rests on the material frame at one instant, whose span ends move by up to a pitch (2.6 % of
// the span) over a passing; bound 2 %. The material frame's own 121.95 Hz is 19 % off.
// With 60 elements: +2.3 %, the spans' tensions 467/474 N (not yet steady at 0.2 s). The running
// span is longer than at rest: 121.85 Hz at 497 N is c/(2·0.295 m), where at rest 126.16 Hz is
// c/(2·0.286 m) (L = 0.290 m between the tangent points; the lighter contact lets the belt leave
// the pulleys earlier). The spans' tensions are equal within 1 % (the free pulley carries no
// torque; 0.1 s after the ramp its torsional ring has decayed).
SceneDef running_string(int elements, double v) {
  SceneDef d = held_string();
  d.belt.elements = elements;
  d.pulleys[0].speed.ramps.push_back({.t0 = 0, .t1 = 0.1, .from = 0, .to = -v / 0.1, .cosine = true});
  d.pulleys[1].kinematic = false;  // free, no torque
  return d;
}

TEST(Modes, RunningSpanFollowsWickertMote) {
  test::expect_warnings({WarningKind::failed_step});
  const int elements = 120;
  const double c0 = std::sqrt(500 / kRho), v = 0.4 * c0, t0 = 0.2;
  const Scene sc = build_scene(running_string(elements, v));
  const auto r = testing::simulate(sc.model, sc.drive, sc.y0, t0, t0, "esdirk32", 1e-6);
  const Eigen::VectorXd& y = r.y.back();
  const ModeAnalysis a = analyze_modes(sc, sc.drive, t0, y);
  ModeSettings frozen;
  frozen.transport = false;
  const ModeAnalysis am = analyze_modes(sc, sc.drive, t0, y, frozen);
  const double T0 = mean_span_tension(sc, sc.drive, t0, y, 0), T1 = mean_span_tension(sc, sc.drive, t0, y, 1);
  const double T = 0.5 * (T0 + T1), c = std::sqrt(T / kRho), vb = a.belt_speed;
  const std::vector<double> fm = span_modes(am), fv = span_modes(a);
  ASSERT_GE(fm.size(), 1u);
  ASSERT_GE(fv.size(), 1u);
  const double expected = fm[0] * (1 - vb * vb / (c * c));
  std::printf(
      "running %d elements: v %.3f m/s, T %.2f/%.2f N, f1 %.3f Hz, material frame %.3f Hz (c/2L' with L' "
      "%.4f m): expected %.3f Hz (%+.2f %%)\n",
      elements, vb, T0, T1, fv[0], fm[0], c / (2 * fm[0]), expected, 100 * (fv[0] / expected - 1));
  EXPECT_NEAR(std::abs(vb), v, 0.01 * v);
  EXPECT_NEAR(T0, T1, 0.01 * T);
  EXPECT_NEAR(fv[0], expected, 0.02 * expected);
  // the motion is steady: it repeats itself over the passing (measured 0.25 % of a pitch, 0.25 %
  // of the speed)
  EXPECT_GT(a.period, 0);
  EXPECT_LT(a.position_defect, kSteadyPosition);
  EXPECT_LT(a.velocity_defect, kSteadyVelocity);
}

// 1c. A span mode above half the passing rate. The Floquet multiplier μ = e^{λT} gives the
// frequency only up to multiples of ν (sim/floquet.hpp); the phase the mode turns through over the
// passing decides which. The same string drive running slowly, v = 3 m/s on 60 elements: ν =
// v/pitch = 150 1/s, so the first span mode (near the fixed string's 126 Hz at rest; v²/c² =
// 0.002) lies above ν/2 = 75 Hz, where its multiplier alone would put it at ν − f ≈ 30 Hz. It must
// come out as the material frame's own first span mode (the belt's points held, checked against
// the string in 1.; its mean over a passing, as the span's ends move by a pitch) times 1 − v²/c².
// Measured: 119.22 Hz against 118.13 Hz (+0.9 %); bound 2 % (1b.).
TEST(Modes, ASpanModeAboveHalfThePassingRateIsNotAliased) {
  test::expect_warnings({WarningKind::failed_step});
  const double v = 3, t0 = 0.2;
  const Scene sc = build_scene(running_string(60, v));
  const auto r = testing::simulate(sc.model, sc.drive, sc.y0, t0, t0, "esdirk32", 1e-6);
  const Eigen::VectorXd& y = r.y.back();
  ModeSettings s;
  s.f_max = 500;
  const ModeAnalysis a = analyze_modes(sc, sc.drive, t0, y, s);
  ASSERT_GT(a.period, 0);
  // the first span mode above half the fixed string's fundamental c/2L at this tension: the
  // material frame's analysis can also list a near-rigid motion of the belt as a span mode (1.0 Hz
  // at one instant of the passing when the run reached t0 in two legs)
  const double T = 0.5 * (mean_span_tension(sc, sc.drive, t0, y, 0) + mean_span_tension(sc, sc.drive, t0, y, 1));
  const double c = std::sqrt(T / kRho), lowest = 0.5 * c / (2 * 0.29);
  const auto first_above = [&](const ModeAnalysis& m) {
    for (const double f : span_modes(m))
      if (f > lowest) return f;
    return 0.0;
  };
  const double f1 = first_above(a);
  ASSERT_GT(f1, 0);
  // the material frame's first span mode, the mean over eight instants of one passing (it moves by
  // some 5 % over a passing as the span's ends do)
  s.transport = false;
  const auto over = testing::simulate(sc.model, sc.drive, sc.y0, t0 + a.period, a.period / 8, "esdirk32", 1e-6);
  double fm = 0;
  int instants = 0;
  for (size_t k = 0; k < over.t.size() && instants < 8; ++k) {
    if (over.t[k] < t0) continue;
    const double f = first_above(analyze_modes(sc, sc.drive, over.t[k], over.y[k], s));
    ASSERT_GT(f, 0);
    fm += f, ++instants;
  }
  ASSERT_EQ(instants, 8);
  fm /= instants;
  const double expected = fm * (1 - a.belt_speed * a.belt_speed / (c * c));
  std::printf("slow string: v %.3f m/s, passing rate %.1f 1/s, f1 %.3f Hz against %.3f Hz (%+.2f %%)\n", a.belt_speed,
              1 / a.period, f1, expected, 100 * (f1 / expected - 1));
  EXPECT_GT(f1, 0.5 / a.period);  // above ν/2: turned through more than half a turn a passing
  EXPECT_NEAR(f1, expected, 0.02 * expected);
}

// the paper's dry drive with both pulleys free, no gravity, a belt of EI 1e-6 (the spans'
// transverse modes, 126 Hz, then stay apart from the torsional one) and no bending damper
Scene torsion_scene() {
  SceneDef d = presets::paper_dry();  // both pulleys free
  d.gravity = 0;
  d.belt.EI = 1e-6;
  d.belt.bending_damping = 0;
  return build_scene(d);
}

// the first of its modes in which the two pulleys take part for more than 0.8 (null: none)
const Mode* torsional_mode(const ModeAnalysis& a) {
  const auto group = [&](const char* name) {
    return static_cast<int>(std::find(a.groups.begin(), a.groups.end(), name) - a.groups.begin());
  };
  const int driver = group("pulley_driver"), driven = group("pulley_driven");
  for (const Mode& md : a.modes)
    if (md.participation[driver] + md.participation[driven] > 0.8) return &md;
  return nullptr;
}

// 2. The two free pulleys of the paper's drive at rest (J = 0.025 kg·m² each, r = 0.1 m) turn
// against each other on the two spans, each a spring EA/L: K = 2·r²·EA/L, ω² = K·(1/J1 + 1/J2).
// The belt adds to each pulley's inertia its wrap (ρ·π·r·r²) and a third of each half span's mass
// (a linear velocity profile with the node at mid-span): 1.6 %. The spans' springs reach from the
// last stuck element on one pulley to the first on the other, between L (the tangent points) and
// L + l (half a pitch onto each wrap): the lumped model's frequency lies between the two.
// (Measured: 140.6 Hz, between 139.9 and 144.6 Hz.)
TEST(Modes, TwoPulleyTorsionalModeIsTheLumpedModel) {
  const Scene sc = torsion_scene();
  const ModeAnalysis a = analyze_modes(sc, sc.drive, 0.0, sc.y0);
  const Mode* torsion = torsional_mode(a);
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

// 2b. The change of tension a mode makes, as its pictures colour the belt (mode_tension_change):
// the two pulleys of 2. turning against each other stretch one span and slacken the other, alike
// along each span (measured: +0.877 to +0.881 and −0.877 to −0.881 of the largest change, which is
// on the wraps; bounds: each span's elements within 0.02 of its mean, the means opposite and above
// 0.5). The pictures coloured the deflected state's own tension: at the deflection drawn, 3 % of
// the layout, it alternated element by element past both ends of the run's bar.
TEST(Modes, TorsionalModeStretchesOneSpanAndSlackensTheOther) {
  const Scene sc = torsion_scene();
  const ModeAnalysis a = analyze_modes(sc, sc.drive, 0.0, sc.y0);
  const Mode* torsion = torsional_mode(a);
  ASSERT_NE(torsion, nullptr);
  const std::vector<std::complex<double>> c = mode_tension_change(sc, sc.drive, 0.0, sc.y0, *torsion);
  ASSERT_EQ(c.size(), static_cast<size_t>(sc.model.n_el()));
  double largest = 0;
  for (const auto& ck : c) largest = std::max(largest, std::abs(ck));
  EXPECT_NEAR(largest, 1, 1e-12);
  // each span's elements (those on no pulley), at the phase drawn (0)
  std::vector<std::string> names;
  const std::vector<int> group = coordinate_groups(sc, sc.drive, 0.0, sc.y0, names);
  double mean[2];
  for (int span = 0; span < 2; ++span) {
    std::vector<double> v;
    for (int i = 0; i < sc.model.n_el(); ++i)
      if (group[3 * i] == span) v.push_back(c[i].real());
    ASSERT_GE(v.size(), 5u) << names[span];
    mean[span] = std::accumulate(v.begin(), v.end(), 0.0) / v.size();
    for (double x : v) EXPECT_NEAR(x, mean[span], 0.02) << names[span];
    EXPECT_GT(std::abs(mean[span]), 0.5) << names[span];
  }
  EXPECT_LT(mean[0] * mean[1], 0);
}

// 3. The tensioner arm of the automotive drive (presets::automotive_tensioner, J about the pivot,
// k = 30 N·m/rad) at rest, without its pivot friction (at rest its tanh law is a damper of T_f/w_f
// that holds the arm: the linearization of dry friction at zero speed has no arm mode).
//   a. Against the same model in time: the arm kicked (0.01 rad/s) and its angle followed, the
//      period between upward crossings of its rest angle over the first three cycles (measured
//      54.07, 53.92, 54.54 Hz, the later ones drift as the kick's other modes decay) against the
//      eigenvalue's 53.70 Hz: bound 2 %. The spring alone would give 27.6 Hz: on this drive the
//      belt (the change of its length round the route with the arm's angle, against its tension
//      and its EA) adds about 84 N·m/rad to the spring's 30.
//   b. Against its spring and inertia: with a spring 100 times stiffer (3000 N·m/rad) the belt's
//      84 N·m/rad are 2.8 % of the stiffness (+1.4 % in f), less the belt's and pulleys' inertia
//      moving with the arm: measured 273.85 Hz against sqrt(k/J)/2π = 275.66 Hz (−0.66 %); bound 2 %.
// Without balancing the matrix (ModeSettings::balance) the eigensolver gave 30.2, 75.4 and 141 Hz
// "arm" modes here: the stiffnesses span 10 decades.
SceneDef free_arm(double stiffness) {
  SceneDef d = presets::automotive_tensioner();
  d.pulleys[1].tensioner->friction_torque = 0;
  d.pulleys[1].tensioner->stiffness = stiffness;
  for (PulleyDef& p : d.pulleys) p.torque = TimeSpeedLaw{}, p.speed = TimeSpeedLaw{};
  return d;
}

const Mode& arm_mode(const ModeAnalysis& a) {
  const int arm = static_cast<int>(std::find(a.groups.begin(), a.groups.end(), "arm_tensioner") - a.groups.begin());
  const Mode* mode = &a.modes.at(0);
  for (const Mode& md : a.modes)
    if (md.participation[arm] > mode->participation[arm]) mode = &md;
  return *mode;
}

TEST(Modes, TensionerArmModeIsTheArmInTimeAndItsSpring) {
  const Scene sc = build_scene(free_arm(30));
  const Model& m = sc.model;
  const ModeAnalysis at_rest = analyze_modes(sc, sc.drive, 0.0, sc.y0);
  const Mode& mode = arm_mode(at_rest);
  Eigen::VectorXd y = sc.y0;
  y[m.n_coord() + m.arm_coord(0)] = 0.01;
  const auto r = testing::simulate(m, sc.drive, y, 0.08, 2e-5, "esdirk32", 1e-8);
  const double psi0 = sc.y0[m.arm_coord(0)];
  std::vector<double> up;  // the upward crossings of the rest angle, interpolated
  for (size_t k = 1; k < r.y.size(); ++k) {
    const double a = r.y[k - 1][m.arm_coord(0)] - psi0, b = r.y[k][m.arm_coord(0)] - psi0;
    if (a < 0 && b >= 0) up.push_back(r.t[k - 1] + (r.t[k] - r.t[k - 1]) * (-a) / (b - a));
  }
  ASSERT_GE(up.size(), 4u);
  for (size_t k = 1; k < 4; ++k) {
    std::printf("arm: eigenvalue %.3f Hz, period %zu in time %.3f Hz\n", mode.frequency, k, 1 / (up[k] - up[k - 1]));
    EXPECT_NEAR(1 / (up[k] - up[k - 1]), mode.frequency, 0.02 * mode.frequency);
  }
  const Arm& arm = m.arms[0];
  const Scene stiff = build_scene(free_arm(3000));
  const ModeAnalysis as = analyze_modes(stiff, stiff.drive, 0.0, stiff.y0);
  const Mode& spring = arm_mode(as);
  const double expected = std::sqrt(3000 / arm.inertia) / (2 * M_PI);
  std::printf("stiff arm: %.2f Hz (zeta %.3f) against sqrt(k/J)/2pi %.2f Hz\n", spring.frequency, spring.damping,
              expected);
  EXPECT_NEAR(spring.frequency, expected, 0.02 * expected);
}

// The table's "where" column: the groups with at least a fifth of the energy, largest first; a
// mode whose energy no group holds a fifth of says "spread:" and names the two largest, so that
// no row of the table is blank (the serpentine drive's 82 Hz mode was, at 200 elements)
TEST(ModesTable, WhereNamesTheLargeGroupsOrSaysTheEnergyIsSpread) {
  const std::vector<std::string> g{"span_a", "wrap_b", "pulley_c", "arm_d", "span_e", "wrap_f"};
  EXPECT_EQ(where_text(g, {0.1, 0.54, 0.05, 0.21, 0.05, 0.05}), "wrap_b 54 %, arm_d 21 %");
  EXPECT_EQ(where_text(g, {0.2, 0.1, 0.1, 0.2, 0.2, 0.2}), "span_a 20 %, arm_d 20 %, span_e 20 %, wrap_f 20 %");
  EXPECT_EQ(where_text(g, {0.15, 0.18, 0.17, 0.16, 0.19, 0.15}), "spread: span_e 19 %, wrap_b 18 %");
  EXPECT_EQ(where_text({"pulley_c"}, {1.0}), "pulley_c 100 %");
  EXPECT_EQ(where_text({}, {}), "");
}

}  // namespace
}  // namespace beltsim
