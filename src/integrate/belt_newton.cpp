#include "integrate/belt_newton.hpp"

namespace beltsim {

bool BeltNewtonAids::reseat(double t, double* z, double* dz, bool keep_correction) {
  const int N = model_.n_coord();
  return friction_reseat(model_, drive_, pairs(t, z), z, z + N, dz, dz + N,
                         keep_correction ? Reseat::correction : Reseat::iterate) > 0;
}

bool BeltNewtonAids::local_solve(double t, double s, double* z, const double* g) {
  const int N = model_.n_coord();
  return friction_local_solve(model_, drive_, pairs(t, z), s, z, z + N, g + N, local_) > 0;
}

void BeltNewtonAids::predict(double t, double dt, double* z) {
  convective_predict(model_, drive_, t, dt, pairs(t, z), z, z + model_.n_coord(), predict_);
}

uint64_t BeltNewtonAids::branches(double t, const double* y) { return contact_branches(model_, pairs(t, y)); }

double BeltNewtonAids::overshoot(double t, const double* z, const double* dz) {
  return friction_overshoot(model_, drive_, pairs(t, z), z, dz + model_.n_coord());
}

double BeltNewtonAids::unstable_rate(double t, const double* z) {
  // Threlfall's curve never falls: a belt under it alone has nothing to look for, not even the
  // comparison of the state with its contact records
  if (!model_.any_law(FrictionKind::stribeck) && !model_.any_law(FrictionKind::lugre)) return 0;
  return falling_friction_rate(model_, pairs(t, z));
}

}  // namespace beltsim
