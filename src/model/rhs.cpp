#include "model/rhs.hpp"

#include <algorithm>

#include "model/forces.hpp"

namespace beltsim {

namespace {
void all_forces(const Model& m, double t, const double* q, const double* v, double* f, double* e_rate,
                AxisMemo* axes = nullptr) {
  std::fill(f, f + m.n_coord(), 0.0);
  if (m.gravity != 0.0) gravity_forces(m, f);
  sde_forces(m, q, v, f, e_rate, axes);
  bending_forces(m, q, v, f, e_rate);
  contact_forces(m, t, q, v, f, e_rate);
  pulley_forces(m, t, v, f, e_rate);
}
}  // namespace

void forces(const Model& m, double t, const double* y, double* f) {
  all_forces(m, t, y, y + m.n_coord(), f, nullptr);
}

void rhs(const Model& m, double t, const double* y, double* dy, AxisMemo* axes) {
  const int N = m.n_coord();
  const double* q = y;
  const double* v = y + N;
  double* e_rate = m.track_energy ? dy + 2 * N : nullptr;
  if (e_rate) std::fill(e_rate, e_rate + kEnergyCount, 0.0);
  // positions move with the velocities (a kinematic pulley with its prescribed speed)
  std::copy(v, v + N, dy);
  for (int j = 0; j < m.n_p(); ++j)
    if (m.pulleys[j].kinematic) dy[m.pulley_coord(j)] = m.omega(j, t, v);
  // accelerations
  double* a = dy + N;
  all_forces(m, t, q, v, a, e_rate, axes);
  for (int k = 0; k < N; ++k) a[k] /= m.mass_of(k);
}

void Jacobian::resize(const Model& m) {
  K.resize(m.n_el(), m.n_p());
  C.resize(m.n_el(), m.n_p());
  f_t.setZero(m.n_coord());
}

void jacobian(const Model& m, double t, const double* y, Jacobian& J, AxisMemo* axes) {
  const double* q = y;
  const double* v = y + m.n_coord();
  J.K.set_zero();
  J.C.set_zero();
  J.f_t.setZero();
  sde_jacobian(m, q, v, J.K, J.C, axes);
  bending_jacobian(m, q, v, J.K, J.C);
  contact_jacobian(m, t, q, v, J.K, J.C, J.f_t.data());
  pulley_jacobian(m, t, v, J.C, J.f_t.data());
}

Energy energy(const Model& m, double t, const double* y) {
  const int N = m.n_coord();
  const double* q = y;
  const double* v = y + N;
  Energy e;
  for (int k = 0; k < 3 * m.n_el(); ++k) e.kinetic += 0.5 * m.mass_of(k) * v[k] * v[k];
  for (int j = 0; j < m.n_p(); ++j) {
    const double w = m.omega(j, t, v);
    e.kinetic += 0.5 * m.pulleys[j].inertia * w * w;
  }
  e.sde = sde_potential(m, q);
  e.bending = bending_potential(m, q);
  e.contact = contact_potential(m, q);
  e.gravity = gravity_potential(m, q);
  return e;
}

}  // namespace beltsim
