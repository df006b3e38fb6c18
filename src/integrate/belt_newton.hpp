// The belt's NewtonAids (integrate/system.hpp): each takes a contact pass at the iterate and
// calls the aid of integrate/newton_aids.hpp.
#pragma once

#include <cstdint>

#include "integrate/newton_aids.hpp"
#include "integrate/system.hpp"
#include "model/contact_law.hpp"
#include "model/model.hpp"

namespace beltsim {

class BeltNewtonAids final : public NewtonAids {
 public:
  BeltNewtonAids(const Model& m, const Drive& d) : model_(m), drive_(d) {}
  bool reseat(double t, double* z, double* dz, bool keep_correction) override;
  bool local_solve(double t, double s, double* z, const double* g) override;
  void predict(double t, double dt, double* z) const override;
  uint64_t branches(double t, const double* y) const override;
  double overshoot(double t, const double* z, const double* dz) const override;

 private:
  const Model& model_;
  const Drive& drive_;
  mutable ContactList pairs_;       // the contact pass at the iterate
  mutable PredictScratch predict_;
  LocalSolveScratch local_;  // Newton's starting point's copies of the state (predict)
};

}  // namespace beltsim
