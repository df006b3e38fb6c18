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
