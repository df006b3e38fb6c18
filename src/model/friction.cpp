// Simplified Threlfall friction (paper eqs. 3–4, Fig. 4), for one element–pulley pair in contact.
//
// Slip velocity of the element centre against the pulley surface at the same point
// (the surface moves with Ω·r along t):
//   v_T = V·t - Ω·r
//   μ(v_T) = μ_i·sat(v_T/Δv),  sat(x) = max(-1, min(1, x))      (μ_i travels with the element)
//   force on the element   F_T = -μ(v_T)·N·t
//   moment on the pulley   M_T = r × (-F_T) = r·μ(v_T)·N           (the reaction of F_T)
// Derivatives, with μ' = μ_i/Δv for |v_T| < Δv and 0 outside, ∂t/∂P = -n·tᵀ/r:
//   ∂v_T/∂P = -(V·n)/r·tᵀ - Ω·nᵀ,   ∂v_T/∂V = tᵀ,   ∂v_T/∂Ω = -r
//   ∂F_T/∂P = -t·(N·μ'·∂v_T/∂P + μ·∂N/∂P) + μ·N·n·tᵀ/r
//   ∂F_T/∂V = -t·(N·μ'·tᵀ + μ·∂N/∂V),   ∂F_T/∂Ω = t·N·μ'·r
//   ∂M_T/∂P = μ·N·nᵀ + r·(N·μ'·∂v_T/∂P + μ·∂N/∂P)
//   ∂M_T/∂V = r·(N·μ'·tᵀ + μ·∂N/∂V),     ∂M_T/∂Ω = -r²·N·μ'
// Dissipated power μ(v_T)·N·v_T >= 0. In the linear zone the slope μ_i·N/(m·Δv) is the stiffest
// eigenvalue of the whole model (≈ 5e9 1/s for the paper's drive, DESIGN §5).
//
// Newton across the band (friction_reseat): at a slipping iterate (|v_T| >= Δv) the friction
// force is locally constant, so a Newton step cannot see the band; when the step would carry
// v_T from one side of the band right across to the other, the solution is almost always
// sticking (|v_T| < Δv). friction_reseat then puts the element back into the band (v_T = 0,
// moving its velocity along t̂) before the next Newton step, which sees the band's slope and
// lands on the sticking solution, or leaves the band again if the element truly slips.
//
// Local solve (friction_local_solve): an implicit stage solves G(Z) = Z - ψ - F(Z)/s = 0. For
// one element in contact, move its velocity by w·t̂ (and its position by w·t̂/s, which keeps the
// position rows G_q = Z_q - ψ_q - Z_v/s at zero and leaves the penetration unchanged to first
// order) with everything else held. Its tangential residual is then
//   g(w) = g0 + A·w + B·(sat((u0 + w)/Δv) - sat(u0/Δv)),
//   A = 1 + (2c + 2k/s)/(m·s)   (the two SDEs' dampers and springs resisting the move),
//   B = μ_i·N/(m·s)             (friction, saturated outside the band),
// with u0 the slip velocity and g0 = t̂·G_v at the iterate. g is increasing and piecewise linear
// in w, so g(w) = 0 is solved exactly by trying the three pieces (slip forwards, slip backwards,
// stick: w = -(g0 + B·(u0/Δv - sat0))/(A + B/Δv)).
#include <algorithm>
#include <cmath>

#include "model/contact_law.hpp"

namespace beltsim {

FrictionLaw friction_law(double mu_i, double dv, const NormalLaw& nl, const Vec2& V, double omega) {
  FrictionLaw fl;
  fl.vT = V.dot(nl.t) - omega * nl.r;
  const double x = fl.vT / dv;
  if (std::abs(x) < 1.0) {
    fl.mu_eff = mu_i * x;
    fl.dmu = mu_i / dv;
  } else {
    fl.mu_eff = std::copysign(mu_i, x);
    fl.dmu = 0.0;
  }
  return fl;
}

void friction_jacobian(const NormalLaw& nl, const FrictionLaw& fl, const Vec2& V, double omega, PairJacobian& J) {
  const double N = nl.N, mu = fl.mu_eff, r = nl.r;
  const Eigen::RowVector2d dvT_dP = -(V.dot(nl.n) / r) * nl.t.transpose() - omega * nl.n.transpose();
  const Eigen::RowVector2d dvT_dV = nl.t.transpose();
  const Eigen::RowVector2d dmuN_dP = N * fl.dmu * dvT_dP + mu * nl.dN_dP;  // ∂(μN)/∂P
  const Eigen::RowVector2d dmuN_dV = N * fl.dmu * dvT_dV + mu * nl.dN_dV;
  J.dF_dP = -nl.t * dmuN_dP + (mu * N / r) * nl.n * nl.t.transpose();
  J.dF_dV = -nl.t * dmuN_dV;
  J.dF_dOmega = nl.t * (N * fl.dmu * r);
  J.dM_dP = mu * N * nl.n.transpose() + r * dmuN_dP;
  J.dM_dV = r * dmuN_dV;
  J.dM_dOmega = -r * r * N * fl.dmu;
}

int friction_local_solve(const Model& m, double t, double s, double* q, double* v, const double* g) {
  const double band = m.friction.dv;
  const Belt& bl = m.belt;
  // the element's own linear resistance to a tangential velocity change w inside one stage: its
  // two SDEs' dampers (2c) and, through the position change w/s, springs (2k), per unit mass
  const double lam = (2 * bl.c + 2 * bl.k / s) / (bl.mass * s);
  const double A = 1 + lam;
  int moved = 0;
  for (int j = 0; j < m.n_p(); ++j) {
    const Pulley& pl = m.pulleys[j];
    const double omega = m.omega(j, t, v);
    for (int i = 0; i < m.belt.n; ++i) {
      const Vec2 P(q[3 * i], q[3 * i + 1]), V(v[3 * i], v[3 * i + 1]);
      NormalLaw nl;
      if (!normal_law(m.contact, P, V, pl.centre, pl.radius, nl) || !nl.pushing) continue;
      const double u0 = V.dot(nl.t) - omega * nl.r;
      const double x0 = std::clamp(u0 / band, -1.0, 1.0);
      const double g0 = g[3 * i] * nl.t.x() + g[3 * i + 1] * nl.t.y();
      const double B = m.mu[i] * nl.N / (s * bl.mass);
      double w = -(g0 + B * (1 - x0)) / A;  // slipping forwards
      if (u0 + w < band) {
        w = -(g0 + B * (-1 - x0)) / A;  // backwards
        if (u0 + w > -band) w = -(g0 + B * (u0 / band - x0)) / (A + B / band);  // sticking
      }
      if (w == 0) continue;
      v[3 * i] += w * nl.t.x();
      v[3 * i + 1] += w * nl.t.y();
      q[3 * i] += w / s * nl.t.x();
      q[3 * i + 1] += w / s * nl.t.y();
      ++moved;
    }
  }
  return moved;
}

int friction_reseat(const Model& m, double t, double* q, double* v, const double* dq, const double* dv) {
  const double band = m.friction.dv;
  int moved = 0;
  for (int j = 0; j < m.n_p(); ++j) {
    const Pulley& pl = m.pulleys[j];
    const int pc = m.pulley_coord(j);
    const double omega0 = m.omega(j, t, v);
    const double omega1 = pl.kinematic ? omega0 : omega0 + dv[pc];
    for (int i = 0; i < m.belt.n; ++i) {
      const Vec2 P0(q[3 * i], q[3 * i + 1]), V0(v[3 * i], v[3 * i + 1]);
      NormalLaw a;
      if (!normal_law(m.contact, P0, V0, pl.centre, pl.radius, a) || !a.pushing) continue;
      const double vt0 = V0.dot(a.t) - omega0 * a.r;
      if (std::abs(vt0) < band) continue;
      const Vec2 P1 = P0 + Vec2(dq[3 * i], dq[3 * i + 1]), V1 = V0 + Vec2(dv[3 * i], dv[3 * i + 1]);
      NormalLaw b;
      if (!normal_law(m.contact, P1, V1, pl.centre, pl.radius, b)) continue;
      const double vt1 = V1.dot(b.t) - omega1 * b.r;
      if (std::abs(vt1) < band || (vt1 > 0) == (vt0 > 0)) continue;
      v[3 * i] -= vt0 * a.t.x();
      v[3 * i + 1] -= vt0 * a.t.y();
      ++moved;
    }
  }
  return moved;
}

}  // namespace beltsim
