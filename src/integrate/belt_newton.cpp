#include "integrate/belt_newton.hpp"

namespace beltsim {

bool BeltNewtonAids::reseat(double t, double* z, double* dz, bool keep_correction) {
  const int N = model_.n_coord();
  contact_pass(model_, drive_, t, z, Span{0, model_.n_el()}, pairs_);
  return friction_reseat(model_, drive_, pairs_, z, z + N, dz, dz + N,
                         keep_correction ? Reseat::correction : Reseat::iterate) > 0;
}

bool BeltNewtonAids::local_solve(double t, double s, double* z, const double* g) {
  const int N = model_.n_coord();
  contact_pass(model_, drive_, t, z, Span{0, model_.n_el()}, pairs_);
  return friction_local_solve(model_, drive_, pairs_, s, z, z + N, g + N, local_) > 0;
}

void BeltNewtonAids::predict(double t, double dt, double* z) const {
  convective_predict(model_, drive_, t, dt, z, z + model_.n_coord(), predict_);
}

uint64_t BeltNewtonAids::branches(double t, const double* y) const {
  contact_pass(model_, drive_, t, y, Span{0, model_.n_el()}, pairs_);
  return contact_branches(model_, pairs_);
}

double BeltNewtonAids::overshoot(double t, const double* z, const double* dz) const {
  const int N = model_.n_coord();
  contact_pass(model_, drive_, t, z, Span{0, model_.n_el()}, pairs_);
  return friction_overshoot(model_, drive_, pairs_, z, dz + N);
}

}  // namespace beltsim
