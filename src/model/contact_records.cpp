#include "model/contact_records.hpp"

#include <cstring>

namespace beltsim {

namespace {
// the part of y = [q | v | e | z] the contact pass reads: q and v (the first 2·n_coord values),
// then z (the last n_bristle)
int read_size(const Model& m) {
  return 2 * m.n_coord() + m.n_bristle();
}
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

}  // namespace beltsim
