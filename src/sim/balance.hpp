// Balancing a matrix before its eigen-analysis (sim/modes.cpp, sim/floquet.cpp).
#pragma once

#include <Eigen/Core>

namespace beltsim {

// Balancing (Parlett & Reinsch, as LAPACK's dgebal without its permutations): A ← D⁻¹·A·D with D
// diagonal powers of 2 that make each row's and column's off-diagonal norms alike. The drive's
// matrix mixes positions and speeds, element and pulley coordinates, and stiffnesses over 10 decades
// (contact 10¹⁰ s⁻² against a span's 10⁵): balanced, the eigenvalues keep their accuracy. Returns D
// (an eigenvector x of the balanced A is D·x of the original).
Eigen::VectorXd balance_matrix(Eigen::MatrixXd& A);

}  // namespace beltsim
