#include "model/contacts.hpp"

#include "model/workspace.hpp"

namespace beltsim {

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
