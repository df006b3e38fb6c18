// Pulleys (paper eq. 8) and gravity.
//
// A free pulley j turns under its applied torque and the belt's friction reactions:
//   I_j·Ω̇_j = M_d(t, Ω_j) + Σ_i r_ji·μ_ji·N_ji          (the sum is added in contact.cpp)
// with M_d a law of laws.hpp (its terms and their derivatives are at the top of laws.cpp):
//   ∂(I·Ω̇)/∂Ω = ∂M_d/∂Ω (the Jacobian's C block),      ∂(I·Ω̇)/∂t = ∂M_d/∂t (f_t).
// A kinematic pulley follows a prescribed Ω(t): its row is Ω̇ = Ω'(t) with unit "mass", nothing
// depends on its state Ω (the prescribed value is used instead), ∂(Ω̇)/∂t = Ω''(t), and the
// drive's power is (I·Ω' - M_belt)·Ω. A step of Ω(t) is a jump of the state, made by the
// simulation where it lands on the step (Simulation::set_landings).
// A coupled pulley (coupling.cpp): its law M_d(t, Ω_r) acts on the rotor, at the rotor's speed Ω_r.
// Gravity: m·g along -y on every element centre, potential m·g·y.
#include "model/forces.hpp"

namespace beltsim {

namespace {
// the coordinate the applied torque of pulley j acts on: the pulley's, or its coupled rotor's
int torque_coord(const Model& m, int j) {
  const int c = m.pulleys[j].coupling;
  return c < 0 ? m.pulley_coord(j) : m.rotor_coord(c);
}
}  // namespace

double applied_torque(const Model& m, const Drive& d, double t, const double* v, int j) {
  const PulleyDrive& p = d.pulleys[j];
  if (p.kinematic) return 0.0;
  return p.torque.eval(t, v[torque_coord(m, j)], d.after_jump(t));
}

void pulley_forces(const Model& m, const Drive& d, double t, const double* v, double* f, double* e_rate) {
  for (int j = 0; j < m.n_p(); ++j) {
    const PulleyDrive& p = d.pulleys[j];
    const int k = m.pulley_coord(j);
    if (p.kinematic) {
      const double rate = d.speed_rate(j, t);
      f[k] += rate;
      if (e_rate) e_rate[kWorkTorques] += m.pulleys[j].inertia * rate * d.omega(m, j, t, v);
    } else {
      const int kt = torque_coord(m, j);
      const double M = p.torque.eval(t, v[kt], d.after_jump(t));
      f[kt] += M;
      if (e_rate) e_rate[kWorkTorques] += M * v[kt];
    }
  }
}

void pulley_jacobian(const Model& m, const Drive& d, double t, const double* v, BlockMatrix& C, double* f_t) {
  for (int j = 0; j < m.n_p(); ++j) {
    const PulleyDrive& p = d.pulleys[j];
    const int k = m.pulley_coord(j);
    if (p.kinematic) {
      if (f_t) f_t[k] += p.speed.d_time2(t);
      continue;
    }
    const int kt = torque_coord(m, j), b = kt - 3 * m.n_el();
    C.pulley_pulley(b, b) += p.torque.d_omega(t, v[kt]);
    if (f_t) f_t[kt] += p.torque.d_time(t, v[kt]);
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
