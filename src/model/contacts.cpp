#include "model/contacts.hpp"

#include <cstring>

#include "model/workspace.hpp"

namespace beltsim {

namespace {
// the part of y = [q | v | e | z] the contact pass reads: q and v (the first 2·n_coord values),
// then z (the last n_bristle)
int read_size(const Model& m) { return 2 * m.n_coord() + m.n_bristle(); }
}  // namespace

bool ContactRecords::of(const Model& m, double t, const double* y, Pairs which) const {
  if (!stamped_ || (which == Pairs::all && which_ != Pairs::all)) return false;
  if (std::memcmp(&t, &t_, sizeof t) != 0 || state_.size() != static_cast<size_t>(read_size(m))) return false;
  const int qv = 2 * m.n_coord(), nz = m.n_bristle();
  return std::memcmp(y, state_.data(), qv * sizeof(double)) == 0 &&
         (nz == 0 || std::memcmp(m.bristles(y), state_.data() + qv, nz * sizeof(double)) == 0);
}

void ContactRecords::stamp(const Model& m, double t, const double* y, Pairs which) {
  const int qv = 2 * m.n_coord(), nz = m.n_bristle();
  state_.resize(read_size(m));
  std::memcpy(state_.data(), y, qv * sizeof(double));
  if (nz) std::memcpy(state_.data() + qv, m.bristles(y), nz * sizeof(double));
  t_ = t, which_ = which, stamped_ = true;
}

void fill_contacts(const Model& m, const Drive& d, double t, const double* y, ContactRecords& r, Pairs which) {
  r.forget();
  contact_pass(m, d, t, y, Span{0, m.n_el()}, r.half[0], which);
  r.half[1].clear();
  r.stamp(m, t, y, which);
}

void fill_contacts(const Model& m, const Drive& d, double t, const double* y, Workspace& w, Pairs which) {
  if (!w.halves) {
    fill_contacts(m, d, t, y, w.contacts, which);
    return;
  }
  ContactRecords& r = w.contacts;
  r.forget();
  w.halves->two.run([&](int p) {
    const HalfRange h = half_range(m.belt.n, p);
    contact_pass(m, d, t, y, Span{h.lo, h.hi}, r.half[p], which);
  });
  r.stamp(m, t, y, which);
}

const ContactRecords& contacts_at(const Model& m, const Drive& d, double t, const double* y, Workspace& w,
                                  Pairs which) {
  if (!w.contacts.of(m, t, y, which)) fill_contacts(m, d, t, y, w, which);
  return w.contacts;
}

}  // namespace beltsim
