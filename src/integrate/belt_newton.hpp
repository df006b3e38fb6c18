// The belt's NewtonAids (integrate/system.hpp): each reads the contact records of the iterate
// (model/contacts.hpp) in the workspace of the problem's right-hand side, which Newton has just
// evaluated there (filled first when it has not), and calls the aid of integrate/newton_aids.hpp.
#pragma once

#include <cstdint>

#include "integrate/newton_aids.hpp"
#include "integrate/system.hpp"
#include "model/contacts.hpp"
#include "model/model.hpp"
#include "model/workspace.hpp"

namespace beltsim {

class BeltNewtonAids final : public NewtonAids {
 public:
  // ws: the workspace of the problem's right-hand side (BeltProblem::workspace)
  BeltNewtonAids(const Model& m, const Drive& d, Workspace& ws) : model_(m), drive_(d), ws_(ws) {}
  bool reseat(double t, double* z, double* dz, bool keep_correction) override;
  bool local_solve(double t, double s, double* z, const double* g) override;
  void predict(double t, double dt, double* z) override;
  uint64_t branches(double t, const double* y) override;
  double overshoot(double t, const double* z, const double* dz) override;
  double unstable_rate(double t, const double* z) override;

 private:
  // the pairs of the contact records of the state y at t
  ContactView pairs(double t, const double* y) { return contacts_at(model_, drive_, t, y, ws_).pairs(); }
  const Model& model_;
  const Drive& drive_;
  Workspace& ws_;
  PredictScratch predict_;   // Newton's starting point's copies of the state (predict)
  LocalSolveScratch local_;  // the local solve's per-pair values
};

}  // namespace beltsim
