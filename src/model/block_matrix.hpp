// BlockMatrix: an N×N matrix (N = 3n + np) with the belt drive's sparsity pattern, used for the
// force Jacobians K = ∂f/∂q and C = ∂f/∂v. Element i couples only to its ring neighbours
// i-1 and i+1 (through the SDEs) and to the pulleys (through contact and friction):
//
//   [ D0 U0          L0 | P0 ]     Di, Li, Ui : 3×3 blocks (diagonal, left and right neighbour;
//   [ L1 D1 U1          | P1 ]                  L0 and U_{n-1} close the ring)
//   [    .. .. ..       | .. ]     Pi : 3×np, element rows × pulley columns
//   [ U_{n-1}  L_{n-1} D_{n-1} |  ]     Ri : np×3, pulley rows × element columns
//   [ R0 R1 ...         | G  ]     G  : np×np
//
// The border (np columns and rows here) holds the pulleys and then the tensioner arms
// (Model::n_border). Storage is dense per block so that the pattern never changes while integrating.
// An element's Pi row and Ri column are non-zero only where it touches a pulley (that pulley's
// column, and its arm's): the code that writes them marks the pair (mark), and clearing and the
// products visit the marked entries only (border_cols), a few of the np·3n of a long belt.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace beltsim {

using Mat3 = Eigen::Matrix3d;

// the elements before and after element i (0 <= i < n) on the ring, without an integer division
// (they are in every evaluation and every solve)
inline int before(int i, int n) {
  return i > 0 ? i - 1 : n - 1;
}
inline int after(int i, int n) {
  return i + 1 < n ? i + 1 : 0;
}

struct BlockMatrix {
  int n = 0, np = 0;
  std::vector<Mat3> diag, lower, upper;          // n each: (i,i), (i,i-1), (i,i+1)
  Eigen::MatrixXd elem_pulley;                   // 3n × np
  Eigen::MatrixXd pulley_elem;                   // np × 3n
  Eigen::MatrixXd pulley_pulley;                 // np × np
  // per element, the border columns b its Pi row and Ri column may be non-zero in: bit b (all bits
  // when np > 64); clear bits mean zero entries
  std::vector<uint64_t> border_cols;

  // the writer of element i's entries in border column b says so before (or as) it writes them
  void mark(int i, int b) { border_cols[i] |= np <= 64 ? uint64_t{1} << b : ~uint64_t{0}; }
  // calls f(b) for each border column b of a mask of border_cols (or a union of them), in
  // ascending order (every column of the np when np > 64 and the mask is not empty)
  template <class F>
  static void each_col(uint64_t mask, int np, F&& f) {
    if (np > 64) {
      if (mask)
        for (int b = 0; b < np; ++b) f(b);
      return;
    }
    for (; mask; mask &= mask - 1) f(__builtin_ctzll(mask));
  }
  void resize(int n_el, int n_p);
  void set_zero();
  // the rows of elements lo..hi-1 (their blocks and pulley columns) and their pulley-row columns
  void set_zero_elements(int lo, int hi);
  int size() const { return 3 * n + np; }
  // y = this · x (x, y of length size())
  void multiply(const double* x, double* y) const;
  // the same for the rows of elements lo..hi-1 only, and for the pulley rows only (a long belt's
  // halves multiply their own rows at once; each row's arithmetic is that of multiply)
  void multiply_elements(const double* x, double* y, int lo, int hi) const;
  void multiply_pulleys(const double* x, double* y) const;
  Eigen::MatrixXd to_dense() const;
};

}  // namespace beltsim
