// The analytic Jacobian (∂f/∂q, ∂f/∂v, ∂f/∂t) against central finite differences of the forces,
// on states built to exercise every branch of every force law: free spans, contact in the damping
// ramp (p < p_max) and beyond it, N clamped at zero, stick (|v_T| < Δv) and slip, bends across
// ±π and angles several laps apart, a back-side idler, non-unit exponents, a kinematic pulley,
// Stribeck's friction law (LuGre's bristles: bristles_jacobian_test.cpp).
//
// Tolerance. Every law is at most quadratic in the state near these points but for the geometry
// (n̂(P), e(φ)), whose curvature scales are the pulley radius and 1 rad: the central-difference
// truncation error is ~ (ε/0.03 m)² ≈ 1e-13 relative for ε = 1e-8 m, 1e-7 m/s (the element spin
// enters only the linear SDE dampers, so it takes ε = 1e-4 rad/s, exact up to rounding). Rounding
// gives |f|·1e-16/ε: with |f| ≲ 1e5 N (an element pushed 1.6 mm deep) at most 1e-3 absolute
// against column maxima ≳ 1e1 (measured: ≤ 5e-8 relative at these steps). So each column must
// agree to 1e-6 of its largest entry. The smallest terms the test must see are far larger:
// the SDE's -h·e·F moment term (h·F ≈ 5 N·m/rad against k·h² ≈ 750), the friction geometry term
// μN/r (≈ 1e3 against c2 ≈ 1e6), the contact damping b·δ (≈ 30 against μN/Δv ≈ 1e7): each is
// ≥ 1e-5 of its column, so dropping one or flipping its sign fails the test (tried: see docs/testing.md).
// States are kept a margin away from every kink (p = 0, p = p_max, N = 0, |v_T| = Δv), far
// beyond what the perturbations can move (the stick margin 1e-6 m/s against ε ≤ 1e-7 m/s).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>
#include <utility>
#include <vector>

#include "model/contact_law.hpp"
#include "model/forces.hpp"
#include "model/jacobian_check.hpp"
#include "model/rhs.hpp"
#include "support/presets.hpp"

namespace beltsim {
namespace {

using test::column_error;
using test::coverage;
using test::Coverage;
using test::expect_jacobian_matches;
using test::running_state;

TEST(Jacobian, PaperDryRunningState) {
  const Scene sc = build_scene(presets::paper_dry());
  const Eigen::VectorXd y = running_state(sc, 0.1, 30.0, 1);
  const Coverage c = coverage(sc.model, sc.drive, 0.1, y);
  EXPECT_GT(c.free, 0);
  EXPECT_GT(c.ramp, 0);
  EXPECT_GT(c.deep, 0);
  EXPECT_GT(c.clamped, 0);
  EXPECT_GT(c.stick, 0);
  EXPECT_GT(c.slip, 0);
  expect_jacobian_matches(sc.model, sc.drive, 0.1, y);  // t = 0.1 s: inside the torque ramp (∂f/∂t ≠ 0)
}

TEST(Jacobian, AnglesAcrossPiAndLaps) {
  const Scene sc = build_scene(presets::paper_dry());
  Eigen::VectorXd y = running_state(sc, 0.35, 20.0, 2);
  const Model& m = sc.model;
  const Drive& dr = sc.drive;
  // element angles shifted by whole laps, and one bend straddling the ±π cut
  for (int i = 0; i < m.n_el(); ++i) y[3 * i + 2] += 2 * M_PI * ((i * 7) % 5 - 2);
  int straddle = 0;
  for (int i = 1; i < m.n_el(); ++i) {
    const double a = std::remainder(y[3 * (i - 1) + 2], 2 * M_PI), b = std::remainder(y[3 * i + 2], 2 * M_PI);
    if (std::abs(a - b) > M_PI) straddle++;
  }
  EXPECT_GT(straddle, 0) << "no bend crosses the ±π cut";
  expect_jacobian_matches(m, dr, 0.35, y);
}

// The axis memo (forces.hpp) changes no result: the right-hand side and the Jacobian with it, after
// evaluations at other states (some angles changed, one from 0.0 to -0.0, whose sine differs in
// the sign of its zero), are the same to the bit as without it.
TEST(Jacobian, AxisMemoChangesNoResult) {
  const Scene sc = build_scene(presets::paper_dry());
  const Model& m = sc.model;
  const Drive& dr = sc.drive;
  const Eigen::VectorXd y1 = running_state(sc, 0.1, 30.0, 3);
  Eigen::VectorXd y2 = y1;
  for (int i = 0; i < m.n_el(); i += 3) y2[3 * i + 2] += 1e-3 * (i + 1);  // a third of the angles move
  Eigen::VectorXd y3 = y2;
  y2[3 * 4 + 2] = 0.0;
  y3[3 * 4 + 2] = -0.0;
  Workspace ws(m, false);
  const AxisMemo& memo = ws.axes;
  Eigen::VectorXd dy(m.n_state()), ref(m.n_state());
  Jacobian J, Jref;
  J.resize(m), Jref.resize(m);
  const Eigen::VectorXd* states[] = {&y1, &y3, &y1, &y2, &y3};  // ends with 0.0 -> -0.0
  for (const Eigen::VectorXd* y : states) {
    rhs(m, dr, 0.1, y->data(), dy.data(), &ws);
    rhs(m, dr, 0.1, y->data(), ref.data());
    EXPECT_EQ(std::memcmp(dy.data(), ref.data(), sizeof(double) * dy.size()), 0);
    jacobian(m, dr, 0.1, y->data(), J, &ws);
    jacobian(m, dr, 0.1, y->data(), Jref);
    const Eigen::MatrixXd K = J.K.to_dense(), Kref = Jref.K.to_dense(), C = J.C.to_dense(), Cref = Jref.C.to_dense();
    EXPECT_EQ(std::memcmp(K.data(), Kref.data(), sizeof(double) * K.size()), 0);
    EXPECT_EQ(std::memcmp(C.data(), Cref.data(), sizeof(double) * C.size()), 0);
  }
  // the memo holds the last state's axes, the sign of the zero angle's sine included (the anchors
  // are compared with their signs: -0.0 == 0.0 would have kept the sine of 0.0)
  EXPECT_TRUE(std::signbit(memo.s[4]));
  EXPECT_EQ(memo.c[0], axis(y3[2]).x());
}

// axis(φ) (forces.hpp: the anchor's cosine and sine turned by Taylor's series) is within a few
// units of rounding of (cos φ, sin φ): 4.4e-16, four units of rounding of 1 (the turn's products
// and sums round; the series' remainders are below 5e-18). Angles across the anchors' cells,
// on their edges and at them, small ones, negative ones and those of a belt that has run for
// hours (1e4 rad); the worst is 1.1e-16 (2.2e-16 in a build for the x86-64 baseline). The sine's
// series cut one term shorter is 7.6e-15 off at a cell's edge, the cosine's 9.7e-12.
TEST(Jacobian, AxisIsCosineAndSine) {
  std::vector<double> phis = {0.0, -0.0, 1e-300, -3e-9, 1.0 / 256, -1.0 / 256, 3.0 / 256, M_PI, -M_PI / 2, 1e4 + 0.3};
  for (int k = -300; k <= 300; ++k)
    for (double f : {-0.5, -0.4999999, -0.25, 0.0, 0.1, 0.37, 0.4999999, 0.5})
      phis.push_back((k + f) / 128 + (k % 7 == 0 ? 1e3 : 0));
  double worst = 0;
  for (double phi : phis) {
    const Vec2 e = axis(phi);
    worst = std::max({worst, std::abs(e.x() - std::cos(phi)), std::abs(e.y() - std::sin(phi))});
  }
  EXPECT_LE(worst, 4.4e-16);
  EXPECT_EQ(axis(5.0 / 128).y(), std::sin(5.0 / 128));  // on an anchor: its own sine
  EXPECT_TRUE(std::signbit(axis(-0.0).y()));
  // the memo's vectorised update gives axis() bit for bit, three times over (anchors new, kept with
  // the angles negated, new)
  const int n = static_cast<int>(phis.size());
  std::vector<double> q(3 * n);
  AxisMemo memo;
  memo.fit(n);
  // (the angles negated after the first pass: 0.0 becomes -0.0 on an anchor the memo holds as 0.0)
  for (const auto& [sign, shift] : {std::pair{1.0, 0.0}, {-1.0, 0.0}, {1.0, 1e-3}}) {
    for (int k = 0; k < n; ++k)
      q[3 * k + 2] = shift != 0 ? sign * phis[k] + shift : sign * phis[k];  // (-0.0 + 0.0 is 0.0)
    memo.update(q.data(), 0, n);
    int differ = 0;
    for (int k = 0; k < n; ++k) {
      const Vec2 e = axis(q[3 * k + 2]);
      differ +=
          std::memcmp(&e.x(), &memo.c[k], sizeof(double)) != 0 || std::memcmp(&e.y(), &memo.s[k], sizeof(double)) != 0;
    }
    EXPECT_EQ(differ, 0) << "sign " << sign << ", shift " << shift;
  }
}

// A long belt's right-hand side and Jacobian evaluated in two halves at once (rhs.hpp, Halves):
// every element row (forces, the blocks, the element-pulley couplings) has the same bits as the
// whole loop's, since each element receives its terms in the whole loop's order; the sums over
// elements (the pulleys' moments, ∂M/∂Ω, the energy rates) are added per half, which may change
// their last bits only: bound 1e-12 of the sum of the magnitudes they add (600 terms of rounding
// 1.1e-16 each). Repeated, so that the worker's hand-over is exercised many times.
TEST(Jacobian, HalvesChangeNoElementRow) {
  SceneDef d = presets::paper_dry();
  d.belt.elements = 600;
  d.track_energy = true;
  const Scene sc = build_scene(d);
  const Model& m = sc.model;
  const Drive& dr = sc.drive;
  ASSERT_GE(m.n_el(), kHalvesElements);
  const int N = m.n_coord(), ne = 3 * m.n_el();
  const Eigen::VectorXd y = running_state(sc, 0.1, 30.0, 6);
  Workspace halves(m);
  ASSERT_TRUE(halves.halves);
  Eigen::VectorXd dy(m.n_state()), ref(m.n_state());
  rhs(m, dr, 0.1, y.data(), ref.data());
  Jacobian J, Jref;
  J.resize(m), Jref.resize(m);
  jacobian(m, dr, 0.1, y.data(), Jref);
  auto same = [](const auto& a, const auto& b, size_t count) { return std::memcmp(a, b, sizeof(double) * count) == 0; };
  for (int rep = 0; rep < 20; ++rep) {
    rhs(m, dr, 0.1, y.data(), dy.data(), &halves);
    for (int k = 0; k < m.n_state(); ++k) {
      if (k < N + ne)  // positions' rates and the elements' accelerations
        ASSERT_TRUE(same(&dy[k], &ref[k], 1)) << "row " << k;
      else
        ASSERT_NEAR(dy[k], ref[k], 1e-12 * (std::abs(ref[k]) + 1e3)) << "row " << k;
    }
    jacobian(m, dr, 0.1, y.data(), J, &halves);
    for (const auto& [A, B] : {std::pair{&J.K, &Jref.K}, std::pair{&J.C, &Jref.C}}) {
      for (int i = 0; i < m.n_el(); ++i)
        ASSERT_TRUE(same(A->diag[i].data(), B->diag[i].data(), 9) && same(A->lower[i].data(), B->lower[i].data(), 9) &&
                    same(A->upper[i].data(), B->upper[i].data(), 9))
            << "element " << i;
      ASSERT_TRUE(same(A->elem_pulley.data(), B->elem_pulley.data(), A->elem_pulley.size()));
      ASSERT_TRUE(same(A->pulley_elem.data(), B->pulley_elem.data(), A->pulley_elem.size()));
      for (int j = 0; j < m.n_p(); ++j)  // a pulley's ∂M/∂Ω is a sum over elements
        for (int l = 0; l < m.n_p(); ++l)
          ASSERT_NEAR((*A).pulley_pulley(j, l), (*B).pulley_pulley(j, l), 1e-12 * std::abs((*B).pulley_pulley(j, l)));
    }
  }
}

TEST(Jacobian, BackSideIdlerAutomotive) {
  const Scene sc = build_scene(presets::automotive_wet());
  const Eigen::VectorXd y = running_state(sc, 0.2, 25.0, 3);
  const Coverage c = coverage(sc.model, sc.drive, 0.2, y);
  EXPECT_GT(c.stick, 0);
  EXPECT_GT(c.slip, 0);
  expect_jacobian_matches(sc.model, sc.drive, 0.2, y);
}

// The idler on a tensioner arm (model/tensioner.cpp), turning either way: the arm's column and
// row through the belt's pairs, the moving centre's terms in the element rows and the pulley's
// row. Dropping any one of ∂F/∂ψ's ψ̇·A_V·h, ∂Q/∂ψ's F·h, ∂M/∂ψ's ψ̇·∂M/∂V·h or ∂Q/∂Ω fails it
// (tried). The arm's own law is below the belt's terms in its column: TensionerArmLaw checks it.
TEST(Jacobian, TensionerArm) {
  for (const double rate : {2.0, -2.0}) {
    SceneDef d = presets::automotive_tensioner();
    TensionerDef& t = *d.pulleys[1].tensioner;
    t.damping = 1.0, t.friction_torque = 1.0, t.friction_speed = 2.0, t.asymmetric = 3.0;
    const Scene sc = build_scene(d);
    ASSERT_EQ(sc.model.n_arm(), 1);
    const Eigen::VectorXd y = running_state(sc, 0.2, 25.0, 7, rate);
    const Coverage c = coverage(sc.model, sc.drive, 0.2, y);
    EXPECT_GT(c.stick, 0);
    EXPECT_GT(c.slip, 0);
    expect_jacobian_matches(sc.model, sc.drive, 0.2, y);
  }
}

// The arm's own law (spring, damper, friction torque, asymmetric factor) against central
// differences of arm_forces alone: in the full Jacobian its ∂Q/∂ψ̇ is hidden under the belt's
// (-gᵀ·A_V·g ≈ L²·μN/Δv per sticking element). The law is smooth but for the kink of the
// asymmetric factor at ψ̇ = 0 (the rates keep 100 steps away); the steps, 1e-6 rad and 1e-6 rad/s
// against curvature scales of w_f = 0.05 rad/s, leave truncation ~ (1e-6/0.05)² = 4e-10 relative.
TEST(Jacobian, TensionerArmLaw) {
  SceneDef d = presets::automotive_tensioner();
  TensionerDef& t = *d.pulleys[1].tensioner;
  t.damping = 0.2, t.friction_torque = 2.0, t.friction_speed = 0.05, t.asymmetric = 3.0;
  const Scene sc = build_scene(d);
  const Model& m = sc.model;
  const int k = m.arm_coord(0), N = m.n_coord(), b = m.n_p();
  for (const double rate : {-0.3, -0.04, -1e-4, 1e-4, 0.03, 0.5}) {
    Eigen::VectorXd y = sc.y0;
    y[k] += 0.01;
    y[N + k] = rate;
    auto Q = [&](const Eigen::VectorXd& z) {
      Eigen::VectorXd f = Eigen::VectorXd::Zero(N);
      arm_forces(m, z.data(), z.data() + N, f.data(), nullptr);
      return f[k];
    };
    BlockMatrix K, C;
    K.resize(m.n_el(), m.n_border()), C.resize(m.n_el(), m.n_border());
    arm_jacobian(m, y.data(), y.data() + N, K, C);
    const double eps = 1e-6;
    Eigen::VectorXd yp = y, ym = y;
    yp[k] += eps, ym[k] -= eps;
    EXPECT_NEAR(K.pulley_pulley(b, b), (Q(yp) - Q(ym)) / (2 * eps), 1e-6 * t.stiffness) << "rate " << rate;
    yp = y, ym = y;
    yp[N + k] += eps, ym[N + k] -= eps;
    const double fd = (Q(yp) - Q(ym)) / (2 * eps);
    EXPECT_NEAR(C.pulley_pulley(b, b), fd, 1e-6 * std::abs(fd)) << "rate " << rate;
  }
  // asymmetric: at the spring's free angle, the arm resists `asymmetric` times harder turning
  // against the spring (the belt pushing it back, press·ψ̇ < 0) than with it
  Eigen::VectorXd y = sc.y0, f = Eigen::VectorXd::Zero(N);
  y[k] = m.arms[0].free_angle;
  y[N + k] = -m.arms[0].press * 0.1;
  arm_forces(m, y.data(), y.data() + N, f.data(), nullptr);
  const double back = f[k];
  f.setZero();
  y[N + k] = m.arms[0].press * 0.1;
  arm_forces(m, y.data(), y.data() + N, f.data(), nullptr);
  EXPECT_NEAR(back / f[k], -3.0, 1e-12);
}

// A rotor coupled to a pulley: the spring-damper's four entries in K and C, the applied torque's
// ∂M/∂Ω on the rotor's column, and the one-way clutch's lock in each of its regimes (the hub
// overtaking the rotor by 40 w, within the smoothing at ±0.5 w, overrun by 40 w, w = 2·T_d/c_L the
// width of σ; the central difference's step 1e-7 rad/s against w = 5e-4 rad/s leaves truncation
// (1e-7/5e-4)² = 4e-8). On the automotive drive's alternator (free, with a viscous load: its
// ∂M/∂Ω lands on the rotor) and on its kinematic crankshaft (∂/∂Ω_p goes to ∂f/∂t).
TEST(Jacobian, CoupledRotor) {
  for (const bool one_way : {false, true}) {
    for (const double slip : {40.0, 0.5, -0.5, -40.0}) {
      SceneDef d = presets::automotive_tensioner();
      d.pulleys[2].torque.per_speed = -0.05;
      d.pulleys[0].torque = TimeSpeedLaw{};
      d.pulleys[0].kinematic = true;
      d.pulleys[0].speed.t = {0.0, 0.5};
      d.pulleys[0].speed.value = {0.0, -60.0};
      for (const int j : {0, 2}) {
        CouplingDef& c = d.pulleys[j].coupling.emplace();
        c.inertia = 3e-3, c.stiffness = 40, c.damping = 0.3, c.one_way = one_way;
      }
      const Scene sc = build_scene(d);
      const Model& m = sc.model;
      ASSERT_EQ(m.n_coupled(), one_way ? 4 : 2);
      Eigen::VectorXd y = running_state(sc, 0.2, 25.0, 11, 0.5);
      const int N = m.n_coord();
      for (int c = 0; c < m.n_coupling(); ++c) {
        const Coupling& cp = m.couplings[c];
        const int kp = m.pulley_coord(cp.pulley), kr = m.rotor_coord(c);
        const double wp = sc.drive.omega(m, cp.pulley, 0.2, y.data() + N);
        const double w = 2 * cp.drag_torque / cp.lock_damping;
        y[kr] = y[kp] - 0.01 * (c + 1);  // a windup
        y[N + kr] = wp - cp.sense * slip * w + 0.3;
        if (cp.one_way) {
          y[kr + 1] = y[kp] - 0.02;
          y[N + kr + 1] = wp + 0.3;  // the rotor's speed is the hub's less sense·slip·w
        }
      }
      SCOPED_TRACE(std::string(one_way ? "one-way" : "two-way") + " slip " + std::to_string(slip));
      expect_jacobian_matches(m, sc.drive, 0.2, y);
    }
  }
}

TEST(Jacobian, NonUnitExponents) {
  SceneDef d = presets::paper_dry();
  d.belt.e_tra = 1.3;
  d.belt.e_tor = 1.2;
  d.belt.reading = StiffnessReading::per_sde;
  d.belt.k = 2e8;  // k·gap^1.3 carries the pretension at a gap of ≈ 2e-4 m
  d.belt.c = 1000;
  d.belt.kt = 1.3;
  d.belt.ct = 0.05;
  const Scene sc = build_scene(d);
  expect_jacobian_matches(sc.model, sc.drive, 0.05, running_state(sc, 0.05, 30.0, 4));
}

// Stribeck's law: its falling branch (v_s = 1 mm/s, between the slips of 0.4 and 2 mm/s the
// running state gives) and its peaked band; the curve's scale v_s is 1e4 times the velocity step,
// so its truncation error (1e-8) stays far inside the 1e-6 asked. The branch's slope, ≈ -2e4 N·s/m
// on an element slipping at 0.4 mm/s, is most of that element's velocity column.
TEST(Jacobian, StribeckLaw) {
  SceneDef d = presets::paper_dry();
  d.friction.law = FrictionKind::stribeck;
  d.friction.static_ratio = 1.6;
  d.friction.stribeck_speed = 1e-3;
  d.friction.exponent = 1.5;
  d.friction.viscous = 0.05;
  const Scene sc = build_scene(d);
  const Eigen::VectorXd y = running_state(sc, 0.1, 30.0, 7);
  const Coverage c = coverage(sc.model, sc.drive, 0.1, y);
  EXPECT_GT(c.stick, 0);
  EXPECT_GT(c.slip, 0);
  expect_jacobian_matches(sc.model, sc.drive, 0.1, y);
}

TEST(Jacobian, KinematicPulleyTimeDerivative) {
  SceneDef d = presets::paper_dry();
  d.pulleys[0].kinematic = true;
  d.pulleys[0].torque = TimeSpeedLaw{};
  d.pulleys[0].speed.t = {0.0, 0.5};
  d.pulleys[0].speed.value = {0.0, -60.0};
  const Scene sc = build_scene(d);
  const Eigen::VectorXd y = running_state(sc, 0.2, 30.0, 5);
  Jacobian J;
  J.resize(sc.model);
  jacobian(sc.model, sc.drive, 0.2, y.data(), J);
  EXPECT_GT(J.f_t.head(3 * sc.model.n_el()).cwiseAbs().maxCoeff(), 0.0) << "friction sees the speed ramp";
  expect_jacobian_matches(sc.model, sc.drive, 0.2, y);
}

// a law given as code (what a Lua law is to the model): M = -0.004·Ω·|Ω| + 2·sin(9t), whose
// derivatives the model takes by finite differences
class Drag final : public LawFunction {
 public:
  double value(double t, double omega) const override { return -0.004 * omega * std::abs(omega) + 2 * std::sin(9 * t); }
  std::string describe() const override { return "drag"; }
  long calls() const override { return 0; }
};

// every kind of law term in the Jacobian: a kinematic driver whose speed is a cosine ramp plus a
// sine plus harmonics (its Ω'' enters ∂f/∂t), and a driven pulley under a speed map, a ramp, a
// sine and code (∂M/∂Ω from the map's slope and the code's forward difference, whose error
// ~1e-8 relative is far inside the 1e-6 asked)
TEST(Jacobian, EveryLawTerm) {
  SceneDef d = presets::paper_dry();
  d.pulleys[0].kinematic = true;
  d.pulleys[0].torque = TimeSpeedLaw{};
  d.pulleys[0].speed.ramps = {{0.0, 0.3, 0.0, -60.0, true}};
  d.pulleys[0].speed.sines = {{0.0, 4.0, 30.0, 0.2}};
  d.pulleys[0].speed.harmonics = {{2.0, 3.0, 0.5, 60.0}};
  TimeSpeedLaw& M = d.pulleys[1].torque;
  M = TimeSpeedLaw{};
  M.omega = {-100.0, 0.0, 100.0};
  M.omega_value = {30.0, 0.0, -70.0};
  M.ramps = {{0.05, 0.2, 0.0, -5.0, true}};
  M.sines = {{1.0, 3.0, 20.0, 0.0}};
  M.fn = std::make_shared<Drag>();
  const Scene sc = build_scene(d);
  const double t = 0.13;
  const Eigen::VectorXd y = running_state(sc, t, 30.0, 6);
  Jacobian J;
  J.resize(sc.model);
  jacobian(sc.model, sc.drive, t, y.data(), J);
  const int k0 = sc.model.pulley_coord(0);
  EXPECT_NE(J.f_t[k0], 0.0) << "the driver's Ω'' is in ∂f/∂t";
  expect_jacobian_matches(sc.model, sc.drive, t, y);
}

}  // namespace
}  // namespace beltsim
