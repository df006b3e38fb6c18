// The friction laws of one element–pulley pair (contact_law.hpp, formulas at the top of
// model/friction.cpp): Stribeck's law without its peak and viscous term is Threlfall's to the bit;
// with them it has the curve's known values; its slope is the derivative of its value. LuGre's
// bristle (model/bristles.cpp): its steady sliding state is Stribeck's curve, it holds a load
// below μ_s at rest, and its slopes are the derivatives of its values.
#include <gtest/gtest.h>

#include <cmath>

#include "model/contact_law.hpp"

namespace beltsim {
namespace {

// a pair pressing on a pulley of r = 0.1 m at the origin, the element at angle 0.3 rad, 0.3 mm
// deep; slip v_T against a pulley turning at 20 rad/s
struct Pair {
  NormalLaw nl;
  Vec2 V;
  double omega = 20.0;
  explicit Pair(double vT) {
    const Contact c{3.0256e9, 6.5e5, 300, 1e-3};
    const Vec2 n(std::cos(0.3), std::sin(0.3));
    const Vec2 P = (0.1 - 3e-4) * n;
    V = (omega * P.norm() + vT) * perp(n);
    EXPECT_TRUE(normal_law(c, P, V, Vec2::Zero(), 0.1, nl));
  }
};

Friction stribeck(double ratio, double vs, double delta, double viscous) {
  Friction f;
  f.dv = 1e-5, f.law = FrictionKind::stribeck;
  f.static_ratio = ratio, f.stribeck_speed = vs, f.exponent = delta, f.viscous = viscous;
  return f;
}

TEST(FrictionLaw, StribeckWithoutPeakOrViscousTermIsThrelfallToTheBit) {
  const Friction f = stribeck(1.0, 0.01, 2.0, 0.0);
  for (double vT : {-0.5, -1e-3, -1e-5, -3e-6, 0.0, 2e-6, 9.9e-6, 1.01e-5, 0.02, 3.0}) {
    const Pair p(vT);
    const FrictionLaw a = friction_law(0.7, f.dv, p.nl, p.V, p.omega);
    const FrictionLaw b = stribeck_law(0.7, f, p.nl, p.V, p.omega);
    EXPECT_EQ(a.vT, b.vT);
    EXPECT_EQ(a.mu_eff, b.mu_eff) << "v_T = " << vT;
    EXPECT_EQ(a.dmu, b.dmu) << "v_T = " << vT;
  }
}

// μ_k = 0.4 (the element's μ), μ_s = 1.5·μ_k, v_s = 5 mm/s, δ = 2, μ_v = 0.01 s/m
TEST(FrictionLaw, StribeckCurveHasItsStaticAndKineticValues) {
  const Friction f = stribeck(1.5, 5e-3, 2.0, 0.01);
  const double mu_k = 0.4;
  // at the band's edge the peak μ_s (less e^(-(Δv/v_s)²) ≈ 1 - 4e-6 of the peak's excess)
  const Pair edge(f.dv);
  const FrictionLaw e = stribeck_law(mu_k, f, edge.nl, edge.V, edge.omega);
  EXPECT_NEAR(e.mu_eff, 1.5 * mu_k, 1e-5);
  // half-way into the band: half of it, odd in v_T
  const Pair half(-0.5 * f.dv);
  EXPECT_NEAR(stribeck_law(mu_k, f, half.nl, half.V, half.omega).mu_eff, -0.75 * mu_k, 1e-5);
  // at v_T = v_s: μ_k·(1 + 0.5/e) + μ_v·v_s
  const Pair at_vs(5e-3);
  EXPECT_NEAR(stribeck_law(mu_k, f, at_vs.nl, at_vs.V, at_vs.omega).mu_eff,
              mu_k * (1 + 0.5 * std::exp(-1.0)) + 0.01 * 5e-3, 1e-9);
  // far past v_s (e^(-400) = 0): μ_k + μ_v·v_T
  const Pair fast(-0.1);
  const FrictionLaw k = stribeck_law(mu_k, f, fast.nl, fast.V, fast.omega);
  EXPECT_NEAR(k.mu_eff, -(mu_k + 0.01 * 0.1), 1e-9);
  EXPECT_NEAR(k.dmu, 0.01, 1e-9);
}

// μ' against central differences of μ, on both sides of zero, inside the band and along the
// falling branch, for δ below, at and above 1. The curve's smallest scale is Δv = 1e-5 m/s inside
// the band (μ is a polynomial times e^(-a) there) and v_s outside: steps of 1e-4 of those give a
// truncation error ~ 1e-8 of μ', and rounding of μ (1e-16) over a difference of ≥ 1e-5 in μ
// ~ 1e-11: bound 1e-6 of μ' or of μ_k/v_s, the falling branch's slope scale, where μ' crosses 0.
TEST(FrictionLaw, StribeckSlopeIsTheDerivativeOfItsValue) {
  for (double delta : {0.6, 1.0, 2.0}) {
    const Friction f = stribeck(1.4, 2e-3, delta, 0.02);
    for (double vT : {-3e-2, -4e-3, -1e-3, -7e-6, -2e-6, 3e-6, 8e-6, 5e-5, 2e-3, 1e-2}) {
      const double h = 1e-4 * (std::abs(vT) < f.dv ? f.dv : std::min(std::abs(vT), 2e-3));
      const Pair p(vT), pp(vT + h), pm(vT - h);
      const FrictionLaw c = stribeck_law(0.8, f, p.nl, p.V, p.omega);
      const double fd = (stribeck_law(0.8, f, pp.nl, pp.V, pp.omega).mu_eff -
                         stribeck_law(0.8, f, pm.nl, pm.V, pm.omega).mu_eff) /
                        (pp.V.dot(pp.nl.t) - pm.V.dot(pm.nl.t));
      EXPECT_NEAR(c.dmu, fd, 1e-6 * std::max(std::abs(fd), 0.8 / f.stribeck_speed))
          << "δ = " << delta << ", v_T = " << vT;
    }
  }
}

Friction lugre(double ratio, double vs, double delta, double viscous) {
  Friction f = stribeck(ratio, vs, delta, viscous);
  f.law = FrictionKind::lugre;
  f.bristle_stiffness = 1e4, f.bristle_damping = 0.3, f.release_time = 1e-3;
  return f;
}

// Sliding steadily at v the deflection settles where ż = 0, z = g(v)·sgn(v)/σ0, and μ is
// Stribeck's curve without its band, μ_i·g(v)·sgn(v) + μ_v·v; at rest (v_T = 0) any deflection
// is steady and μ = σ0·z: a load below μ_s is held. Rounding only: bound 1e-12.
TEST(FrictionLaw, LugreSlidesOnStribecksCurveAndHoldsAtRest) {
  const Friction f = lugre(1.5, 5e-3, 2.0, 0.01), s = stribeck(1.5, 5e-3, 2.0, 0.01);
  const double mu_k = 0.4;
  for (double v : {-0.3, -5e-3, -1e-4, 2e-4, 5e-3, 0.08}) {
    const Pair p(v);
    const double curve = stribeck_law(mu_k, s, p.nl, p.V, p.omega).mu_eff;  // |v| > Δv: sat = ±1
    const double z = (curve - f.viscous * v) / f.bristle_stiffness;
    const Bristle b = bristle_law(mu_k, f, v, z);
    EXPECT_NEAR(b.zdot, 0.0, 1e-12 * std::abs(v)) << "v = " << v;
    EXPECT_NEAR(b.mu, curve, 1e-12) << "v = " << v;
  }
  const double held = 0.9 * 1.5 * mu_k;
  const Bristle rest = bristle_law(mu_k, f, 0.0, held / f.bristle_stiffness);
  EXPECT_EQ(rest.zdot, 0.0);
  EXPECT_NEAR(rest.mu, held, 1e-15);
}

// ∂ż/∂v, ∂ż/∂z, ∂μ/∂v, ∂μ/∂z against central differences, δ = 1.5 and 2, away from v = 0 (the
// kink of |v|) and on both sides of v_s; steps 1e-3 of |v| and of z: truncation ~1e-6 relative
// (the curve's scale is v_s, at least 2.5 times |v| here... or |v| itself), bound 1e-5 relative
// to the slope's scale (1 for ż's, σ0 for μ's in z).
TEST(FrictionLaw, BristleSlopes) {
  for (double delta : {1.5, 2.0}) {
    const Friction f = lugre(1.6, 5e-3, delta, 0.05);
    for (double v : {-2e-2, -4e-3, -5e-4, 3e-4, 2e-3, 1e-2})
      for (double zr : {-0.8, 0.2, 1.1}) {
        const double mu_k = 0.5, z = zr * 1.6 * mu_k / f.bristle_stiffness;
        const Bristle b = bristle_law(mu_k, f, v, z);
        const double hv = 1e-3 * std::abs(v), hz = 1e-3 * std::abs(z);
        const Bristle vp = bristle_law(mu_k, f, v + hv, z), vm = bristle_law(mu_k, f, v - hv, z);
        const Bristle zp = bristle_law(mu_k, f, v, z + hz), zm = bristle_law(mu_k, f, v, z - hz);
        EXPECT_NEAR(b.dzdot_dv, (vp.zdot - vm.zdot) / (2 * hv), 1e-5) << "δ " << delta << ", v " << v << ", z " << zr;
        EXPECT_NEAR(b.dmu_dv, (vp.mu - vm.mu) / (2 * hv), 1e-5) << "δ " << delta << ", v " << v << ", z " << zr;
        EXPECT_NEAR(b.dzdot_dz, (zp.zdot - zm.zdot) / (2 * hz), 1e-5 * f.bristle_stiffness * std::abs(v));
        EXPECT_NEAR(b.dmu_dz, (zp.mu - zm.mu) / (2 * hz), 1e-5 * f.bristle_stiffness);
      }
  }
}

}  // namespace
}  // namespace beltsim
