// Spring-loaded tensioner arms.
//
// Arm a holds pulley j's centre at c = P0 + L·e(ψ), e(ψ) = (cos ψ, sin ψ), about its pivot P0;
// ψ is a coordinate of the state (Model::arm_coord), with the lever g = ∂c/∂ψ = L·(-sin ψ, cos ψ)
// and h = c - P0 = L·e(ψ), ∂g/∂ψ = -h. The centre's velocity is V_c = g·ψ̇.
//
// Arm equation (I_a about the pivot, the pulley's mass included):
//   I_a·ψ̈ = -k·(ψ - ψ0) - s(ψ̇)·(c·ψ̇ + T_f·tanh(ψ̇/w_f)) - g·Σ F_i
// with F_i the force of pair i (element i on the arm's pulley, contact.cpp) on its element: the
// pulley takes -F_i at its centre, whose moment about the pivot is -g·F_i. The friction torque is
// T_f·tanh(ψ̇/w_f): smooth (C∞) through ψ̇ = 0, within 1 % of ±T_f beyond |ψ̇| = 2.65·w_f, so the
// integrator sees no jump; it cannot hold the arm still against a moment below T_f (it creeps at
// ψ̇ ≈ w_f·M/T_f). s(ψ̇) = `asymmetric` while the belt pushes the arm back (press·ψ̇ < 0, press the
// sense in which the spring presses the pulley on the belt), else 1: continuous, as its factor is
// zero at ψ̇ = 0 (a kink only).
//   ∂Q/∂ψ = -k,   ∂Q/∂ψ̇ = -s·(c + T_f/w_f·(1 - tanh²(ψ̇/w_f)))
// Potential k·(ψ - ψ0)²/2; dissipated power s·(c·ψ̇² + T_f·tanh(ψ̇/w_f)·ψ̇) ≥ 0 (EnergyIndex's
// kDissArms).
//
// The pairs on the arm's pulley see the element relative to the centre: F_i = F(P_i - c, V_i - V_c, Ω)
// (contact_law.hpp), so with A_P = ∂F/∂P, A_V = ∂F/∂V (relative), ∂V_c/∂ψ = -ψ̇·h, ∂V_c/∂ψ̇ = g:
//   element rows   ∂F/∂ψ = -A_P·g + ψ̇·A_V·h,        ∂F/∂ψ̇ = -A_V·g
//   arm row        ∂Q/∂P_i = -gᵀ·A_P,  ∂Q/∂V_i = -gᵀ·A_V,  ∂Q/∂Ω = -gᵀ·∂F/∂Ω
//                  ∂Q/∂ψ = -gᵀ·∂F/∂ψ + F·h,          ∂Q/∂ψ̇ = -gᵀ·∂F/∂ψ̇
//   pulley row     ∂M/∂ψ = -∂M/∂P·g + ψ̇·∂M/∂V·h,    ∂M/∂ψ̇ = -∂M/∂V·g
// (M = r·μ·N the pair's moment on the pulley, friction.cpp). The pulley turns on a bearing on the
// arm: its own equation keeps its moment about its centre, the arm takes none of it.
#include <cmath>

#include "model/contact_law.hpp"
#include "model/forces.hpp"

namespace beltsim {

namespace {
struct ArmLaw {
  double Q = 0, dQ_dpsi = 0, dQ_drate = 0, dissipated = 0;
};
ArmLaw arm_law(const Arm& a, double psi, double rate) {
  ArmLaw o;
  const double s = a.press * rate < 0 ? a.asymmetric : 1.0;
  const double th = std::tanh(rate / a.friction_speed);
  const double resist = s * (a.damping * rate + a.friction_torque * th);
  o.Q = -a.stiffness * (psi - a.free_angle) - resist;
  o.dQ_dpsi = -a.stiffness;
  o.dQ_drate = -s * (a.damping + a.friction_torque / a.friction_speed * (1 - th * th));
  o.dissipated = resist * rate;
  return o;
}
}  // namespace

void arm_forces(const Model& m, const double* q, const double* v, double* f, double* e_rate) {
  for (int a = 0; a < m.n_arm(); ++a) {
    const int k = m.arm_coord(a);
    const ArmLaw l = arm_law(m.arms[a], q[k], v[k]);
    f[k] += l.Q;
    if (e_rate) e_rate[kDissArms] += l.dissipated;
  }
}

void arm_jacobian(const Model& m, const double* q, const double* v, BlockMatrix& K, BlockMatrix& C) {
  for (int a = 0; a < m.n_arm(); ++a) {
    const int k = m.arm_coord(a), b = m.n_p() + a;
    const ArmLaw l = arm_law(m.arms[a], q[k], v[k]);
    K.pulley_pulley(b, b) += l.dQ_dpsi;
    C.pulley_pulley(b, b) += l.dQ_drate;
  }
}

void arm_pair_jacobian(const Model& m, int a, const double* q, const double* v, const Vec2& F,
                       const Eigen::Matrix2d& dF_dP, const Eigen::Matrix2d& dF_dV, const PairJacobian& J, int i,
                       BlockMatrix& K, BlockMatrix& C) {
  const Arm& arm = m.arms[a];
  const int j = arm.pulley, b = m.n_p() + a;
  const double psi = q[m.arm_coord(a)], rate = v[m.arm_coord(a)];
  const Vec2 g = arm_lever(m, a, q), h = arm.length * Vec2(std::cos(psi), std::sin(psi));
  const Vec2 dF_dpsi = -dF_dP * g + rate * (dF_dV * h);
  const Vec2 dF_drate = -dF_dV * g;
  // element rows
  K.mark(i, b), C.mark(i, b);
  K.elem_pulley.block<2, 1>(3 * i, b) += dF_dpsi;
  C.elem_pulley.block<2, 1>(3 * i, b) += dF_drate;
  // arm row
  K.pulley_elem.block<1, 2>(b, 3 * i) -= g.transpose() * dF_dP;
  C.pulley_elem.block<1, 2>(b, 3 * i) -= g.transpose() * dF_dV;
  C.pulley_pulley(b, j) -= g.dot(J.dF_dOmega);
  K.pulley_pulley(b, b) += -g.dot(dF_dpsi) + F.dot(h);
  C.pulley_pulley(b, b) -= g.dot(dF_drate);
  // the pulley's row
  K.pulley_pulley(j, b) += -J.dM_dP.dot(g) + rate * J.dM_dV.dot(h);
  C.pulley_pulley(j, b) -= J.dM_dV.dot(g);
}

double arm_potential(const Model& m, const double* q) {
  double u = 0;
  for (int a = 0; a < m.n_arm(); ++a) {
    const double d = q[m.arm_coord(a)] - m.arms[a].free_angle;
    u += 0.5 * m.arms[a].stiffness * d * d;
  }
  return u;
}

}  // namespace beltsim
