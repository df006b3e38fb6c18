// LuGre's friction law (Canudas de Wit et al., 1995) for an element–pulley pair, with one bristle
// deflection z_i [m] per element, a state of its own (Model::friction.law = lugre):
//
//   g(v) = μ_i·(1 + (μ_s/μ_k - 1)·exp(-(|v|/v_s)^δ))     Stribeck's curve, μ_i the element's μ_k
//   ż    = v_T - σ0·|v_T|·z/g(v_T)                       in contact (p > 0)
//   ż    = -z/τ                                          out of contact: the bristles let go
//   μ    = σ0·z + σ1·ż + μ_v·v_T,   F_T = -μ·N·t on the element, M_T = r·μ·N on the pulley
//
// with v_T = V·t - Ω·r the slip velocity of friction.cpp. On a belt whose segments have laws of
// their own (Model::law_of) only the elements under LuGre's carry a deflection: the others' z
// stays 0 (ż = 0). At rest under a tangential load the
// deflection settles at z = μ/σ0 (|μ| < g(0) = μ_s) and the element stays put: no drift, unlike
// the regularised laws, whose elements creep at Δv·μ/μ_i. Sliding steadily, z = g(v)·sgn(v)/σ0 and
// μ = g(v)·sgn(v) + μ_v·v: Stribeck's curve. A belt element holds σ0·N [N/m] of tangential
// stiffness in stick (N its normal force), its eigenvalue σ0·N/m: at the default σ0 = 1e5 1/m that
// of Threlfall's band at the paper's Δv (μ/Δv = 1e5 1/m for μ = 1).
//
// Derivatives (contact_law.hpp: bristle_law), with a = (|v|/v_s)^δ and v·g'(v) = -(g - μ_i)·δ·a:
//   ∂ż/∂v_T = 1 - σ0·z·sgn(v_T)·(g + δ·a·(g - μ_i))/g²,   ∂ż/∂z = -σ0·|v_T|/g
//   ∂μ/∂v_T = σ1·∂ż/∂v_T + μ_v (friction.cpp's μ' at a fixed z),  ∂μ/∂z = σ0 + σ1·∂ż/∂z
// and through v_T (friction.cpp): ∂v_T/∂P = -(V·n)/r·tᵀ - Ω·nᵀ, ∂v_T/∂V = tᵀ, ∂v_T/∂Ω = -r; on a
// tensioner arm (centre c(ψ), lever λ = ∂c/∂ψ, V relative to ψ̇·λ): ∂v_T/∂ψ = -∂v_T/∂P·λ +
// ψ̇·t·(c - pivot), ∂v_T/∂ψ̇ = -t·λ. The forces' columns: ∂F_i/∂z_i = -N·∂μ/∂z·t,
// ∂M_j/∂z_i = r·N·∂μ/∂z, and an arm's moment -F·λ gives -∂F_i/∂z_i·λ. ż has a kink at v_T = 0
// (|v_T|) and a jump at contact onset, which the contact switches locate.
//
// Linear solves (bristle_eliminate): the rows of z in (s·I - ∂F/∂y)·u = r are
//   (s - ∂ż_i/∂z_i)·u_z,i - H_q,i·u_q - H_v,i·u_v = r_z,i
// (H_q,i, H_v,i: row i of ∂ż/∂q, ∂ż/∂v), so u_z = D·(r_z + H_q·u_q + H_v·u_v), D_i = 1/(s - ∂ż_i/∂z_i)
// (> 0: ∂ż/∂z <= 0). The velocity rows s·M·u_v - K·u_q - C·u_v - Z·u_z = M·r_v then read
//   s·M·u_v - (K + Z·D·H_q)·u_q - (C + Z·D·H_v)·u_v = M·r_v + Z·D·r_z
// the mechanical system with K' and C' of the same pattern (Z·D·H touches element i's own block
// and the border only), solved as before by the ring solver.
#include "model/bristles.hpp"

#include <cmath>

#include "model/contact_law.hpp"

namespace beltsim {

void BristleJacobian::resize(int n_el, int n_border) {
  dz.assign(n_el, 0.0);
  dP.assign(n_el, Vec2::Zero());
  dV.assign(n_el, Vec2::Zero());
  F.assign(n_el, Vec2::Zero());
  t.assign(n_el, 0.0);
  dq_b.setZero(n_el, n_border);
  dv_b.setZero(n_el, n_border);
  F_b.setZero(n_border, n_el);
}

void BristleJacobian::clear(const Model& m) {
  resize(static_cast<int>(dz.size()), static_cast<int>(dq_b.cols()));
  for (int i = 0; i < m.n_el(); ++i) {
    const Friction& f = m.friction_of(i);
    dz[i] = f.law == FrictionKind::lugre ? -1.0 / f.release_time : 0.0;
  }
}

void bristle_rates(const Model& m, const double* z, const ContactView& pairs, double* dz) {
  for (int i = 0; i < m.n_el(); ++i) {
    const Friction& f = m.friction_of(i);
    dz[i] = f.law == FrictionKind::lugre ? -z[i] / f.release_time : 0.0;
  }
  for (const ContactPair& c : pairs) {
    const Friction& f = m.friction_of(c.i);
    if (c.touching && f.law == FrictionKind::lugre) dz[c.i] = bristle_law(c.mu, f, c.fl.vT, z[c.i]).zdot;
  }
}

void bristle_jacobian(const Model& m, const Drive& d, double t, const double* q, const double* v, const double* z,
                      const ContactView& pairs, BristleJacobian& B) {
  for (const ContactPair& c : pairs) {
    const Friction& f = m.friction_of(c.i);
    if (!c.touching || f.law != FrictionKind::lugre) continue;
    const int i = c.i, j = c.j;
    const NormalLaw& nl = c.nl;
    const Vec2 V = Vec2(v[3 * i], v[3 * i + 1]) - m.centre_velocity(j, q, v);
    const Bristle b = bristle_law(c.mu, f, c.fl.vT, z[i]);
    const Vec2 dvT_dP = slip_velocity_dP(nl, V, c.omega);
    B.dz[i] = b.dzdot_dz;
    B.dP[i] = b.dzdot_dv * dvT_dP;
    B.dV[i] = b.dzdot_dv * nl.t;
    const bool kinematic = d.kinematic(j);
    if (kinematic)
      B.t[i] = -b.dzdot_dv * nl.r * d.speed_rate(j, t);
    else
      B.dv_b(i, j) = -b.dzdot_dv * nl.r;
    const Vec2 dF_dz = nl.pushing ? Vec2(-nl.N * b.dmu_dz * nl.t) : Vec2::Zero();
    B.F[i] = dF_dz;
    if (!kinematic && nl.pushing) B.F_b(j, i) = nl.r * nl.N * b.dmu_dz;
    const int a = m.pulleys[j].arm;
    if (a >= 0) {
      const int col = m.n_p() + a;
      const Vec2 lever = arm_lever(m, a, q);
      const Vec2 radial = m.centre(j, q) - m.arms[a].pivot;  // ∂λ/∂ψ = -radial
      const double rate = v[m.arm_coord(a)];
      B.dq_b(i, col) = b.dzdot_dv * (-dvT_dP.dot(lever) + rate * nl.t.dot(radial));
      B.dv_b(i, col) = -b.dzdot_dv * nl.t.dot(lever);
      B.F_b(col, i) = -dF_dz.dot(lever);
    }
  }
}

void bristle_eliminate(const Model& m, const BristleJacobian& B, double s, const BlockMatrix& K, const BlockMatrix& C,
                       BlockMatrix& K_eff, BlockMatrix& C_eff, std::vector<double>& D) {
  const int n = m.n_el(), nb = m.n_border();
  K_eff = K;
  C_eff = C;
  D.resize(n);
  for (int i = 0; i < n; ++i) {
    D[i] = 1.0 / (s - B.dz[i]);
    const Vec2 Fi = D[i] * B.F[i];  // Z·D, element rows
    // element rows × element columns
    K_eff.diag[i].topLeftCorner<2, 2>() += Fi * B.dP[i].transpose();
    C_eff.diag[i].topLeftCorner<2, 2>() += Fi * B.dV[i].transpose();
    for (int b = 0; b < nb; ++b) {
      // element rows × border columns, border rows × element and border columns
      const double hq = B.dq_b(i, b), hv = B.dv_b(i, b), zb = D[i] * B.F_b(b, i);
      if (hq == 0.0 && hv == 0.0 && zb == 0.0) continue;  // adds nothing
      K_eff.mark(i, b), C_eff.mark(i, b);
      for (int r = 0; r < 2; ++r) {
        K_eff.elem_pulley(3 * i + r, b) += Fi[r] * hq;
        C_eff.elem_pulley(3 * i + r, b) += Fi[r] * hv;
        K_eff.pulley_elem(b, 3 * i + r) += zb * B.dP[i][r];
        C_eff.pulley_elem(b, 3 * i + r) += zb * B.dV[i][r];
      }
      if (zb == 0.0) continue;
      for (int c = 0; c < nb; ++c) {
        K_eff.pulley_pulley(b, c) += zb * B.dq_b(i, c);
        C_eff.pulley_pulley(b, c) += zb * B.dv_b(i, c);
      }
    }
  }
}

void bristle_load(const Model& m, const BristleJacobian& B, const std::vector<double>& D, const double* r_z, double* f) {
  const int n = m.n_el(), nb = m.n_border();
  for (int i = 0; i < n; ++i) {
    const double w = D[i] * r_z[i];
    f[3 * i] += B.F[i].x() * w;
    f[3 * i + 1] += B.F[i].y() * w;
    for (int b = 0; b < nb; ++b) f[3 * n + b] += B.F_b(b, i) * w;
  }
}

void bristle_back(const Model& m, const BristleJacobian& B, const std::vector<double>& D, const double* r_z,
                  const double* u_q, const double* u_v, double* u_z) {
  const int n = m.n_el(), nb = m.n_border();
  for (int i = 0; i < n; ++i) {
    double h = r_z[i] + B.dP[i].dot(Vec2(u_q[3 * i], u_q[3 * i + 1])) + B.dV[i].dot(Vec2(u_v[3 * i], u_v[3 * i + 1]));
    for (int b = 0; b < nb; ++b) h += B.dq_b(i, b) * u_q[3 * n + b] + B.dv_b(i, b) * u_v[3 * n + b];
    u_z[i] = D[i] * h;
  }
}

}  // namespace beltsim
