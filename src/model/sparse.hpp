// Assembly of A = α·M - β·C - K (M the diagonal mass matrix, C = ∂f/∂v, K = ∂f/∂q) as an Eigen
// sparse matrix whose pattern is the same for every call, so a solver may analyse it once.
#pragma once

#include <Eigen/SparseCore>

#include "model/block_matrix.hpp"
#include "model/bristles.hpp"
#include "model/drive.hpp"
#include "model/model.hpp"

namespace beltsim {

// only the first `rows` coordinates (rows = n_coord for all, 3n for the elements alone)
void assemble(const Model& m, const Drive& d, double alpha, double beta, const BlockMatrix& C, const BlockMatrix& K, int rows,
              Eigen::SparseMatrix<double>& A);

// The full Jacobian of the first-order system y' = F(t, y), y = [q | v | e | z] (the peer
// integrators' view): J = [[0, I], [M⁻¹K, M⁻¹C]] with the energy rows zero (quadratures), a
// kinematic pulley's q row zero (its speed is prescribed), and every diagonal entry stored; under
// LuGre's law B (else null) gives the bristles' rows and columns (each row holds its element's
// and every border column, so the pattern does not depend on which pulley an element touches).
void assemble_ode_jacobian(const Model& m, const Drive& d, const BlockMatrix& K, const BlockMatrix& C,
                           const BristleJacobian* B, Eigen::SparseMatrix<double>& J);

}  // namespace beltsim
