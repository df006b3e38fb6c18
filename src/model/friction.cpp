// Friction of one element–pulley pair in contact: the paper's simplified Threlfall law (eqs. 3–4,
// Fig. 4), and Stribeck's (below).
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
// Stribeck's law (Model::friction.law = stribeck) replaces μ(v_T) and μ' above and changes nothing
// else (friction_jacobian reads μ and μ' only). With the element's μ_i as its kinetic coefficient
// μ_k, s = μ_s/μ_k (static_ratio), v_s (stribeck_speed), δ (exponent), μ_v (viscous):
//   a = (|v_T|/v_s)^δ,   g(v_T) = 1 + (s - 1)·e^(-a)          (g: μ_s/μ_k at rest, 1 at large slip)
//   μ(v_T) = μ_i·g(v_T)·sat(v_T/Δv) + μ_v·v_T
//   μ' = μ_i·(g - (g - 1)·δ·a)/Δv + μ_v                      |v_T| < Δv
//   μ' = -μ_i·(g - 1)·δ·a/|v_T| + μ_v                         |v_T| >= Δv
// (v·g'(v) = -(g - 1)·δ·a, so the band's slope has no 0/0 at v_T = 0). The band Δv regularises
// the step at v_T = 0 as Threlfall's does; with s = 1 and μ_v = 0 the law is Threlfall's to the bit.
// Outside the band μ' <= μ_v: the falling branch of the Stribeck curve.
//
// Dissipated power μ(v_T)·N·v_T >= 0 for both laws. In the linear zone the slope μ_i·N/(m·Δv) is
// the stiffest eigenvalue of the whole model (≈ 5e9 1/s for the paper's drive; docs/integration.md).
//
// The integrator's Newton aids for the band (reseat, local solve) are in
// src/integrate/newton_aids.cpp.
#include <cmath>

#include "model/contact_law.hpp"

namespace beltsim {

void friction_jacobian(const NormalLaw& nl, const NormalJacobian& dn, const FrictionLaw& fl, const Vec2& V, double omega,
                       PairJacobian& J) {
  const double N = nl.N, mu = fl.mu_eff, r = nl.r;
  const Eigen::RowVector2d dvT_dP = slip_velocity_dP(nl, V, omega).transpose();
  const Eigen::RowVector2d dvT_dV = nl.t.transpose();
  const Eigen::RowVector2d dmuN_dP = N * fl.dmu * dvT_dP + mu * dn.dN_dP;  // ∂(μN)/∂P
  const Eigen::RowVector2d dmuN_dV = N * fl.dmu * dvT_dV + mu * dn.dN_dV;
  J.dF_dP = -nl.t * dmuN_dP + (mu * N / r) * nl.n * nl.t.transpose();
  J.dF_dV = -nl.t * dmuN_dV;
  J.dF_dOmega = nl.t * (N * fl.dmu * r);
  J.dM_dP = mu * N * nl.n.transpose() + r * dmuN_dP;
  J.dM_dV = r * dmuN_dV;
  J.dM_dOmega = -r * r * N * fl.dmu;
}

}  // namespace beltsim
