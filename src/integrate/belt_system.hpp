// The belt model as an OdeSystem. The linear systems of the implicit methods are reduced to the
// size of q using the second-order structure. With J = [[0, I], [M⁻¹K, M⁻¹C]] (K = ∂f/∂q,
// C = ∂f/∂v, M diagonal) the stage system (s·I - J)·[u_q; u_v] = [r_q; r_v] becomes
//   (s²·M - s·C - K)·u_v = s·M·r_v + K·r_q,    u_q = (r_q + u_v)/s
// and the energy quadratures (rows of J taken as zero, see rhs.hpp) give u_e = r_e/s.
// A = s²·M - s·C - K keeps the ring-plus-pulleys pattern; RingSolver factorises it in O(n).
#pragma once

#include <memory>

#include "integrate/newton_aids.hpp"
#include "integrate/ring_solver.hpp"
#include "integrate/system.hpp"
#include "model/model.hpp"
#include "model/rhs.hpp"

namespace beltsim {

class BeltSystem final : public OdeSystem {
 public:
  // d: the drive the run holds (Simulation); changes to it apply from the next evaluation
  BeltSystem(const Model& m, const Drive& d);
  int size() const override { return model_.n_state(); }
  void rhs(double t, const double* y, double* dy) override { beltsim::rhs(model_, drive_, t, y, dy, &ws_); }
  double atol_scale(int k) const override;
  double resolution(int k) const override;
  bool prepare_jacobian(double t, const double* y) override;
  void time_derivative(double* f_t) const override;
  bool factor(double s) override;
  bool sparse_jacobian(double t, const double* y, Eigen::SparseMatrix<double>& J) override;
  void solve(const double* r, double* u) override;
  bool reseat(double t, double* z, double* dz, bool keep_correction) override;
  bool local_solve(double t, double s, double* z, const double* g) override;
  uint64_t branches(double t, const double* y) const override;
  void predict(double t, double dt, double* z) const override;
  int switch_count() const override;
  void switches(double t, const double* y, double* g) const override;
  std::string describe(int k) const override;
  std::string check(double t, const double* y) const override;
  const Model& model() const { return model_; }
  const Drive& drive() const { return drive_; }

 private:
  const Model& model_;
  const Drive& drive_;
  Jacobian J_;
  Workspace ws_;                     // the right-hand side's and the Jacobian's (model/workspace.hpp)
  mutable ContactList pairs_;        // the Newton aids' and switching functions' contact pass
  mutable PredictScratch predict_;   // Newton's starting point's copies of the state (predict)
  double s_ = 0;
  RingSolver solver_;
  Eigen::VectorXd rhs_, kr_, uv_;
};

}  // namespace beltsim
