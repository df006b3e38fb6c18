// Coupled pulleys (model/coupling.cpp, scene/coupling.cpp): a free pulley and its rotor oscillate
// at the two-inertia torsional frequency, the start state is unloaded, a one-way clutch overruns
// (the rotor keeps its speed, ~no torque) and drives when the pulley is ahead, and what a coupling
// may not be given.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "model/forces.hpp"
#include "model/rhs.hpp"
#include "scene/validate.hpp"
#include "sim/simulation.hpp"
#include "support/parameter_error.hpp"
#include "support/presets.hpp"
#include "support/scratch.hpp"
#include "support/warning_guard.hpp"

namespace beltsim {
namespace {

using test::error_of;

// The paper's drive with μ = 0 and no applied torques: the belt puts no moment on a pulley (the
// normal force passes through its centre), so the driven pulley and a rotor coupled to it are a
// free two-inertia system. The driven pulley turns in the sense `Coupling::sense` (-1 here: the
// belt runs clockwise).
SceneDef frictionless(const CouplingDef& c) {
  SceneDef d = presets::paper_dry();
  d.belt.mu = 0;
  for (PulleyDef& p : d.pulleys) p.torque = TimeSpeedLaw{};
  d.pulleys[1].coupling = c;
  return d;
}

RunSettings coupling_settings(const std::string& name) {
  RunSettings rs;
  rs.integrator = "esdirk32";
  rs.rtol = 1e-7;
  rs.atol = 1e-9;
  rs.sample_dt = 1e-3;
  rs.out_dir = (test::scratch_dir("beltsim_coupling_test") / name).string();
  return rs;
}

// the scene with the pulley's and the rotor's (and hub's) speeds set in the start state
Scene started(const SceneDef& d, double pulley_speed, double rotor_speed) {
  Scene sc = build_scene(d);
  const Model& m = sc.model;
  const int N = m.n_coord();
  sc.y0[N + m.pulley_coord(1)] = pulley_speed;
  sc.y0[N + m.rotor_coord(0)] = rotor_speed;
  if (m.couplings[0].one_way) sc.y0[N + m.hub_coord(0)] = pulley_speed;
  return sc;
}

// Known answer: two inertias J_1, J_2 on a spring k oscillate at ω = √(k·(1/J_1 + 1/J_2)); their
// angular momentum J_1·ω_1 + J_2·ω_2 is conserved. The windup's zero crossings, interpolated
// linearly between samples 0.2 ms apart (the sine's curvature vanishes at a crossing: the error is
// third order, ~(ω·h)³/24 of a period ≈ 2e-7), give the period; the integrator's rtol 1e-7 bounds
// the phase error over 4 periods to ~1e-6: the tolerance 1e-4 leaves room for both.
TEST(Coupling, TwoInertiaNaturalFrequency) {
  CouplingDef c;
  c.inertia = 0.01;
  c.stiffness = 50;
  const Scene sc = started(frictionless(c), 0.0, 1.0);
  const double J1 = sc.model.pulleys[1].inertia, J2 = c.inertia;
  const double omega = std::sqrt(c.stiffness * (1 / J1 + 1 / J2));
  Simulation s(sc, coupling_settings("natural"));
  const double h = 2e-4, end = 4 * 2 * M_PI / omega + 2 * h;
  std::vector<double> crossings;
  double prev = s.pulley(1).windup, t_prev = 0;
  double worst_momentum = 0;
  for (double t = h; t <= end; t += h) {
    s.run_to(t);
    const PulleyObs p = s.pulley(1);
    if ((prev < 0) != (p.windup < 0)) crossings.push_back(t_prev + h * prev / (prev - p.windup));
    worst_momentum = std::max(worst_momentum, std::abs(J1 * p.omega + J2 * p.rotor_speed - J2 * 1.0));
    prev = p.windup, t_prev = t;
  }
  ASSERT_GE(crossings.size(), 8u);
  const double half_period = (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  EXPECT_NEAR(M_PI / half_period, omega, 1e-4 * omega);
  // amplitude of the windup: the relative speed 1 rad/s over ω
  EXPECT_LT(worst_momentum, 1e-6 * J2);
}

// The start state: the spring relaxed, the rotor turning with the pulley, so the coupling puts no
// torque on either; the pulley's applied torque law acts on the rotor (the pulley's row holds
// only the belt's moment).
TEST(Coupling, StartStateIsUnloadedAndTheLawActsOnTheRotor) {
  SceneDef d = presets::paper_dry();
  CouplingDef& c = d.pulleys[1].coupling.emplace();
  c.inertia = 0.01, c.stiffness = 50, c.damping = 0.1;
  const Scene sc = build_scene(d);
  const Model& m = sc.model;
  Eigen::VectorXd y = sc.y0;
  const int N = m.n_coord();
  y[N + m.pulley_coord(1)] = 30.0;
  y[N + m.rotor_coord(0)] = 30.0;
  const CouplingState st = coupling_state(m, sc.drive, 0.0, y.data(), y.data() + N, 0);
  EXPECT_EQ(st.windup, 0.0);
  EXPECT_EQ(st.transmitted, 0.0);
  Eigen::VectorXd f(N), f_bare(N);
  forces(m, sc.drive, 0.0, y.data(), f.data());
  // the driven pulley's law, -70 N·m at 700 rpm, at the rotor's speed
  EXPECT_NEAR(f[m.rotor_coord(0)], sc.drive.pulleys[1].torque.eval(0.0, 30.0), 1e-12);
  EXPECT_LT(f[m.rotor_coord(0)], -1.0);
  // the pulley's row: the belt's moment alone (the same as with no law on it)
  Drive bare = sc.drive;
  bare.pulleys[1].torque = TimeSpeedLaw{};
  forces(m, bare, 0.0, y.data(), f_bare.data());
  EXPECT_EQ(f[m.pulley_coord(1)], f_bare[m.pulley_coord(1)]);
  EXPECT_EQ(f_bare[m.rotor_coord(0)], 0.0);
}

CouplingDef one_way() {
  CouplingDef c;
  c.inertia = 0.01;
  c.stiffness = 50;
  c.damping = 0.2;
  c.one_way = true;
  return c;
}

// The rotor ahead of the pulley in the drive sense (the pulley decelerated under it): the clutch
// overruns. The rotor keeps its speed but for the clutch's drag T_d (its deceleration T_d/J_r over
// 0.1 s: 0.5 rad/s); the drag's reaction turns the hub and through the spring the pulley the other
// way (T_d/(J_1 + J_h) over 0.1 s: 0.2 rad/s); the torque on the rotor is the drag alone.
// A two-way coupling in the same state drags the rotor back at once (the contrast).
TEST(Coupling, OneWayClutchOverruns) {
  const CouplingDef c = one_way();
  const Scene sc = started(frictionless(c), -50.0, -80.0);  // sense -1: the rotor 30 rad/s ahead
  ASSERT_EQ(sc.model.couplings[0].sense, -1);
  Simulation s(sc, coupling_settings("overrun"));
  s.run_to(0.1);
  const PulleyObs p = s.pulley(1);
  const double drag_slowdown = c.drag_torque / c.inertia * 0.1;  // 0.5 rad/s
  EXPECT_NEAR(p.rotor_speed, -80.0 + drag_slowdown, 0.01 * drag_slowdown);
  const double J1 = sc.model.pulleys[1].inertia;
  const double drag_push = c.drag_torque / (J1 + c.hub_inertia) * 0.1;  // 0.2 rad/s
  // the spring's oscillation about that (excited by the drag's onset) is T_d/k ≈ 1e-3 rad: the
  // speeds are within 1 % of the drag's changes
  EXPECT_NEAR(p.omega, -50.0 - drag_push, 0.01 * drag_push + 0.01);
  EXPECT_NEAR(p.coupling_torque, c.drag_torque, 1e-3 * c.drag_torque);  // against the rotor's turning
  // two-way: the spring takes the rotor back within a quarter period
  CouplingDef two = c;
  two.one_way = false;
  Simulation t(started(frictionless(two), -50.0, -80.0), coupling_settings("two_way"));
  t.run_to(0.02);
  EXPECT_GT(t.pulley(1).rotor_speed, -70.0);
}

// The overrunning clutch's energy: its drag takes T_d·|slip| per second, about T_d·30 rad/s over
// the 0.1 s (the slip falls by the two changes above, 0.7 of 30 rad/s: the mean within 1.2 %), and
// it is the couplings' loss, not the belt's friction (μ = 0 here: that channel stays exactly 0).
// With no torques applied the energy only changes by what the channels take: ΔE + D = 0 (to 1e-6
// of D; the integrals are carried in the state at rtol 1e-7).
TEST(Coupling, ClutchDragIsTheCouplingsLoss) {
  const CouplingDef c = one_way();
  SceneDef d = frictionless(c);
  d.track_energy = true;
  const Scene sc = started(d, -50.0, -80.0);
  Simulation s(sc, coupling_settings("clutch_energy"));
  const double E0 = s.energy().total();
  s.run_to(0.1);
  const std::vector<double> e = s.energy_integrals();
  ASSERT_EQ(e.size(), static_cast<size_t>(kEnergyCount));
  const double drag = c.drag_torque * 30.0 * 0.1;
  EXPECT_NEAR(e[kDissCouplings], drag, 0.015 * drag);
  EXPECT_EQ(e[kDissFriction], 0.0);
  EXPECT_EQ(e[kDissArms], 0.0);
  double dissipated = 0;
  for (int k = kDissSdeAxial; k < kEnergyCount; ++k) dissipated += e[k];
  EXPECT_NEAR(s.energy().total() - E0 + dissipated, e[kWorkTorques], 1e-6 * dissipated);
}

// The pulley ahead of the rotor in the drive sense: the clutch engages and the rotor follows; the
// damper settles the spring, and then all three turn together at the speed their angular momentum
// gives (J_1·ω_1 + J_h·ω_1 + J_r·ω_r over the sum, less the clutch's slip |T|/c_L ≈ 0 at the end).
TEST(Coupling, OneWayClutchLockedFollows) {
  const CouplingDef c = one_way();
  // the engagement at t = 0 and the spring's ringing after it (the clutch lets go and takes up
  // again while the damper settles it) fail a few steps of the implicit iteration
  test::expect_warnings({WarningKind::failed_step});
  const Scene sc = started(frictionless(c), -80.0, -50.0);
  const double J1 = sc.model.pulleys[1].inertia, Jh = c.hub_inertia, Jr = c.inertia;
  const double common = ((J1 + Jh) * -80.0 + Jr * -50.0) / (J1 + Jh + Jr);
  Simulation s(sc, coupling_settings("locked"));
  s.run_to(0.005);
  EXPECT_LT(s.pulley(1).coupling_torque, -1.0);  // driving the rotor in the sense -1
  s.run_to(3.0);
  const PulleyObs p = s.pulley(1);
  EXPECT_NEAR(p.rotor_speed, common, 1e-3);
  EXPECT_NEAR(p.omega, common, 1e-3);
}

TEST(Coupling, ErrorsNameTheParameter) {
  SceneDef d = presets::paper_dry();
  CouplingDef& c = d.pulleys[1].coupling.emplace();
  c.inertia = 0.01, c.stiffness = -3;
  EXPECT_EQ(error_of([&] { build_scene(d); }), "pulley 'driven'.coupling.stiffness must be > 0 (got -3 N·m/rad)");
  c.stiffness = 50, c.inertia = 0;
  EXPECT_EQ(error_of([&] { build_scene(d); }), "pulley 'driven'.coupling.inertia must be > 0 (got 0 kg·m²)");
  c.inertia = 0.01, c.one_way = true, c.lock_damping = 0;
  EXPECT_EQ(error_of([&] { build_scene(d); }), "pulley 'driven'.coupling.lock_damping must be > 0 (got 0 N·m·s/rad)");
}

}  // namespace
}  // namespace beltsim
