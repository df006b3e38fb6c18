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
// x_T = T⁻¹·r_T - Y·x_b with S·x_b = r_b - F·T⁻¹·r_T. A pulley's row of F and column of E are
// zero outside its wrap: F·Y and F·z take the blocks of the wrap only, and T⁻¹·E's forward sweep
// of a column starts at its wrap. Cost per factorisation ≈ n·(27 + 9m) multiply-adds beyond the
// block inversions at most (the dense F·Y alone was n·3m², the serpentine drive's largest part).
// No pivoting across blocks: A = s²M - sC - K is block
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
    // F's and E's pulley rows and columns (pb + j, after the border elements') are non-zero on
    // the elements of the pulley's wrap only: F's row is zero outside blocks f_lo[j]..f_hi[j]-1
    // (f_lo = f_hi: all of it), and column c of E before block start[c] (all of it when start[c] =
    // len), which solve_T's forward sweep skips
    std::vector<int> f_lo, f_hi, start;
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
  // in place: z = T_c⁻¹·z for `cols` columns `stride` apart; column c is zero before its block
  // start[c] (all of it when start[c] = len: it stays zero), which the forward sweep skips
  // (no start: every column from block 0)
  static void solve_T(const Chain& ch, double* z, int cols = 1, int stride = 0, const int* start = nullptr);
  // F·X over the non-zero blocks of F's rows (X with 3len rows): out = F·X, or out -= F·X
  template <class X, class Out>
  void f_times(const Chain& ch, const X& x, Out&& out, bool subtract) const;
  // runs f(chain) for each chain: at once through two_ when split and given
  template <class F>
  void each_chain(F&& f);
};

}  // namespace beltsim
