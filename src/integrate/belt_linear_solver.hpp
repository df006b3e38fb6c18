// The belt's LinearSolver (integrate/system.hpp). The linear systems of the implicit methods are
// reduced to the size of q using the second-order structure. With J = [[0, I], [M⁻¹K, M⁻¹C]]
// (K = ∂f/∂q, C = ∂f/∂v, M diagonal) the stage system (s·I - J)·[u_q; u_v] = [r_q; r_v] becomes
//   (s²·M - s·C - K)·u_v = s·M·r_v + K·r_q,    u_q = (r_q + u_v)/s
// and the energy quadratures (rows of J taken as zero, see rhs.hpp) give u_e = r_e/s. LuGre's
// bristle deflections are eliminated first (model/bristles.hpp: bristle_eliminate), which puts
// K' and C' in the place of K and C and adds their share to the right-hand side.
// A = s²·M - s·C - K keeps the ring-plus-pulleys pattern; RingSolver factorises it in O(n).
#pragma once

#include <Eigen/Core>

#include "integrate/ring_solver.hpp"
#include "integrate/system.hpp"
#include "model/model.hpp"
#include "model/rhs.hpp"

namespace beltsim {

class BeltLinearSolver final : public LinearSolver {
 public:
  // ws: the workspace of the problem's right-hand side (BeltProblem::workspace), which the
  // Jacobian's evaluation shares (the right-hand side's contact records, and the two halves' worker)
  BeltLinearSolver(const Model& m, const Drive& d, Workspace& ws);
  bool prepare_jacobian(double t, const double* y) override;
  void time_derivative(double* f_t) const override;
  bool factor(double s) override;
  void solve(const double* r, double* u) override;
  bool sparse_jacobian(double t, const double* y, Eigen::SparseMatrix<double>& J) override;

 private:
  const Model& model_;
  const Drive& drive_;
  Workspace& ws_;
  Jacobian J_;  // taken by prepare_jacobian, factored by factor
  double s_ = 0;
  // under LuGre's law: K', C' and D of the factored s (K_ and C_ point at them, else at J_'s)
  BlockMatrix K_eff_, C_eff_;
  std::vector<double> D_;
  const BlockMatrix* K_ = nullptr;
  RingSolver solver_;
  Eigen::VectorXd rhs_, kr_, uv_, fz_;
  Eigen::VectorXd mass_;  // Drive::mass of every coordinate when the matrix was factored
};

}  // namespace beltsim
