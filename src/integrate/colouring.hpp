// Column colouring for difference-quotient Jacobians (Curtis, Powell & Reid 1974): columns that
// share no row can be perturbed together, since each row of F then changes through at most one
// of them. One right-hand side per colour gives every entry of the pattern.
//
// Greedy distance-2 colouring: columns taken in order, each gets the smallest colour that no
// column sharing a row with it already has (Coleman & Moré 1983, "sequential" ordering). At most
// 1 + the largest number of columns a column shares rows with; at least the largest row count.
#pragma once

#include <vector>

#include <Eigen/SparseCore>

#include "integrate/system.hpp"

namespace beltsim {

struct ColumnColouring {
  int colours = 0;
  std::vector<int> colour;                   // colour of each column
  std::vector<std::vector<int>> columns_of;  // the columns of each colour, ascending
};

// the pattern is the stored entries of A (explicit zeros included), any storage order
ColumnColouring colour_columns(const Eigen::SparseMatrix<double>& A);

// J = ∂F/∂y at (t, y) by coloured forward differences into the values of J (compressed, column
// major, pattern coloured by c), with f0 = F(t, y) given: for each colour, every column k of it is
// perturbed at once by δ_k, F is evaluated once, and each row r of column k's pattern gets
// (F_r(y + Σδ) − F_r(y))/δ_k, exact because no other column of that colour touches row r.
// δ_k = √ε·max(|y_k|, typical_k), typical_k = sys.atol_scale(k): the square root of the
// rounding unit balances a forward difference's truncation error (∝ δ) against its cancellation
// error (∝ ε/δ); the typical size (0.1 m, 1 m/s, ...) keeps δ_k away from zero for components
// that pass through zero. work: 2·size scratch. Returns the right-hand sides taken (the
// colours), or -1 when F was not finite at a perturbed point.
long difference_jacobian(OdeProblem& sys, const ColumnColouring& c, double t, const double* y, const double* f0,
                         Eigen::SparseMatrix<double>& J, std::vector<double>& work);

// true when no two columns of one colour share a row of A's pattern
bool valid_colouring(const Eigen::SparseMatrix<double>& A, const ColumnColouring& c);

}  // namespace beltsim
