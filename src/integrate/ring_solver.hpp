// Direct solver for A = α·M - β·C - K with the belt drive's pattern (model/block_matrix.hpp), in
// O(n) operations.
//
// Element 0 is moved into the border with the pulleys, which leaves the elements 1..n-1 as a
// plain (not cyclic) block-tridiagonal matrix T with 3×3 blocks, bordered by m = 3 + Model::n_border() rows and
// columns:
//     A = [ T  E ]      T: elements 1..n-1          E, F: their couplings to the border
//         [ F  G ]      G: element 0, the pulleys, the tensioner arms and the coupled rotors (dense, m×m)
// T is factorised by block LU (block Thomas: Δ_1 = D_1, Λ_i = L_i·Δ_{i-1}⁻¹, Δ_i = D_i - Λ_i·U_{i-1});
// then Y = T⁻¹·E (m columns) and the Schur complement S = G - F·Y, factorised densely. A solve is
// x_T = T⁻¹·r_T - Y·x_b with S·x_b = r_b - F·T⁻¹·r_T. Cost per factorisation ≈ n·(27 + 9m)
// multiply-adds beyond the block inversions. No pivoting across blocks: A = s²M - sC - K is block
// diagonally dominant for the step sizes the implicit methods use (s²M and the dampers and
// springs all add to the diagonal blocks); the 3×3 blocks are factorised with partial pivoting.
//
// A belt of kHalvesElements or more (model/two_way.hpp) also moves element h = n/2 into the
// border (m = 6 + np), which cuts T into two independent chains, elements 1..h-1 and h+1..n-1:
//     T = [ T0    ]   E = [ E0 ]   F = [ F0 F1 ]   S = G - F0·Y0 - F1·Y1
//         [    T1 ]       [ E1 ]
// Each chain's factorisation, its Y_c = T_c⁻¹·E_c and F_c·Y_c, and its share of a solve run at
// once on the two cores (TwoWay), each chain on the core that assembled its rows of the Jacobian.
// The split depends on n only, never on the cores: with one core (or no TwoWay) the chains run
// one after the other and give the same bits. F_c's element rows touch only the chain's two end
// blocks, so F_c·Y_c costs 2·9m for them plus the np dense pulley rows.
#pragma once

#include <vector>

#include <Eigen/Dense>

#include "model/block_matrix.hpp"
#include "model/drive.hpp"
#include "model/model.hpp"
#include "model/two_way.hpp"

namespace beltsim {

class RingSolver {
 public:
  // factorises α·M - β·C - K; false when a pivot block or the Schur complement is singular.
  // `two` (may be null) runs a split ring's two chains at once, now and in the solves after.
  bool factor(const Model& m, const Drive& d, double alpha, double beta, const BlockMatrix& C, const BlockMatrix& K,
              TwoWay* two = nullptr);
  // x = A⁻¹·r (length 3n + np); x may alias r
  void solve(const double* r, double* x);

 private:
  // elements first..first+len-1 of T (local block t = element first + t)
  struct Chain {
    int first = 0, len = 0;
    std::vector<Mat3> Dinv, Lam, U;
    Eigen::MatrixXd F, Y;     // m×3len, 3len×m (Y first holds E)
    Eigen::MatrixXd FY;       // m×m, F·Y (split only)
    Eigen::VectorXd z, Fz;    // a solve's T⁻¹·r_T and F·z (split only)
    bool ok = true;
  };
  int n_ = 0, np_ = 0, mb_ = 0;
  int border_[2] = {0, 0}, nb_ = 1;  // the belt elements in the border
  std::vector<Chain> chains_;
  Eigen::MatrixXd G_;
  Eigen::PartialPivLU<Eigen::MatrixXd> S_;
  Eigen::VectorXd rb_, xb_;
  TwoWay* two_ = nullptr;

  void resize(int n, int np);
  // the border index of element i (-1: in a chain)
  int border_of(int i) const;
  bool factor_chain(Chain& ch, const Model& m, double alpha, double beta, const BlockMatrix& C,
                    const BlockMatrix& K) const;
  // in place: z = T_c⁻¹·z for `cols` columns `stride` apart; the columns skip_lo..skip_hi-1
  // (zero but in their last block) take the backward sweep only
  static void solve_T(const Chain& ch, double* z, int cols = 1, int stride = 0, int skip_lo = 0, int skip_hi = 0);
  // runs f(chain) for each chain: at once through two_ when split and given
  template <class F>
  void each_chain(F&& f);
};

}  // namespace beltsim
