// Direct solver for A = α·M - β·C - K with the belt drive's pattern (model/block_matrix.hpp), in
// O(n) operations.
//
// Element 0 is moved into the border with the pulleys, which leaves the elements 1..n-1 as a
// plain (not cyclic) block-tridiagonal matrix T with 3×3 blocks, bordered by m = 3 + np rows and
// columns:
//     A = [ T  E ]      T: elements 1..n-1          E, F: their couplings to the border
//         [ F  G ]      G: element 0 and the pulleys (dense, m×m)
// T is factorised by block LU (block Thomas: Δ_1 = D_1, Λ_i = L_i·Δ_{i-1}⁻¹, Δ_i = D_i - Λ_i·U_{i-1});
// then Y = T⁻¹·E (m columns) and the Schur complement S = G - F·Y, factorised densely. A solve is
// x_T = T⁻¹·r_T - Y·x_b with S·x_b = r_b - F·T⁻¹·r_T. Cost per factorisation ≈ n·(27 + 9m)
// multiply-adds beyond the block inversions. No pivoting across blocks: A = s²M - sC - K is block
// diagonally dominant for the step sizes the implicit methods use (s²M and the dampers and
// springs all add to the diagonal blocks); the 3×3 blocks are factorised with partial pivoting.
#pragma once

#include <vector>

#include <Eigen/Dense>

#include "model/block_matrix.hpp"
#include "model/model.hpp"

namespace beltsim {

class RingSolver {
 public:
  // factorises α·M - β·C - K; false when a pivot block or the Schur complement is singular
  bool factor(const Model& m, double alpha, double beta, const BlockMatrix& C, const BlockMatrix& K);
  // x = A⁻¹·r (length 3n + np); x may alias r
  void solve(const double* r, double* x);

 private:
  int n_ = 0, np_ = 0, mb_ = 0;
  std::vector<Mat3> Dinv_, Lam_, U_;      // per element 1..n-1 (index i-1)
  Eigen::MatrixXd E_, F_, Y_;             // 3(n-1)×m, m×3(n-1), 3(n-1)×m
  Eigen::MatrixXd G_;
  Eigen::PartialPivLU<Eigen::MatrixXd> S_;
  Eigen::VectorXd z_, rb_, xb_;
  // in place: z = T⁻¹·z for `cols` columns `stride` apart
  void solve_T(double* z, int cols = 1, int stride = 0) const;
};

}  // namespace beltsim
