// Pulleys (paper eq. 8) and gravity.
//
// A free pulley j turns under its applied torque and the belt's friction reactions:
//   I_j·Ω̇_j = M_d(t, Ω_j) + Σ_i r_ji·μ_ji·N_ji          (the sum is added in contact.cpp)
//   M_d(t, Ω) = constant + per_speed·Ω + table(t)        ∂M_d/∂Ω = per_speed, ∂M_d/∂t = table'(t)
// A kinematic pulley follows a prescribed Ω(t): its row is Ω̇ = Ω'(t) with unit "mass", nothing
// depends on its state Ω (the prescribed value is used instead), and the drive's power is
// (I·Ω' - M_belt)·Ω. Gravity: m·g along -y on every element centre, potential m·g·y.
#include "model/forces.hpp"

namespace beltsim {

double applied_torque(const Model& m, double t, const double* v, int j) {
  const Pulley& p = m.pulleys[j];
  if (p.kinematic) return 0.0;
  return p.torque.eval(t, v[m.pulley_coord(j)]);
}

void pulley_forces(const Model& m, double t, const double* v, double* f, double* e_rate) {
  for (int j = 0; j < m.n_p(); ++j) {
    const Pulley& p = m.pulleys[j];
    const int k = m.pulley_coord(j);
    if (p.kinematic) {
      const double rate = p.speed.table_slope(t);
      f[k] += rate;
      if (e_rate) e_rate[kWorkTorques] += p.inertia * rate * p.speed.eval(t, 0.0);
    } else {
      const double M = p.torque.eval(t, v[k]);
      f[k] += M;
      if (e_rate) e_rate[kWorkTorques] += M * v[k];
    }
  }
}

void pulley_jacobian(const Model& m, double t, const double*, BlockMatrix& C, double* f_t) {
  for (int j = 0; j < m.n_p(); ++j) {
    const Pulley& p = m.pulleys[j];
    if (p.kinematic) continue;  // Ω'(t) is piecewise constant: no derivative
    C.pulley_pulley(j, j) += p.torque.per_speed;
    if (f_t) f_t[m.pulley_coord(j)] += p.torque.table_slope(t);
  }
}

void gravity_forces(const Model& m, double* f) {
  const double w = m.belt.mass * m.gravity;
  for (int i = 0; i < m.belt.n; ++i) f[3 * i + 1] -= w;
}

double gravity_potential(const Model& m, const double* q) {
  double u = 0;
  for (int i = 0; i < m.belt.n; ++i) u += m.belt.mass * m.gravity * q[3 * i + 1];
  return u;
}

}  // namespace beltsim
