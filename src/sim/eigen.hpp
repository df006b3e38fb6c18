// The one dense eigen-decomposition of the mode analyses (sim/modes.cpp, sim/floquet.cpp,
// sim/mode_check.cpp), Eigen's EigenSolver after balancing, in one translation unit (its templates
// cost 15 s of the compiler's time wherever they are instantiated).
#pragma once

#include <Eigen/Core>

namespace beltsim {

// Balancing (Parlett & Reinsch, as LAPACK's dgebal without its permutations): A ← D⁻¹·A·D with D
// diagonal powers of 2 that make each row's and column's off-diagonal norms alike. The drive's
// matrix mixes positions and speeds, element and pulley coordinates, and stiffnesses over 10 decades
// (contact 10¹⁰ s⁻² against a span's 10⁵): balanced, the eigenvalues keep their accuracy. Returns D
// (an eigenvector x of the balanced A is D·x of the original).
Eigen::VectorXd balance_matrix(Eigen::MatrixXd& A);

struct EigenPairs {
  Eigen::VectorXcd values;
  Eigen::MatrixXcd vectors;  // column k belongs to values[k] (empty when not asked for)
};

// the eigenvalues of A and, with `vectors`, its eigenvectors (of A itself, not of the balanced
// matrix); balanced first unless `balance` is false. Throws std::runtime_error naming `what` when
// the eigensolver does not converge.
EigenPairs eigen_pairs(Eigen::MatrixXd A, bool vectors, bool balance, const char* what);

}  // namespace beltsim
