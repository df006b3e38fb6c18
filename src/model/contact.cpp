// Belt–pulley contact (paper eq. 2, Fig. 3): penalty normal force with a depth-ramped damper.
//
// Element centre P (velocity V), pulley centre c, contact radius R:
//   r = |P - c|,  n = (P - c)/r,  t = (-n_y, n_x),  p = R - r (contact when p > 0),  ṗ = -n·V
//   N = max(0, c1·p² + c2·p + δ(p)·b·ṗ),  δ(p) = min(p/p_max, 1)
// and the element feels N·n (a contact never pulls: N is clamped at zero).
// Derivatives (while N > 0; zero when clamped or out of contact):
//   ∂p/∂P = -nᵀ,  ∂n/∂P = t·tᵀ/r,  ∂ṗ/∂P = -(V·t)/r·tᵀ,  ∂ṗ/∂V = -nᵀ,  δ' = 1/p_max (p < p_max)
//   ∂N/∂P = -(2·c1·p + c2 + δ'·b·ṗ)·nᵀ - δ·b·(V·t)/r·tᵀ,    ∂N/∂V = -δ·b·nᵀ
//   ∂(N·n)/∂P = n·∂N/∂P + N·t·tᵀ/r,                         ∂(N·n)/∂V = n·∂N/∂V
// The normal force has no moment about the pulley centre. Potential c1·p³/3 + c2·p²/2;
// dissipated power (N - N_el)·ṗ with N_el = c1·p² + c2·p (damping, and the work the clamp removes).
// Friction of the same pair is in friction.cpp; this file loops over pairs and assembles both.
// A pulley on a tensioner arm: P and V above are relative to its moving centre, and the arm takes
// the reaction of the pairs' forces (tensioner.cpp).
#include <cmath>
#include <limits>

#include "model/contact_law.hpp"

namespace beltsim {

NormalJacobian normal_law_derivatives(const Contact& c, const Vec2& V, const NormalLaw& o) {
  NormalJacobian d;
  if (!o.pushing) {
    d.dN_dP.setZero();
    d.dN_dV.setZero();
    return d;
  }
  const double ddelta = o.p < c.p_max ? 1.0 / c.p_max : 0.0;
  const double vt = V.dot(o.t);
  d.dN_dP = -(2 * c.c1 * o.p + c.c2 + ddelta * c.b * o.pdot) * o.n.transpose() -
            o.delta * c.b * vt / o.r * o.t.transpose();
  d.dN_dV = -o.delta * c.b * o.n.transpose();
  return d;
}

void contact_forces(const Model& m, const Drive& d, const double* q, const ContactList& pairs, double* f,
                    double* f_pulley, double* e_rate) {
  // pairs come pulley by pulley: each pulley's moment is summed over its pairs, then added
  int at = 0;
  const int np = static_cast<int>(pairs.size());
  for (int j = 0; j < m.n_p(); ++j) {
    double moment = 0, omega = 0;
    Vec2 load = Vec2::Zero();  // Σ F over the pairs: the belt's hub load is its negative
    for (; at < np && pairs[at].j == j; ++at) {
      const ContactPair& c = pairs[at];
      const NormalLaw& nl = c.nl;
      omega = c.omega;
      if (!c.touching) continue;
      if (e_rate) e_rate[kDissContact] += (nl.N - nl.N_el) * nl.pdot;
      if (!nl.pushing) continue;
      const FrictionLaw& fl = c.fl;
      const int i = c.i;
      const Vec2 F = nl.N * nl.n - fl.mu_eff * nl.N * nl.t;
      f[3 * i] += F.x();
      f[3 * i + 1] += F.y();
      load += F;
      moment += nl.r * fl.mu_eff * nl.N;
      if (e_rate) e_rate[kDissFriction] += fl.mu_eff * nl.N * fl.vT;
    }
    if (!d.kinematic(j)) {
      f_pulley[j] += moment;
    } else if (e_rate) {
      e_rate[kWorkTorques] -= moment * omega;  // the drive holds the speed against the belt
    }
    const int a = m.pulleys[j].arm;
    if (a >= 0) f_pulley[m.n_p() + a] -= load.dot(arm_lever(m, a, q));
  }
}

void contact_jacobian(const Model& m, const Drive& d, double t, const double* q, const double* v,
                      const ContactList& pairs, BlockMatrix& K, BlockMatrix& C, double* f_t, double* dM_dOmega) {
  int at = 0;
  const int np = static_cast<int>(pairs.size());
  for (int j = 0; j < m.n_p(); ++j) {
    const bool kinematic = d.kinematic(j);
    const double omega_rate = kinematic ? d.speed_rate(j, t) : 0.0;
    const Vec2 vc = m.centre_velocity(j, q, v);  // the laws take velocities relative to the centre
    const int arm = m.pulleys[j].arm;
    double dmo = 0;  // Σ ∂M/∂Ω over the pairs (the block is zero before: the same sum as adding in place)
    for (; at < np && pairs[at].j == j; ++at) {
      const ContactPair& c = pairs[at];
      if (!c.touching || !c.nl.pushing) continue;
      const int i = c.i;
      const Vec2 V = Vec2(v[3 * i], v[3 * i + 1]) - vc;
      const NormalLaw& nl = c.nl;
      const NormalJacobian dn = normal_law_derivatives(m.contact, V, nl);
      // normal force
      const Eigen::Matrix2d dNn_dP = nl.n * dn.dN_dP + nl.N / nl.r * nl.t * nl.t.transpose();
      const Eigen::Matrix2d dNn_dV = nl.n * dn.dN_dV;
      K.diag[i].topLeftCorner<2, 2>() += dNn_dP;
      C.diag[i].topLeftCorner<2, 2>() += dNn_dV;
      // friction
      PairJacobian J;
      friction_jacobian(nl, dn, c.fl, V, c.omega, J);
      K.diag[i].topLeftCorner<2, 2>() += J.dF_dP;
      C.diag[i].topLeftCorner<2, 2>() += J.dF_dV;
      if (kinematic) {
        // Omega(t) is prescribed: its effect enters as an explicit time dependence
        if (f_t) {
          f_t[3 * i] += J.dF_dOmega.x() * omega_rate;
          f_t[3 * i + 1] += J.dF_dOmega.y() * omega_rate;
        }
        continue;
      }
      K.mark(i, j), C.mark(i, j);
      C.elem_pulley.block<2, 1>(3 * i, j) += J.dF_dOmega;
      K.pulley_elem.block<1, 2>(j, 3 * i) += J.dM_dP;
      C.pulley_elem.block<1, 2>(j, 3 * i) += J.dM_dV;
      dmo += J.dM_dOmega;
      if (arm >= 0) {
        const Vec2 F = nl.N * nl.n - c.fl.mu_eff * nl.N * nl.t;
        arm_pair_jacobian(m, arm, q, v, F, dNn_dP + J.dF_dP, dNn_dV + J.dF_dV, J, i, K, C);
      }
    }
    if (kinematic) continue;
    if (dM_dOmega) {
      dM_dOmega[j] += dmo;
    } else {
      C.pulley_pulley(j, j) += dmo;
    }
  }
}

double contact_potential(const Model& m, const double* q) {
  double u = 0;
  for (int j = 0; j < m.n_p(); ++j) {
    const Pulley& pl = m.pulleys[j];
    const Vec2 centre = m.centre(j, q);
    for (int i = 0; i < m.belt.n; ++i) {
      const double r = (Vec2(q[3 * i], q[3 * i + 1]) - centre).norm();
      const double p = pl.radius - r;
      if (p > 0) u += m.contact.c1 * p * p * p / 3.0 + m.contact.c2 * p * p / 2.0;
    }
  }
  return u;
}

}  // namespace beltsim
