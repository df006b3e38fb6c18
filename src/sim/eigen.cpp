#include "sim/eigen.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <stdexcept>
#include <string>

namespace beltsim {

Eigen::VectorXd balance_matrix(Eigen::MatrixXd& A) {
  const Eigen::Index n = A.rows();
  Eigen::VectorXd D = Eigen::VectorXd::Ones(n);
  for (bool changed = true; changed;) {
    changed = false;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double c = A.col(i).cwiseAbs().sum() - std::abs(A(i, i));
      const double r = A.row(i).cwiseAbs().sum() - std::abs(A(i, i));
      if (c == 0 || r == 0) continue;
      double f = 1, cc = c;
      while (cc < r / 2) cc *= 2, f *= 2;
      while (cc >= 2 * r) cc /= 2, f /= 2;
      if ((cc + r / f) < 0.95 * (c + r)) {
        changed = true;
        D[i] *= f;
        A.row(i) /= f;
        A.col(i) *= f;
      }
    }
  }
  return D;
}

EigenPairs eigen_pairs(Eigen::MatrixXd A, bool vectors, bool balance, const char* what) {
  const Eigen::VectorXd D = balance ? balance_matrix(A) : Eigen::VectorXd::Ones(A.rows());
  Eigen::EigenSolver<Eigen::MatrixXd> es(A, vectors);
  if (es.info() != Eigen::Success) throw std::runtime_error(std::string(what) + ": the eigensolver did not converge");
  EigenPairs out;
  out.values = es.eigenvalues();
  if (vectors) out.vectors = D.cast<std::complex<double>>().asDiagonal() * es.eigenvectors();
  return out;
}

}  // namespace beltsim
