#include "model/rhs.hpp"

#include <cstdint>

#include <algorithm>

#include "model/forces.hpp"

namespace beltsim {

namespace {
bool split(const Model& m, const Halves* halves) { return halves && m.belt.n >= kHalvesElements; }
Span half(const Model& m, int p) {
  const HalfRange r = half_range(m.belt.n, p);
  return Span{r.lo, r.hi};
}

void all_forces(const Model& m, double t, const double* q, const double* v, double* f, double* e_rate,
                AxisMemo* axes = nullptr, Halves* halves = nullptr) {
  const int n = m.belt.n, np = m.n_p();
  std::fill(f, f + m.n_coord(), 0.0);
  if (m.gravity != 0.0) gravity_forces(m, f);
  if (axes) axes->fit(n);
  if (!split(m, halves)) {
    const Span all{0, n};
    sde_forces(m, q, v, f, e_rate, axes, all);
    bending_forces(m, q, v, f, e_rate, all);
    contact_forces(m, t, q, v, f, f + 3 * n, e_rate, all);
  } else {
    halves->two.run([&](int p) {
      double* sums = halves->sum(p);
      std::fill(sums, sums + np + kEnergyCount, 0.0);
      double* e = e_rate ? sums + np : nullptr;
      sde_forces(m, q, v, f, e, axes, half(m, p));
      bending_forces(m, q, v, f, e, half(m, p));
      contact_forces(m, t, q, v, f, sums, e, half(m, p));
    });
    const double *s0 = halves->sum(0), *s1 = halves->sum(1);
    for (int j = 0; j < np; ++j) f[3 * n + j] += s0[j] + s1[j];
    if (e_rate)
      for (int c = 0; c < kEnergyCount; ++c) e_rate[c] += s0[np + c] + s1[np + c];
  }
  pulley_forces(m, t, v, f, e_rate);
}
}  // namespace

Halves::Halves(const Model& m) {
  // each half's sums on cache lines of their own: the two cores add to them element by element
  constexpr int line = 64 / sizeof(double);
  stride_ = (2 * m.n_p() + kEnergyCount + line - 1) / line * line;
  storage_.assign(2 * stride_ + line, 0.0);
  const auto at = reinterpret_cast<std::uintptr_t>(storage_.data());
  first_ = static_cast<int>(((64 - at % 64) % 64) / sizeof(double));
}

void forces(const Model& m, double t, const double* y, double* f) {
  all_forces(m, t, y, y + m.n_coord(), f, nullptr);
}

void rhs(const Model& m, double t, const double* y, double* dy, AxisMemo* axes, Halves* halves) {
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
  all_forces(m, t, q, v, a, e_rate, axes, halves);
  for (int k = 0; k < N; ++k) a[k] /= m.mass_of(k);
}

void Jacobian::resize(const Model& m) {
  K.resize(m.n_el(), m.n_p());
  C.resize(m.n_el(), m.n_p());
  f_t.setZero(m.n_coord());
}

void jacobian(const Model& m, double t, const double* y, Jacobian& J, AxisMemo* axes, Halves* halves) {
  const double* q = y;
  const double* v = y + m.n_coord();
  const int n = m.belt.n, np = m.n_p();
  J.f_t.setZero();
  if (axes) axes->fit(n);
  if (!split(m, halves)) {
    J.K.set_zero();
    J.C.set_zero();
    const Span all{0, n};
    sde_jacobian(m, q, v, J.K, J.C, axes, all);
    bending_jacobian(m, q, v, J.K, J.C, all);
    contact_jacobian(m, t, q, v, J.K, J.C, J.f_t.data(), nullptr, all);
  } else {
    J.K.pulley_pulley.setZero();
    J.C.pulley_pulley.setZero();
    halves->two.run([&](int p) {
      // each half clears the rows it writes: cleared by the other core, they would first have to
      // come over from its cache
      J.K.set_zero_elements(half(m, p).lo, half(m, p).hi);
      J.C.set_zero_elements(half(m, p).lo, half(m, p).hi);
      double* dmo = halves->sum(p) + np + kEnergyCount;
      std::fill(dmo, dmo + np, 0.0);
      sde_jacobian(m, q, v, J.K, J.C, axes, half(m, p));
      bending_jacobian(m, q, v, J.K, J.C, half(m, p));
      contact_jacobian(m, t, q, v, J.K, J.C, J.f_t.data(), dmo, half(m, p));
    });
    const double *d0 = halves->sum(0) + np + kEnergyCount, *d1 = halves->sum(1) + np + kEnergyCount;
    for (int j = 0; j < np; ++j) J.C.pulley_pulley(j, j) += d0[j] + d1[j];
  }
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
