// Checks with known answers (docs/testing.md, Known answers), in that order: 1-4, the initial
// state, energy and the waves on a free span (5-6, the belt on its pulleys: known_answers_contact_test.cpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <tuple>

#include <Eigen/Eigenvalues>

#include "model/contacts.hpp"
#include "model/forces.hpp"
#include "model/observables.hpp"
#include "model/rhs.hpp"
#include "physics/helpers.hpp"
#include "support/presets.hpp"
#include "sim/simulation.hpp"
#include "support/warning_guard.hpp"
#include "support/scratch.hpp"

namespace beltsim {
namespace {

using testing::rigid_motion;
using testing::simulate;

// ---- 1. the initial state ----------------------------------------------------------------------
// The static solve is a Newton iteration run to |a| < 1e-9 m/s² or until it stalls at rounding;
// the force scale of an element is T0/m ≈ 2.6e5 m/s², so 1e-6 of it (0.26 m/s²) is a bound that
// only a broken initial state exceeds (the walk alone, without Newton, leaves ≈ 1e3 m/s²).
std::vector<SceneDef> static_cases() {
  std::vector<SceneDef> cases{presets::automotive_wet()};
  for (int n : {60, 70, 80, 100, 120, 140, 150, 240}) {  // 70, 120, 140 need the trust region
    SceneDef d = presets::paper_dry();
    d.belt.elements = n;
    cases.push_back(d);
  }
  return cases;
}

TEST(KnownAnswers, InitialStateIsStatic) {
  // 70, 120 and 140 elements need the static solve's trust-region retry (static_cases)
  test::expect_warnings({WarningKind::static_retry});
  for (const SceneDef& d : static_cases()) {
    const Scene sc = build_scene(d);
    const Model& m = sc.model;
    const Drive& dr = sc.drive;
    Eigen::VectorXd dy(m.n_state());
    rhs(m, dr, 0.0, sc.y0.data(), dy.data());
    const double scale = d.belt.pretension / m.belt.mass;
    EXPECT_LT(dy.segment(m.n_coord(), 3 * m.n_el()).cwiseAbs().maxCoeff(), 1e-6 * scale);
    EXPECT_NEAR(sc.static_tension, d.belt.pretension, 1e-4 * d.belt.pretension);
  }
}

// Hub load of a pulley at rest. Statics of the belt between the midpoints of the spans on either
// side: hub load = F_out - F_in + weight of that belt, F the SDE force vectors (k·d) at the two
// midpoints. This holds whatever the bending stiffness does to the belt's shape; the only error is
// the contact of neighbouring pulleys (none here) and rounding: bound 1e-6 of the load.
TEST(KnownAnswers, HubLoadIsTheSumOfTheSpanTensions) {
  for (const SceneDef& d : {presets::paper_dry(), presets::automotive_wet()}) {
    const Scene sc = build_scene(d);
    const Model& m = sc.model;
    const Drive& dr = sc.drive;
    const int n = m.n_el();
    const size_t np = sc.route_pulleys.size();
    ContactRecords contacts;
    fill_contacts(m, dr, 0.0, sc.y0.data(), contacts);
    for (size_t k = 0; k < np; ++k) {
      Vec2 hub;
      belt_torque(contacts, sc.route_pulleys[k], &hub);
      const int in = span_sde(m, sc.route.spans[(k + np - 1) % np], sc.y0.data());
      const int out = span_sde(m, sc.route.spans[k], sc.y0.data());
      const Vec2 F_in = m.belt.k * sde_gap(m, sc.y0.data(), in), F_out = m.belt.k * sde_gap(m, sc.y0.data(), out);
      const int carried = ((out - in) % n + n) % n;  // elements in, in+1, ..., out-1
      const Vec2 weight(0, -carried * m.belt.mass * m.gravity);
      const Vec2 expected = F_out - F_in + weight;
      EXPECT_LT((hub - expected).norm(), 1e-6 * expected.norm()) << sc.route_names[k];
    }
  }
}

// The flexible-belt textbook's hub load, 2·T0·sin(θ/2), from the inputs alone: on the paper's
// drive (two pulleys of one radius, so each wrap is θ = π, and the pretension T0 = 500 N) that is
// 2·T0 = 1000 N on each. The textbook leaves out the bending stiffness (bending length
// sqrt(EI/T) = 7 mm ≪ r = 0.1 m) and the belt's weight (1.1 N in all): bound 0.5 % (measured
// 0.02 %). Not on the small automotive pulleys, where the bending stiffness turns the spans by
// degrees.
TEST(KnownAnswers, HubLoadOfTheFlexibleBeltTextbook) {
  const SceneDef d = presets::paper_dry();
  const Scene sc = build_scene(d);
  ContactRecords contacts;
  fill_contacts(sc.model, sc.drive, 0.0, sc.y0.data(), contacts);
  ASSERT_EQ(sc.route_pulleys.size(), 2u);
  const double flexible = 2 * d.belt.pretension * std::sin(M_PI / 2);
  for (size_t k = 0; k < 2; ++k) {
    Vec2 hub;
    belt_torque(contacts, sc.route_pulleys[k], &hub);
    EXPECT_NEAR(hub.norm(), flexible, 5e-3 * flexible) << sc.route_names[k];
  }
}

// ---- 2. energy ---------------------------------------------------------------------------------
// Without damping, friction and loads the model is conservative: the total energy of a belt set
// vibrating must stay constant up to the integrator's error. RKF45 at rtol 1e-10 over 2 ms:
// measured drift 1e-9 of the injected kinetic energy; bound 1e-6 of it.
TEST(KnownAnswers, EnergyIsConservedWithoutDissipation) {
  SceneDef d = presets::paper_dry();
  d.belt.axial_damping = 0;
  d.belt.bending_damping = 0;
  d.contact.b = 0;
  d.belt.mu = 0;
  for (PulleyDef& p : d.pulleys) p.torque = TimeSpeedLaw{};
  const Scene sc = build_scene(d);
  const Model& m = sc.model;
  const Drive& dr = sc.drive;
  Eigen::VectorXd y0 = sc.y0;
  const int N = m.n_coord();
  double kick = 0;
  for (int i = 0; i < m.n_el(); ++i) {  // a transverse and longitudinal kick of every element
    y0[N + 3 * i] = 0.05 * std::sin(0.7 * i);
    y0[N + 3 * i + 1] = 0.1 * std::cos(1.3 * i);
    kick += 0.5 * m.belt.mass * (y0[N + 3 * i] * y0[N + 3 * i] + y0[N + 3 * i + 1] * y0[N + 3 * i + 1]);
  }
  const double E0 = energy(m, dr, 0, y0.data()).total();
  const auto s = simulate(m, dr, y0, 2e-3, 2e-4, "rkf45", 1e-10);
  for (size_t k = 0; k < s.t.size(); ++k)
    EXPECT_NEAR(energy(m, dr, s.t[k], s.y[k].data()).total(), E0, 1e-6 * kick) << "t = " << s.t[k];
}

// With everything on, the work of the torques equals the change of mechanical energy plus what
// each dissipation channel took (the channels are integrated with the state). Over the first
// 50 ms of the paper's drive at rtol 1e-7 the balance closes to 1e-6 of the work (measured
// 1e-8); each channel must also be non-negative.
TEST(KnownAnswers, WorkOfTorquesBalancesEnergyAndDissipation) {
  SceneDef d = presets::paper_dry();
  d.track_energy = true;
  const Scene sc = build_scene(d);
  const Model& m = sc.model;
  const Drive& dr = sc.drive;
  const auto s = simulate(m, dr, sc.y0, 0.05, 0.01, "esdirk32", 1e-7);
  const double E0 = energy(m, dr, 0, sc.y0.data()).total();
  const Eigen::VectorXd& y = s.y.back();
  const double* e = y.data() + 2 * m.n_coord();
  const double dE = energy(m, dr, s.t.back(), y.data()).total() - E0;
  double dissipated = 0;
  for (int k = kDissSdeAxial; k < kEnergyCount; ++k) {
    EXPECT_GE(e[k], -1e-12) << "channel " << k;
    dissipated += e[k];
  }
  EXPECT_GT(e[kWorkTorques], 0.0);
  EXPECT_NEAR(e[kWorkTorques], dE + dissipated, 1e-6 * e[kWorkTorques]);
}

// ---- 3 and 4. waves on a free span --------------------------------------------------------------
// Linearise the static state (the analytic Jacobian, checked against finite differences in
// jacobian_test.cpp) and keep the coordinates of the elements of the upper span that touch no
// pulley and lie between the tangent points, less one at each end; their neighbours are held, on
// the straight span too. Gravity off, so the span is straight.
struct Span {
  Scene scene;
  std::vector<int> elements;
  Eigen::MatrixXd K;  // ∂f/∂q over all coordinates
};

Span free_upper_span(double EI = 0.026) {
  SceneDef d = presets::paper_dry();
  d.gravity = 0;
  d.belt.EI = EI;
  Span s{build_scene(d), {}, {}};
  const Model& m = s.scene.model;
  const Drive& dr = s.scene.drive;
  const Eigen::VectorXd& y = s.scene.y0;
  for (int i = 0; i < m.n_el(); ++i) {
    // on the straight part of the upper span, between the tangent points x = 0 and x = l_p
    bool free = y[3 * i + 1] > 0.05 && y[3 * i] > 0 && y[3 * i] < 0.29;
    for (const Pulley& p : m.pulleys) free = free && (Vec2(y[3 * i], y[3 * i + 1]) - p.centre).norm() > p.radius;
    if (free) s.elements.push_back(i);
  }
  // hold the first and last of them too, so the held ends are on the straight span as well
  s.elements.erase(s.elements.begin());
  s.elements.pop_back();
  Jacobian J;
  J.resize(m);
  jacobian(m, dr, 0.0, y.data(), J);
  s.K = J.K.to_dense();
  return s;
}

// 3. Longitudinal: the x-motions of a straight chain of F masses m joined by springs k, both ends
// held, have ω_j = 2·sqrt(k/m)·sin(jπ/(2(F+1))) (the discrete dispersion ω(κ) = 2·sqrt(k/m)·
// sin(κl/2) at κl = jπ/(F+1)). Exact for a straight span: bound 1e-6 (rounding and the span's
// residual tilt). The lowest tends to the continuum c·π/L, c = sqrt(EA/ρ), within the
// dispersion error (κl)²/24 ≈ 0.2 % here: bound 0.5 %.
TEST(KnownAnswers, LongitudinalWavesFollowTheChainDispersion) {
  const Span s = free_upper_span();
  const Model& m = s.scene.model;
  const int F = static_cast<int>(s.elements.size());
  ASSERT_GE(F, 10);
  Eigen::MatrixXd A(F, F);
  for (int a = 0; a < F; ++a)
    for (int b = 0; b < F; ++b) A(a, b) = -s.K(3 * s.elements[a], 3 * s.elements[b]) / m.belt.mass;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(0.5 * (A + A.transpose()));
  const double w0 = std::sqrt(m.belt.k / m.belt.mass);
  for (int j = 1; j <= F; ++j) {
    const double expected = 2 * w0 * std::sin(j * M_PI / (2.0 * (F + 1)));
    EXPECT_NEAR(std::sqrt(es.eigenvalues()[j - 1]), expected, 1e-6 * expected) << "mode " << j;
  }
  const double c = std::sqrt(1.52e5 / 0.096);
  const double L = (F + 1) * m.belt.pitch;
  EXPECT_NEAR(std::sqrt(es.eigenvalues()[0]), c * M_PI / L, 5e-3 * c * M_PI / L);
}

// 4. Transverse: a tensioned span has f_n = (n/2L)·sqrt(T/ρ) (≈ 124 Hz for 0.29 m, 500 N). Here L
// ends at the inner ends of the held (clamped) rods: L = (F+1)·l - l_e.
std::vector<double> transverse_frequencies(const Span& s) {
  const Model& m = s.scene.model;
  const int F = static_cast<int>(s.elements.size());
  Eigen::MatrixXd K(2 * F, 2 * F), M = Eigen::MatrixXd::Zero(2 * F, 2 * F);
  for (int a = 0; a < F; ++a) {
    for (int b = 0; b < F; ++b)
      for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c) K(2 * a + r, 2 * b + c) = -s.K(3 * s.elements[a] + 1 + r, 3 * s.elements[b] + 1 + c);
    M(2 * a, 2 * a) = m.belt.mass;
    M(2 * a + 1, 2 * a + 1) = m.belt.rot_inertia;
  }
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(0.5 * (K + K.transpose()), M);
  std::vector<double> f;
  for (int k = 0; k < 2 * F; ++k) f.push_back(std::sqrt(es.eigenvalues()[k]) / (2 * M_PI));
  return f;
}

// Flexible belt (EI → 1e-6 N·m²): the string. The chain of F ≈ 13 rods departs from the continuum
// by (nπ/(F+1))²/24 ≲ 1 % for n ≤ 2 (measured ≤ 0.3 %): bound 1.5 %.
TEST(KnownAnswers, TransverseModesOfAFlexibleSpanAreTheString) {
  const Span s = free_upper_span(1e-6);
  const Model& m = s.scene.model;
  const int F = static_cast<int>(s.elements.size());
  const double L = (F + 1) * m.belt.pitch - m.belt.rigid_length;
  const double f0 = std::sqrt(s.scene.static_tension / 0.096) / (2 * L);
  const std::vector<double> f = transverse_frequencies(s);
  for (int n = 1; n <= 2; ++n) EXPECT_NEAR(f[n - 1], n * f0, 1.5e-2 * n * f0) << "mode " << n;
}

// The real belt (EI = 0.026 N·m²) is a stiff string, B = π²·EI/(T·L²). Its modes lie between those
// of a stiff string with pinned ends, n·f0·sqrt(1 + B·n²), and with clamped ends (Fletcher),
// n·f0·sqrt(1 + B·n²)·(1 + 2·sqrt(B)/π + 4·B/π²): the discrete torsional spring at each held rod
// is a clamp of finite stiffness. (Measured: 141 Hz between 138 and 146 Hz.)
TEST(KnownAnswers, TransverseModesOfTheStiffSpanLieBetweenPinnedAndClamped) {
  const Span s = free_upper_span(0.026);
  const Model& m = s.scene.model;
  const int F = static_cast<int>(s.elements.size());
  const double L = (F + 1) * m.belt.pitch - m.belt.rigid_length;
  const double T = s.scene.static_tension;
  const double f0 = std::sqrt(T / 0.096) / (2 * L);
  const double B = M_PI * M_PI * 0.026 / (T * L * L);
  const std::vector<double> f = transverse_frequencies(s);
  for (int n = 1; n <= 3; ++n) {
    const double pinned = n * f0 * std::sqrt(1 + B * n * n);
    const double clamped = pinned * (1 + 2 * std::sqrt(B) / M_PI + 4 * B / (M_PI * M_PI));
    EXPECT_GT(f[n - 1], pinned) << "mode " << n;
    EXPECT_LT(f[n - 1], clamped) << "mode " << n;
  }
}

// 4b. A moving span: the transverse modes of a string running at speed v drop to
// f_n = (n/2L)·(c² - v²)/c, c = sqrt(T/ρ) (T the span tension at that speed). Both pulleys are held
// at the speed of the belt; after 30 ms at speed the upper span is set vibrating in its first mode
// and the belt's height at mid-span is followed for 80 ms, averaged over the time one pitch takes
// to pass (the polygon of rigid elements running onto the pulleys shakes the span at that rate).
// Measured against the same run at rest, so the span's length and end conditions drop out of the
// ratio f(v)/f(0) = [(c_v² - v²)/c_v]/c_0. The frequency is the peak of the windowed spectrum
// between 60 and 250 Hz (≈ 10 periods).
struct SpanVibration {
  double f = 0, T = 0;
  double T_min = 1e300, T_max = -1e300;  // span tension over the record [N]
};

SpanVibration vibrate_span(double v) {
  SceneDef d = presets::paper_dry();
  d.gravity = 0;
  // the string of the formula: no bending stiffness, no bending damping (see the test's comment)
  d.belt.EI = 1e-6;
  d.belt.bending_damping = 0;
  for (PulleyDef& p : d.pulleys) {
    p.torque = TimeSpeedLaw{};
    p.kinematic = true;
    p.speed.constant = -v / p.radius;
  }
  const Scene sc = build_scene(d);
  const Model& m = sc.model;
  const Drive& dr = sc.drive;
  const int N = m.n_coord();
  Eigen::VectorXd y0 = v > 0 ? simulate(m, dr, rigid_motion(sc, v), 0.03, 0.03, "esdirk32", 1e-6).y.back() : sc.y0;
  for (int i = 0; i < m.n_el(); ++i) {  // first-mode velocity on the upper span
    const double x = y0[3 * i];
    if (y0[3 * i + 1] > 0.05 && x > 0 && x < 0.29) y0[N + 3 * i + 1] += 1.0 * std::sin(M_PI * x / 0.29);
  }
  const double dt = 1e-4;
  const auto s = simulate(m, dr, y0, 0.08, dt, "esdirk32", 1e-6);
  std::vector<double> h;  // the belt's height at x = 0.145 on the upper span
  double T = 0;
  SpanVibration out;
  for (const Eigen::VectorXd& y : s.y) {
    double best_l = -1e9, best_r = 1e9, yl = 0, yr = 0;
    for (int i = 0; i < m.n_el(); ++i) {
      if (y[3 * i + 1] < 0.05) continue;
      const double dx = y[3 * i] - 0.145;
      if (dx <= 0 && dx > best_l) best_l = dx, yl = y[3 * i + 1];
      if (dx > 0 && dx < best_r) best_r = dx, yr = y[3 * i + 1];
    }
    h.push_back(yl + (yr - yl) * (-best_l) / (best_r - best_l));
    const double Tk = sde_axial_force(m, y.data(), y.data() + N, sde_nearest(m, y.data(), Vec2(0.145, 0.1)));
    T += Tk / static_cast<double>(s.y.size());
    out.T_min = std::min(out.T_min, Tk);
    out.T_max = std::max(out.T_max, Tk);
  }
  const int window = v > 0 ? std::max(1, static_cast<int>(std::lround(m.belt.pitch / v / dt))) : 1;
  std::vector<double> smooth, ts;
  for (size_t k = 0; k + window <= h.size(); ++k) {
    double a = 0;
    for (int j = 0; j < window; ++j) a += h[k + j] / window;
    smooth.push_back(a);
    ts.push_back(s.t[k] + 0.5 * (window - 1) * dt);
  }
  double mean = 0;
  for (double x : smooth) mean += x / static_cast<double>(smooth.size());
  // the strongest frequency between 60 and 250 Hz (the first mode; the second is above 250 Hz),
  // from the Fourier sum of the Hann-windowed signal, on a 0.1 Hz grid
  out.T = T;
  double best = 0;
  const size_t K = smooth.size();
  for (double f = 60; f <= 250; f += 0.1) {
    double re = 0, im = 0;
    for (size_t k = 0; k < K; ++k) {
      const double w = 0.5 - 0.5 * std::cos(2 * M_PI * k / (K - 1));
      re += w * (smooth[k] - mean) * std::cos(2 * M_PI * f * ts[k]);
      im += w * (smooth[k] - mean) * std::sin(2 * M_PI * f * ts[k]);
    }
    if (re * re + im * im > best) best = re * re + im * im, out.f = f;
  }
  return out;
}

// The formula is for a flexible string, so the belt here has EI → 1e-6 N·m² and no bending
// damping: measured f(v)/f(0) = 0.798 (126.8 Hz at rest, 101.2 Hz at 30 m/s, mean span tension
// 486 N) against 0.808. The span tension wanders between 465 and 506 N during the record (±4 %),
// and the expected ratio moves by 0.72 % per 1 % of tension: bound 3 %.
// With the paper's belt the span vibrates faster than this formula says (ratio 1.146 against
// 1.067, measured). Most likely the torsional dampers: a belt running through a bending wave turns
// each element at v·w'', the dampers resist that with b_tor·l·v·w'''' per length, at 30 m/s an
// extra bending stiffness of about 0.03 N·m², more than EI itself. Measured: without b_tor the gap
// halves (1.122 against 1.078), without EI as well it closes (above).
TEST(KnownAnswers, MovingSpanVibratesSlower) {
  // the steps, not held to the elements' vibration (their velocities are out of the error norm),
  // grow until the implicit iteration fails on the nearly flexible belt (EI 1e-6 N·m², undamped)
  // now and then: those steps are retried at a fifth of their size
  test::expect_warnings({WarningKind::failed_step});
  const double v = 30.0, rho = 0.096;
  const SpanVibration rest = vibrate_span(0.0), moving = vibrate_span(v);
  ASSERT_GT(rest.f, 0.0);
  ASSERT_GT(moving.f, 0.0);
  const double c0 = std::sqrt(rest.T / rho), cv = std::sqrt(moving.T / rho);
  const double expected = (cv * cv - v * v) / cv / c0;
  EXPECT_NEAR(moving.f / rest.f, expected, 0.03 * expected)
      << "f(0) = " << rest.f << " Hz at " << rest.T << " N, f(v) = " << moving.f << " Hz at " << moving.T
      << " N (" << moving.T_min << " to " << moving.T_max << " N)";
}

}  // namespace
}  // namespace beltsim
