// Checks with known answers (docs/testing.md, Known answers), in that order: 5-6, the belt on
// its pulleys (capstan, drift, centrifugal tension, creep, slip arc) with each friction law.
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

// ---- 5. capstan ---------------------------------------------------------------------------------
// A belt over a pulley slips when T1/T2 > exp(μθ). With μ = 0.2, θ = π and T1 + T2 = 2·T0 the
// two-pulley drive carries at most r·2·T0·(e^{μπ} - 1)/(e^{μπ} + 1) = 30.4 N·m. The driven pulley
// is locked, the driver's torque ramps up in 10 ms and is held to 40 ms. Below the limit the driver
// only creeps (elastic strain of the belt: |Ω| < 0.5 rad/s); above it the belt slips and the
// driver accelerates at (M - 30.4 N·m)/I: at 1.05·limit that is -1.8 rad/s after the 30 ms hold
// (measured -2.1), so Ω < -1 rad/s. Torques at ±5 % of the limit: the bending stiffness and the
// belt's inertia shift it by less (measured: no slip at 0.95, slip at 1.05).
double driver_speed_after(double torque) {
  SceneDef d = presets::paper_dry();
  d.belt.mu = 0.2;
  d.pulleys[0].torque = TimeSpeedLaw{};
  d.pulleys[0].torque.t = {0.0, 0.01};
  d.pulleys[0].torque.value = {0.0, -torque};
  d.pulleys[1].torque = TimeSpeedLaw{};
  d.pulleys[1].kinematic = true;  // locked: prescribed speed 0
  const Scene sc = build_scene(d);
  const auto s = simulate(sc.model, sc.drive, sc.y0, 0.04, 0.01, "esdirk32", 1e-5);
  return s.y.back()[sc.model.n_coord() + sc.model.pulley_coord(0)];
}

TEST(KnownAnswers, CapstanLimitOfTheWetDrive) {
  // r·2·T0·(e^{μπ} - 1)/(e^{μπ} + 1) with the scene's r = 0.1 m, T0 = 500 N, μ = 0.2 (30.4 N·m)
  const double limit = 0.1 * 2 * 500 * (std::exp(0.2 * M_PI) - 1) / (std::exp(0.2 * M_PI) + 1);
  EXPECT_LT(std::abs(driver_speed_after(0.95 * limit)), 0.5);
  EXPECT_LT(driver_speed_after(1.05 * limit), -1.0) << "the driver should run away clockwise";
}

// The same with each friction law. Stribeck's (μ_k = 0.2, μ_s = 1.5·μ_k, v_s = 0.1 m/s): its belt
// holds up to the limit of μ_s, 43.9 N·m, as long as its elements slip at ≪ v_s; the torque ramps
// in over 30 ms here, which winds the belt up onto the driver at a few cm/s (over 10 ms, at
// 0.03 m/s, the curve fell under the load and the belt ran away at 0.95 of μ_s's limit). At 0.95 of
// that limit Stribeck's belt holds (|Ω| < 0.5 rad/s) where Threlfall's with μ = μ_k slips. At 1.05
// of each law's static limit the belt slips grossly, and at large slip (|v_T| ≥ 3·v_s, where
// e^(-(v_T/v_s)²) < 1.3e-4, once the driver turns at 3 rad/s) the belt's moment on the driver is
// the Euler–Eytelwein limit of the kinetic μ for both laws, 100·tanh(μ_k·π/2) = 30.4 N·m.
// Measured: Stribeck's belt at 41.7 N·m turns at 0.04 rad/s after 60 ms, Threlfall's at -15 rad/s;
// past the limits the belt's moment is 30.74 N·m (Threlfall's, at -2.1 rad/s) and 30.78 N·m
// (Stribeck's, at -17.7 rad/s), +1.0 and +1.2 % over 30.42: bound 3 % (the belt's inertia and
// bending, which the capstan formula leaves out).
struct Capstan {
  double omega = 0;   // the driver's speed at the end [rad/s]
  double moment = 0;  // the belt's moment on the driver then [N·m]
};
Capstan capstan_run(const Friction& f, double mu, double torque, double t_ramp, double t_end) {
  SceneDef d = presets::paper_dry();
  d.belt.mu = mu;
  d.friction = f;
  d.pulleys[0].torque = TimeSpeedLaw{};
  d.pulleys[0].torque.t = {0.0, t_ramp};
  d.pulleys[0].torque.value = {0.0, -torque};
  d.pulleys[1].torque = TimeSpeedLaw{};
  d.pulleys[1].kinematic = true;  // locked: prescribed speed 0
  const Scene sc = build_scene(d);
  const auto s = simulate(sc.model, sc.drive, sc.y0, t_end, 0.01, "esdirk32", 1e-5);
  const Eigen::VectorXd& y = s.y.back();
  const double* q = y.data();
  const double* v = q + sc.model.n_coord();
  ContactRecords contacts;
  fill_contacts(sc.model, sc.drive, s.t.back(), q, contacts);
  return {v[sc.model.pulley_coord(0)], belt_torque(contacts, 0, nullptr)};
}
double capstan_limit(double mu) { return 0.1 * 2 * 500 * std::tanh(mu * M_PI / 2); }

Friction stribeck_friction(double ratio, double vs) {
  Friction f = SceneDef{}.friction;
  f.law = FrictionKind::stribeck;
  f.static_ratio = ratio;
  f.stribeck_speed = vs;
  f.exponent = 2;
  f.viscous = 0;
  return f;
}

// LuGre's (model/bristles.cpp) with the same curve; its bristles (σ0 = 1e5 1/m, the default) hold
// the belt up to μ_s's limit at any slip below v_s, like Stribeck's band. Past the limit, with
// σ0 = 1e5 as with Stribeck's law, the belt comes to rest on the locked pulley and the driver
// slides under it: its moment is steady, 30.93 N·m (30.78 with σ0 = 1e6 and with Stribeck's law).
// With soft bristles (σ0 = 1e4) the belt breaks loose on the locked pulley instead, rides on the
// driver and speeds up with it: the locked pulley then carries μ_k's limit (30.77 N·m over the
// last 10 ms) and the driver's moment is that plus what accelerates the belt, 32.44 N·m at 0.06 s
// and rising. Neither is the bristles' damping: with σ1 = 0 the moments are 30.93 and 32.48 N·m.
Friction lugre_friction(double ratio, double vs) {
  Friction f = stribeck_friction(ratio, vs);
  f.law = FrictionKind::lugre;
  return f;
}

TEST(KnownAnswers, CapstanLimitWithEachLaw) {
  // the runs that slip grossly shorten and retry steps as the belt breaks loose
  test::expect_warnings({WarningKind::failed_step});
  const double mu_k = 0.2;
  const Friction threlfall = SceneDef{}.friction, stribeck = stribeck_friction(1.5, 0.1);
  const double between = 0.95 * capstan_limit(1.5 * mu_k);
  const Capstan held = capstan_run(stribeck, mu_k, between, 0.03, 0.06);
  const Capstan slips = capstan_run(threlfall, mu_k, between, 0.03, 0.06);
  const Capstan t = capstan_run(threlfall, mu_k, 1.05 * capstan_limit(mu_k), 0.01, 0.04);
  const Capstan s = capstan_run(stribeck, mu_k, 1.05 * capstan_limit(1.5 * mu_k), 0.03, 0.06);
  std::printf("capstan: at %.1f N·m Stribeck %.3f rad/s, Threlfall %.3f rad/s; past the limits Threlfall %.2f rad/s "
              "%.2f N·m, Stribeck %.2f rad/s %.2f N·m; μ_k's limit %.2f N·m\n",
              between, held.omega, slips.omega, t.omega, t.moment, s.omega, s.moment, capstan_limit(mu_k));
  EXPECT_LT(std::abs(held.omega), 0.5);
  EXPECT_LT(slips.omega, -1.0) << "Threlfall's belt should run away clockwise";
  EXPECT_LT(t.omega, -1.0);
  EXPECT_LT(s.omega, -3.0);
  EXPECT_NEAR(std::abs(t.moment), capstan_limit(mu_k), 0.03 * capstan_limit(mu_k));
  EXPECT_NEAR(std::abs(s.moment), capstan_limit(mu_k), 0.03 * capstan_limit(mu_k));
  // LuGre's: held between the limits, and at large slip the kinetic limit
  const Friction lugre = lugre_friction(1.5, 0.1);
  const Capstan lheld = capstan_run(lugre, mu_k, between, 0.03, 0.06);
  const Capstan ls = capstan_run(lugre, mu_k, 1.05 * capstan_limit(1.5 * mu_k), 0.03, 0.06);
  std::printf("capstan, LuGre: at %.1f N·m %.3f rad/s; past the limit %.2f rad/s %.2f N·m\n", between, lheld.omega,
              ls.omega, ls.moment);
  EXPECT_LT(std::abs(lheld.omega), 0.5);
  EXPECT_LT(ls.omega, -3.0);
  EXPECT_NEAR(std::abs(ls.moment), capstan_limit(mu_k), 0.03 * capstan_limit(mu_k));
}

// Drift under a constant tangential load below the limit. Threlfall's law has no true stick: an
// element carries μ·N·v_T/Δv, so a load needs a slip. The driver's torque M (half the μ = 0.2
// limit) against the locked driven pulley: in the steady state the belt creeps over both pulleys
// at one slip u, the driver turning at Ω = 2u/r, and each wrap (π) carries T1/T2 = e^(kπ) with
// k = μ·u/Δv, T1 + T2 = 2·T0 and r·(T1 - T2) = M, so
//   Ω = 4·Δv·atanh(M/(2·r·T0))/(π·μ·r)                  (Threlfall)
// and Stribeck's, whose band slope is μ_s/Δv while u ≪ v_s, drifts at that over μ_s/μ_k. Δv is
// 0.05 m/s here (the paper's 1e-5 would take minutes to wind the belt up through the band: the
// time constant Σμ·N/Δv over the belt's stiffness EA/L is 25 ms at 0.05 m/s and 2 min at 1e-5),
// v_s = 1 m/s ≫ u = 0.024 m/s. The speed averaged over 0.25-0.3 s (10 time constants);
// measured 0.4862 rad/s against 0.4811 (+1.1 %) and 0.3257 against 0.3207 (+1.6 %): bound 5 %
// (the wrap is not quite π where the belt's bending lifts it off at the ends).
double drift_speed(Friction f, double torque) {
  SceneDef d = presets::paper_dry();
  d.belt.mu = 0.2;
  f.dv = 0.05;
  d.friction = f;
  d.pulleys[0].torque = TimeSpeedLaw{};
  d.pulleys[0].torque.t = {0.0, 0.01};
  d.pulleys[0].torque.value = {0.0, -torque};
  d.pulleys[1].torque = TimeSpeedLaw{};
  d.pulleys[1].kinematic = true;
  const Scene sc = build_scene(d);
  const auto s = simulate(sc.model, sc.drive, sc.y0, 0.3, 0.005, "esdirk32", 1e-5);
  double omega = 0;
  int count = 0;
  for (size_t k = 0; k < s.t.size(); ++k)
    if (s.t[k] >= 0.25) omega += s.y[k][sc.model.n_coord() + sc.model.pulley_coord(0)], ++count;
  return omega / count;
}

TEST(KnownAnswers, DriftUnderASubLimitLoadIsTheBandsCreep) {
  const double M = 15.0, mu = 0.2, r = 0.1, T0 = 500, dv = 0.05;
  const double expected = 4 * dv * std::atanh(M / (2 * r * T0)) / (M_PI * mu * r);
  const Friction stribeck = stribeck_friction(1.5, 1.0);
  const double threlfall = -drift_speed(SceneDef{}.friction, M), peaked = -drift_speed(stribeck, M);
  std::printf("drift: Threlfall %.4f rad/s, Stribeck %.4f rad/s, expected %.4f and %.4f\n", threlfall, peaked,
              expected, expected / 1.5);
  EXPECT_NEAR(threlfall, expected, 0.05 * expected);
  EXPECT_NEAR(peaked, expected / 1.5, 0.05 * expected / 1.5);
}

// LuGre's law has true stick: under the same load each element's bristle deflects to z = μ/σ0 and
// the belt stops. With σ0 = 1e5 1/m the deflections wind the driver on by at most
// 2·μ_s/σ0/r = 3e-5 rad in all, so its mean speed over 0.25-0.3 s, long after the load came on,
// is the belt's ringing, not a creep: bound 1 % of Threlfall's drift (0.48 rad/s; measured
// below 1e-6 rad/s, 3.6e-5 with σ0 = 1e4).
TEST(KnownAnswers, LugreHoldsASubLimitLoadWithoutDrift) {
  // the load's ramp end winds the belt up at once: a few steps retried at a fifth of their size
  test::expect_warnings({WarningKind::failed_step});
  const double M = 15.0, mu = 0.2, r = 0.1, T0 = 500, dv = 0.05;
  const double threlfall = 4 * dv * std::atanh(M / (2 * r * T0)) / (M_PI * mu * r);
  const double held = -drift_speed(lugre_friction(1.5, 1.0), M);
  std::printf("drift: LuGre %.2e rad/s, Threlfall's creep %.4f rad/s\n", held, threlfall);
  EXPECT_LT(std::abs(held), 0.01 * threlfall);
}

// ---- 6. centrifugal tension ---------------------------------------------------------------------
// Both pulleys held at the speed of a belt running at v = 30 m/s (the belt starts in that rigid
// motion). The belt on a half wrap turns its momentum round: the pulley carries the two span
// tensions less the centrifugal part, hub load = 2·(T - ρv²), ρv² = 86 N (17 % of the pretension).
// After 10 ms the start-up ripple has decayed below 0.5 % (measured); bound 1 % of the load,
// which the centrifugal term exceeds 17-fold.
TEST(KnownAnswers, CentrifugalTensionUnloadsThePulleys) {
  // the steps, not held to the elements' vibration (their velocities are out of the error norm),
  // grow until the implicit iteration fails on an element entering a wrap at 30 m/s: a few steps
  // retried at a fifth of their size
  test::expect_warnings({WarningKind::failed_step});
  SceneDef d = presets::paper_dry();
  const double v = 30.0, rho = 0.096;
  for (PulleyDef& p : d.pulleys) {
    p.torque = TimeSpeedLaw{};
    p.kinematic = true;
    p.speed.constant = -v / p.radius;  // clockwise travel
  }
  const Scene sc = build_scene(d);
  const Model& m = sc.model;
  const Drive& dr = sc.drive;
  const auto s = simulate(m, dr, rigid_motion(sc, v), 0.01, 0.01, "esdirk32", 1e-6);
  const Eigen::VectorXd& y = s.y.back();
  const double* q = y.data();
  const double* vel = q + m.n_coord();
  double T = 0;
  for (const Route::Span& sp : sc.route.spans)
    T += 0.5 * sde_axial_force(m, q, vel, sde_nearest(m, q, 0.5 * (sp.from + sp.to)));
  ContactRecords contacts;
  fill_contacts(m, dr, s.t.back(), q, contacts);
  for (int j = 0; j < m.n_p(); ++j) {
    Vec2 hub;
    belt_torque(contacts, j, &hub);
    const double expected = 2 * (T - rho * v * v);
    EXPECT_NEAR(hub.norm(), expected, 0.01 * expected) << m.pulleys[j].name << ", span tension " << T << " N";
  }
}

// Creep (Reynolds): a belt carrying T1 on the tight side and T2 on the slack side leaves the
// driver stretched more than it arrives on the driven pulley, so the driven pulley turns slower.
// Where the belt sticks to a pulley it moves with the rim at the radius R - p it rides at (p the
// contact penetration under N = 2·T·sin(α/2), α = pitch/R) and carries the strain T/EA of the
// tension T there; the elements pass both pulleys at the same rate, so at the middle of each wrap
//   |ω_j|·(R - p(T_j)) - v_T,j = c·(1 + T_j/EA)      (c: the belt's speed at zero strain)
// with v_T,j the element's slip there (travel clockwise: v_T is along the anticlockwise tangent;
// 0 where the belt sticks). Hence
//   ω2/ω1 = [(R - p(T_1))/(R - p(T_2))]·(1 + T_2/EA + v_T,2/c)/(1 + T_1/EA + v_T,1/c)
// with T_1, T_2 the tensions at the middle of the driver's and the driven pulley's wrap. These are
// not the spans' tensions: each element runs onto a pulley faster than the rim under it and is
// slowed to the rim's speed by friction over its first pitch or two, which raises the tension of
// the stuck belt over the span's (measured with Threlfall's law: by 172 N on the driver, 120 N on
// the driven pulley; 100 to 250 N with the other laws). With the spans' tensions the formula gives
// 0.0504 rad/s, 13 % under the loss.
// Driver held at 20 rad/s, driven loaded by 1.5 N·m·s/rad (30 N·m), both starting at the belt's
// speed (2 m/s); the loss is the driven pulley's mean speed from its angle over 0.3-0.5 s, when
// the start-up oscillation has decayed, and the tensions and the slip are averaged over samples
// 1 ms apart. (The driven pulley's speed ripples at the element passing frequency, 99.2 Hz: the
// mean of samples 5 ms apart takes its second harmonic at 1.7 Hz, ±0.01 rad/s over a 0.2 s
// window.) Measured (rtol 1e-6; rtol 1e-7 changes the losses by less than 0.1 %): Threlfall's
// 0.05830 rad/s against 0.05782 (+0.8 %), Stribeck's (μ_s = 1.5·μ, v_s = 0.1 m/s) 0.06233
// against 0.06208 (+0.4 %; with v_s = 0.01 m/s 0.06277 against 0.06302, but its falling branch,
// ten times steeper, held the run to 20 s of CPU instead of 2), LuGre's (σ0 = 1e5 1/m) 0.05929
// against 0.05861 (+1.1 %): bound 3 %, twice the largest deviation. That check reads T_j and v_T,j from the run itself, so it tests
// the model's consistency with the formula, not the loss: the independent prediction is the
// formula with the spans' tensions (the tensions between the pulleys, which the load sets, and no
// slip), asserted by expect_creep_loss.
struct Creep {
  double loss = 0;           // ω1 - |ω2| [rad/s]
  double expected = 0;       // the formula above [rad/s]
  double stuck_only = 0;     // the same with v_T,j = 0 [rad/s]
  double span_tensions = 0;  // the same with the spans' tensions and v_T,j = 0 [rad/s]
  double rise[2] = {0, 0};   // T_j less the tension of the span running onto pulley j [N]
};
Creep creep_run(const Friction& f) {
  SceneDef d = presets::paper_dry();
  d.friction = f;
  const double w1 = 20.0, R = 0.1, v = w1 * R, EA = 1.52e5;
  d.pulleys[0].torque = TimeSpeedLaw{};
  d.pulleys[0].kinematic = true;
  d.pulleys[0].speed.constant = -w1;
  d.pulleys[1].torque = TimeSpeedLaw{};
  d.pulleys[1].torque.per_speed = -1.5;
  const Scene sc = build_scene(d);
  const Model& m = sc.model;
  const Drive& dr = sc.drive;
  const auto s = simulate(m, dr, rigid_motion(sc, v), 0.5, 0.001, "esdirk32", 1e-6);
  // the middle of each wrap: the point of the pulley's rim facing away from the other pulley
  const Vec2 mid[2] = {m.pulleys[0].centre + R * (m.pulleys[0].centre - m.pulleys[1].centre).normalized(),
                       m.pulleys[1].centre + R * (m.pulleys[1].centre - m.pulleys[0].centre).normalized()};
  double span[2] = {0, 0}, T[2] = {0, 0}, slip[2] = {0, 0}, angle[2] = {0, 0};
  int count = 0;
  for (size_t k = 0; k < s.t.size(); ++k) {
    if (s.t[k] < 0.3 - 1e-9) continue;
    const double* y = s.y[k].data();
    const double* vel = y + m.n_coord();
    if (count == 0) angle[0] = y[m.pulley_coord(1)];
    angle[1] = y[m.pulley_coord(1)];
    ContactRecords contacts;
    fill_contacts(m, dr, s.t[k], y, contacts);
    for (int j = 0; j < 2; ++j) {
      // spans[1] (lower) runs onto the driver: tight; spans[0] (upper) onto the driven pulley
      const Route::Span& sp = sc.route.spans[1 - j];
      span[j] += sde_axial_force(m, y, vel, sde_nearest(m, y, 0.5 * (sp.from + sp.to)));
      T[j] += sde_axial_force(m, y, vel, sde_nearest(m, y, mid[j]));
      int nearest = 0;
      for (int i = 1; i < m.n_el(); ++i)
        if ((Vec2(y[3 * i], y[3 * i + 1]) - mid[j]).norm() < (Vec2(y[3 * nearest], y[3 * nearest + 1]) - mid[j]).norm())
          nearest = i;
      slip[j] += element_contact(contacts, nearest).slip;
    }
    count++;
  }
  const double alpha = m.belt.pitch / R;
  auto depth = [&](double tension) {  // c1·p² + c2·p = 2·T·sin(α/2)
    const double N = 2 * tension * std::sin(alpha / 2), c1 = m.contact.c1, c2 = m.contact.c2;
    return (-c2 + std::sqrt(c2 * c2 + 4 * c1 * N)) / (2 * c1);
  };
  auto loss = [&](const double* tension, const double* vT) {
    return w1 * (1 - (R - depth(tension[0])) / (R - depth(tension[1])) * (1 + tension[1] / EA + vT[1] / v) /
                         (1 + tension[0] / EA + vT[0] / v));
  };
  Creep c;
  for (int j = 0; j < 2; ++j) span[j] /= count, T[j] /= count, slip[j] /= count, c.rise[j] = T[j] - span[j];
  const double none[2] = {0, 0};
  c.loss = w1 + (angle[1] - angle[0]) / 0.2;
  c.expected = loss(T, slip);
  c.stuck_only = loss(T, none);
  c.span_tensions = loss(span, none);
  EXPECT_NEAR(span[0] - span[1], 300.0, 30.0) << "the load is 30 N·m on r = 0.1 m";
  std::printf(
      "%s: creep loss %.5f rad/s, expected %.5f (%+.1f %%; without the slip %.5f, with the spans' tensions "
      "%.5f); tension at the middle of the wraps %.1f and %.1f N, %+.1f and %+.1f N over the spans'; slip there "
      "%.2e and %.2e m/s\n",
      friction_law_name(f.law), c.loss, c.expected, 100 * (c.loss / c.expected - 1), c.stuck_only, c.span_tensions,
      T[0], T[1], c.rise[0], c.rise[1], slip[0], slip[1]);
  return c;
}

// The loss against the formula with the spans' tensions (Creep::span_tensions): the loss lies over
// it by the rise of the stuck belt's tension at each wrap's entry, which the spans' tensions leave
// out (above), and with soft bristles by their creep through the wraps. Measured (rtol 1e-6) over
// it by 15.7 % (Threlfall's), 23.1 % (Stribeck's), 17.7 % and 13.3 % (LuGre's, σ0 = 1e5 and 1e4
// 1/m): bounds 0 and 30 %, the largest excess with a quarter of it again for the laws' and the
// bristles' other settings.
void expect_creep_loss(const Creep& c) {
  EXPECT_GT(c.loss, c.span_tensions) << "the loss lies over the spans' prediction";
  EXPECT_LT(c.loss, 1.3 * c.span_tensions) << "the spans' prediction is within 30 % of the loss";
}

TEST(KnownAnswers, CreepSpeedLossMatchesTheTensionDifference) {
  // the drive's first stick-slip changes cost esdirk32 a failed step (shortened and retried)
  test::expect_warnings({WarningKind::failed_step});
  const Creep c = creep_run(SceneDef{}.friction);
  EXPECT_NEAR(c.loss, c.expected, 0.03 * c.expected);
  expect_creep_loss(c);
}

TEST(KnownAnswers, CreepSpeedLossIsTheSameWithStribecksLaw) {
  test::expect_warnings({WarningKind::failed_step});
  const Creep c = creep_run(stribeck_friction(1.5, 0.1));
  EXPECT_NEAR(c.loss, c.expected, 0.03 * c.expected);
  expect_creep_loss(c);
}

// LuGre's law: an element sticks by its bristle deflection z = μ/σ0, and the belt creeps through
// the wrap where z changes along it, at v_T = v·dz/ds. Stiff bristles (σ0 = 1e5 1/m, the default)
// hold the belt still at the middle of each wrap, as the regularised laws' band does (measured
// slip 1.4e-5 m/s: 0.1 % of the loss); soft ones (σ0 = 1e4) let it creep there (5.2e-4 and
// -2.0e-4 m/s on the driver and the driven pulley: without that slip the formula gives 0.04892,
// 14 % under the loss), and they slow the elements running onto a pulley less abruptly, so the
// tension of the stuck belt rises less over the span's (48 and 53 N against 170 and 112 N with
// σ0 = 1e5). The two effects partly cancel: the loss is 0.05682 rad/s with σ0 = 1e4 and 0.05929
// with σ0 = 1e5, 1.3 % and 1.1 % over the formula (0.05609 and 0.05862). Bounds: 3 % against the
// formula; the slip's share of it above 7 % with soft bristles, below 2 % with stiff ones; the
// rise with soft bristles under half that with stiff ones.
TEST(KnownAnswers, CreepSpeedLossWithLugresLawComesFromTheBristles) {
  test::expect_warnings({WarningKind::failed_step});
  Friction stiff = lugre_friction(1.5, 0.01), soft = stiff;
  soft.bristle_stiffness = 1e4;
  const Creep s = creep_run(stiff), c = creep_run(soft);
  EXPECT_NEAR(s.loss, s.expected, 0.03 * s.expected);
  EXPECT_NEAR(c.loss, c.expected, 0.03 * c.expected);
  expect_creep_loss(s);
  expect_creep_loss(c);
  EXPECT_LT(std::abs(s.expected - s.stuck_only), 0.02 * s.expected) << "stiff bristles hold the middle of the wraps";
  EXPECT_GT(c.expected - c.stuck_only, 0.07 * c.expected) << "soft bristles let the belt creep through the wraps";
  EXPECT_LT(c.rise[0], 0.5 * s.rise[0]);
  EXPECT_LT(c.rise[1], 0.5 * s.rise[1]);
}

// Euler–Eytelwein: on a steady drive the gross-slip arc of each pulley (where the friction is
// saturated and the tension falls from T1 to T2) spans the angle ln((T1 − m'v²)/(T2 − m'v²))/μ,
// so its length is R·ln(...)/μ; the rest of the wrap is the adhesion arc (model/observables.hpp).
// Scene: the two-pulley drive with μ = 0.3, the driver held at 20 rad/s (ramped in 0.05 s), the
// driven loaded by 1.5 N·m·s/rad (30 N·m: T1 ≈ 655, T2 ≈ 355 N, arc ≈ 0.205 m of the 0.314 m
// wrap). A thin belt (EI/10) and, so that refining changes the discretisation and not the belt,
// the contact constants and the bending damping given per length (the paper's are per element and
// per SDE). slip_arc and the span tensions averaged over the
// samples from 0.12 s to 0.2 s (8 element passings at 60 elements; steady: the averages over
// 0.15-0.25 s and 0.1-1 s agree within 0.5 %, measured). m'v² = 0.4 N here.
// Measured (rtol 1e-4), error of the slip arc against R·ln(T1/T2)/μ, driver / driven:
//    60 elements   +9.3 % /  -8.3 %
//   120 elements   +1.5 % /  -7.8 %
//   240 elements   -1.1 % /  -1.8 %
// and with the old criterion (|slip| > Δv) at 240: +9 % / +12 % (it counts the elements settling
// onto the rim where the belt runs on). Bounds: the mean error over both pulleys falls with each
// refinement, and is within 3 % at 240 elements (twice the measured 1.45 %).
TEST(KnownAnswers, SlipArcApproachesEulerEytelwein) {
  // the finer belts meet more stick-slip changes per second: failed steps, shortened and retried
  test::expect_warnings({WarningKind::failed_step});
  const double l60 = build_scene(presets::paper_dry()).model.belt.rigid_length;  // an element's rest length at 60
  std::vector<double> err;
  for (int n : {60, 120, 240}) {
    SceneDef d = presets::paper_dry();
    const double mu = 0.3, w1 = 20.0, R = 0.1;
    d.belt.elements = n;
    d.belt.mu = mu;
    d.belt.EI *= 0.1;
    // the paper's per-element contact and per-SDE bending damping as they are at 60 elements,
    // given per length (scene.hpp) so that they stay when the belt is divided finer
    d.belt.bending_viscosity = 0.1 * d.belt.bending_damping * l60;
    d.contact_per_length.c1 = d.contact.c1 / l60;
    d.contact_per_length.c2 = d.contact.c2 / l60;
    d.contact_per_length.b = d.contact.b / l60;
    d.pulleys[0].torque = TimeSpeedLaw{};
    d.pulleys[0].kinematic = true;
    d.pulleys[0].speed.t = {0.0, 0.05};
    d.pulleys[0].speed.value = {0.0, -w1};
    d.pulleys[1].torque = TimeSpeedLaw{};
    d.pulleys[1].torque.per_speed = -1.5;
    const Scene sc = build_scene(d);
    RunSettings rs;
    rs.out_dir = (beltsim::test::scratch_dir("beltsim_physics_test") / ("ee_" + std::to_string(n))).string();
    rs.keep_samples = true;
    rs.t_end = 0.2;
    const RunResult r = run(sc, rs);
    const std::vector<std::string> cols = timeseries_columns(sc);
    auto col = [&](const std::string& name) { return std::find(cols.begin(), cols.end(), name) - cols.begin(); };
    double slip[2] = {0, 0}, T1 = 0, T2 = 0;
    int count = 0;
    for (const std::vector<double>& row : r.samples) {
      if (row[0] < 0.12) continue;
      slip[0] += row[col("driver.slip_arc")], slip[1] += row[col("driven.slip_arc")];
      T2 += row[col("span_driver_driven.tension")];  // upper span, leaving the driver: slack
      T1 += row[col("span_driven_driver.tension")];
      count++;
    }
    T1 /= count, T2 /= count;
    const double v = w1 * R, c = 0.096 * v * v;
    const double expected = R * std::log((T1 - c) / (T2 - c)) / mu;
    const double e0 = slip[0] / count / expected - 1, e1 = slip[1] / count / expected - 1;
    std::printf("%3d elements: T1 = %.1f N, T2 = %.1f N, R·ln(T1/T2)/μ = %.4f m; slip arc: driver %.4f m (%+.1f %%), "
                "driven %.4f m (%+.1f %%)\n",
                n, T1, T2, expected, slip[0] / count, 100 * e0, slip[1] / count, 100 * e1);
    err.push_back(0.5 * (std::abs(e0) + std::abs(e1)));
  }
  EXPECT_LT(err[1], err[0]);
  EXPECT_LT(err[2], err[1]);
  EXPECT_LT(err[2], 0.03);
}

// The creep against the belt on each wrap (model/observables.hpp, PulleyObs::creep_pitch): in
// steady running < 0 on a driver, > 0 on a driven pulley, 0 on a wrap without a gross-slip arc, as
// a free idler's is (it carries no torque, so the tension does not change round it). Scene:
// tests/support/free_idler.lua, the paper's two pulleys loaded to 40 N·m and a free idler of
// 0.05 m on the tight side; the samples from 0.4 to 0.6 s (62 to 68 rad/s, the torque ramped in
// by 0.3 s). Measured (the run's default integrator and rtol): driver -2.6e-3 to -2.3e-4 (mean
// -1.27e-3), driven 0 to +1.0e-3 (mean +5.4e-4; 0 at the samples between its elements' slips),
// idler 0 at 200 of the 201 samples and +8.4e-5 at one (its last element slipping forwards alone
// as it lifts off, at N = 3.9 N), mean +4.2e-7. Against the speed of the whole loop (the
// definition before) the idler read +1.1e-2 on average, nine times the driver's creep, and the
// driver from -3.5e-3 to +4.0e-3: the belt's speed differs from wrap to wrap by more than a
// pulley's creep. Bounds: the driver's and the driven's signs at every sample (the driven's >= 0);
// the idler's mean within a hundredth of the driver's (the measured 4.2e-7 is a thirtieth of
// that) and 0 at all but 5 % of the samples (measured 0.5 %).
TEST(KnownAnswers, CreepSignOfEachPulley) {
  const Scene sc = build_scene(presets::script_scene("tests/support/free_idler.lua"));
  RunSettings rs;
  rs.out_dir = (beltsim::test::scratch_dir("beltsim_physics_test") / "free_idler").string();
  rs.keep_samples = true;
  rs.t_end = 0.6;
  const RunResult r = run(sc, rs);
  const std::vector<std::string> cols = timeseries_columns(sc);
  auto col = [&](const std::string& name) { return std::find(cols.begin(), cols.end(), name) - cols.begin(); };
  double mean[3] = {0, 0, 0};
  int count = 0, idler_creeps = 0;
  for (const std::vector<double>& row : r.samples) {
    if (row[0] < 0.4 - 1e-9) continue;
    const double driver = row[col("driver.creep_pitch")], driven = row[col("driven.creep_pitch")],
                 idler = row[col("idler.creep_pitch")];
    EXPECT_LT(driver, 0) << "t = " << row[0];
    EXPECT_GE(driven, 0) << "t = " << row[0];
    idler_creeps += idler != 0;
    mean[0] += driver, mean[1] += driven, mean[2] += idler, count++;
  }
  for (double& x : mean) x /= count;
  std::printf("creep_pitch over 0.4-0.6 s: driver %.3e, driven %.3e, idler %.3e (nonzero at %d of %d samples)\n",
              mean[0], mean[1], mean[2], idler_creeps, count);
  EXPECT_EQ(count, 201);
  EXPECT_GT(mean[1], 0);
  EXPECT_LT(std::abs(mean[2]), 0.01 * std::abs(mean[0]));
  EXPECT_LE(idler_creeps, 0.05 * count);
}

}  // namespace
}  // namespace beltsim
