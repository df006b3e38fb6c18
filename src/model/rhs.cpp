#include "model/rhs.hpp"

#include <cstdint>

#include <algorithm>

#include "model/bristles.hpp"
#include "model/contact_law.hpp"
#include "model/contacts.hpp"
#include "model/forces.hpp"

namespace beltsim {

namespace {
Span half(const Model& m, int p) {
  const HalfRange r = half_range(m.belt.n, p);
  return Span{r.lo, r.hi};
}

// the forces of every law at (t, y): the contact stage (one pass per half, filling w.contacts
// whatever they held: a change of the Drive is seen here), then each law
void all_forces(const Model& m, const Drive& d, double t, const double* y, double* f, double* e_rate, Workspace& w) {
  const int n = m.belt.n, np = m.n_p();
  const double* q = y;
  const double* v = y + m.n_coord();
  const double* z = m.bristles(y);
  ContactList* pairs = w.contacts.half;
  std::fill(f, f + m.n_coord(), 0.0);
  if (m.gravity != 0.0) gravity_forces(m, f);
  w.axes.fit(n);
  w.contacts.forget();
  if (!w.halves) {
    const Span all{0, n};
    sde_forces(m, q, v, f, e_rate, &w.axes, all);
    bending_forces(m, q, v, f, e_rate, all);
    contact_pass(m, d, t, q, v, z, all, pairs[0]);
    pairs[1].clear();
    contact_forces(m, d, q, pairs[0], f, f + 3 * n, e_rate);
  } else {
    Halves& h = *w.halves;
    h.two.run([&](int p) {
      double* sums = h.sum(p);
      std::fill(sums, sums + np + kEnergyCount, 0.0);
      double* e = e_rate ? sums + np : nullptr;
      sde_forces(m, q, v, f, e, &w.axes, half(m, p));
      bending_forces(m, q, v, f, e, half(m, p));
      contact_pass(m, d, t, q, v, z, half(m, p), pairs[p]);
      contact_forces(m, d, q, pairs[p], f, sums, e);
    });
    const double *s0 = h.sum(0), *s1 = h.sum(1);
    for (int j = 0; j < np; ++j) f[3 * n + j] += s0[j] + s1[j];
    if (e_rate)
      for (int c = 0; c < kEnergyCount; ++c) e_rate[c] += s0[np + c] + s1[np + c];
  }
  w.contacts.stamp(m, t, y, Pairs::touching);
  pulley_forces(m, d, t, v, f, e_rate);
  if (!m.arms.empty()) arm_forces(m, q, v, f, e_rate);
  if (!m.couplings.empty()) coupling_forces(m, d, t, q, v, f, e_rate);
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

Workspace::Workspace(const Model& m, bool split) {
  // a tensioner arm's terms join border rows and columns that both halves would write: one thread
  if (split && m.belt.n >= kHalvesElements && m.arms.empty()) halves = std::make_unique<Halves>(m);
}

void forces(const Model& m, const Drive& d, double t, const double* y, double* f) {
  Workspace w(m, false);
  all_forces(m, d, t, y, f, nullptr, w);
}

void rhs(const Model& m, const Drive& d, double t, const double* y, double* dy, Workspace* w) {
  std::unique_ptr<Workspace> own;
  if (!w) own = std::make_unique<Workspace>(m, false), w = own.get();
  const int N = m.n_coord();
  const double* v = y + N;
  double* e_rate = m.track_energy ? dy + 2 * N : nullptr;
  if (e_rate) std::fill(e_rate, e_rate + kEnergyCount, 0.0);
  // positions move with the velocities (a kinematic pulley with its prescribed speed)
  std::copy(v, v + N, dy);
  for (int j = 0; j < m.n_p(); ++j)
    if (d.kinematic(j)) dy[m.pulley_coord(j)] = d.omega(m, j, t, v);
  // accelerations
  double* a = dy + N;
  all_forces(m, d, t, y, a, e_rate, *w);
  // (Drive::mass, the elements' written out: this loop is in every evaluation)
  const double me = m.belt.mass, je = m.belt.rot_inertia;
  for (int i = 0; i < m.n_el(); ++i) a[3 * i] /= me, a[3 * i + 1] /= me, a[3 * i + 2] /= je;
  for (int k = 3 * m.n_el(); k < N; ++k) a[k] /= d.mass(m, k);
  // the bristles' deflections
  if (const double* z = m.bristles(y)) bristle_rates(m, z, w->contacts.pairs(), dy + m.bristle_offset());
}

void Jacobian::resize(const Model& m) {
  K.resize(m.n_el(), m.n_border());
  C.resize(m.n_el(), m.n_border());
  f_t.setZero(m.n_coord());
  if (m.n_bristle()) B.resize(m.n_el(), m.n_border());
}

void jacobian(const Model& m, const Drive& d, double t, const double* y, Jacobian& J, Workspace* w) {
  std::unique_ptr<Workspace> own;
  if (!w) own = std::make_unique<Workspace>(m, false), w = own.get();
  const double* q = y;
  const double* v = y + m.n_coord();
  const double* z = m.bristles(y);
  const int n = m.belt.n, np = m.n_p();
  // the contact stage: the right-hand side's records when they are this state's, else a pass
  const ContactList* pairs = contacts_at(m, d, t, y, *w).half;
  J.f_t.setZero();
  w->axes.fit(n);
  if (!w->halves) {
    J.K.set_zero();
    J.C.set_zero();
    const Span all{0, n};
    sde_jacobian(m, q, v, J.K, J.C, &w->axes, all);
    bending_jacobian(m, q, v, J.K, J.C, all);
    contact_jacobian(m, d, t, q, v, pairs[0], J.K, J.C, J.f_t.data(), nullptr);
  } else {
    Halves& h = *w->halves;
    J.K.pulley_pulley.setZero();
    J.C.pulley_pulley.setZero();
    h.two.run([&](int p) {
      // each half clears the rows it writes: cleared by the other core, they would first have to
      // come over from its cache
      J.K.set_zero_elements(half(m, p).lo, half(m, p).hi);
      J.C.set_zero_elements(half(m, p).lo, half(m, p).hi);
      double* dmo = h.sum(p) + np + kEnergyCount;
      std::fill(dmo, dmo + np, 0.0);
      sde_jacobian(m, q, v, J.K, J.C, &w->axes, half(m, p));
      bending_jacobian(m, q, v, J.K, J.C, half(m, p));
      contact_jacobian(m, d, t, q, v, pairs[p], J.K, J.C, J.f_t.data(), dmo);
    });
    const double *d0 = h.sum(0) + np + kEnergyCount, *d1 = h.sum(1) + np + kEnergyCount;
    for (int j = 0; j < np; ++j) J.C.pulley_pulley(j, j) += d0[j] + d1[j];
  }
  pulley_jacobian(m, d, t, v, J.C, J.f_t.data());
  if (!m.arms.empty()) arm_jacobian(m, q, v, J.K, J.C);
  if (!m.couplings.empty()) coupling_jacobian(m, d, t, v, J.K, J.C, J.f_t.data());
  if (z) {
    J.B.clear(m);
    bristle_jacobian(m, d, t, q, v, z, w->contacts.pairs(), J.B);
  }
}

Energy energy(const Model& m, const Drive& d, double t, const double* y) {
  const int N = m.n_coord();
  const double* q = y;
  const double* v = y + N;
  Energy e;
  for (int k = 0; k < 3 * m.n_el(); ++k) e.kinetic += 0.5 * m.mass_of(k) * v[k] * v[k];
  for (int j = 0; j < m.n_p(); ++j) {
    const double w = d.omega(m, j, t, v);
    e.kinetic += 0.5 * m.pulleys[j].inertia * w * w;
  }
  for (int a = 0; a < m.n_arm(); ++a) e.kinetic += 0.5 * m.arms[a].inertia * v[m.arm_coord(a)] * v[m.arm_coord(a)];
  for (int c = 0; c < m.n_coupling(); ++c) {
    const Coupling& cp = m.couplings[c];
    const double wr = v[m.rotor_coord(c)], wh = cp.one_way ? v[m.hub_coord(c)] : 0.0;
    e.kinetic += 0.5 * cp.inertia * wr * wr + 0.5 * cp.hub_inertia * wh * wh;
  }
  e.arm = arm_potential(m, q);
  e.coupling = coupling_potential(m, q);
  e.sde = sde_potential(m, q);
  e.bending = bending_potential(m, q);
  e.contact = contact_potential(m, q);
  e.gravity = gravity_potential(m, q);
  return e;
}

}  // namespace beltsim
