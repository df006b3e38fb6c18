#include "model/block_matrix.hpp"

namespace beltsim {

void BlockMatrix::resize(int n_el, int n_p) {
  n = n_el;
  np = n_p;
  diag.assign(n, Mat3::Zero());
  lower.assign(n, Mat3::Zero());
  upper.assign(n, Mat3::Zero());
  elem_pulley.setZero(3 * n, np);
  pulley_elem.setZero(np, 3 * n);
  pulley_pulley.setZero(np, np);
}

void BlockMatrix::set_zero() {
  set_zero_elements(0, n);
  pulley_pulley.setZero();
}

void BlockMatrix::set_zero_elements(int lo, int hi) {
  for (int i = lo; i < hi; ++i) {
    diag[i].setZero();
    lower[i].setZero();
    upper[i].setZero();
  }
  elem_pulley.middleRows(3 * lo, 3 * (hi - lo)).setZero();
  pulley_elem.middleCols(3 * lo, 3 * (hi - lo)).setZero();
}

void BlockMatrix::multiply(const double* x, double* y) const {
  multiply_elements(x, y, 0, n);
  multiply_pulleys(x, y);
}

void BlockMatrix::multiply_elements(const double* x, double* y, int lo, int hi) const {
  using Vec3 = Eigen::Vector3d;
  Eigen::Map<const Eigen::VectorXd> xp(x + 3 * n, np);
  Eigen::Map<Eigen::VectorXd> ye(y + 3 * lo, 3 * (hi - lo));
  for (int i = lo; i < hi; ++i) {
    const int im = (i + n - 1) % n, ip = (i + 1) % n;
    Eigen::Map<Vec3>(y + 3 * i) = diag[i] * Eigen::Map<const Vec3>(x + 3 * i) +
                                  lower[i] * Eigen::Map<const Vec3>(x + 3 * im) +
                                  upper[i] * Eigen::Map<const Vec3>(x + 3 * ip);
  }
  // noalias: matrix-vector products straight into the output, no temporaries (no allocation)
  ye.noalias() += elem_pulley.middleRows(3 * lo, 3 * (hi - lo)) * xp;
}

void BlockMatrix::multiply_pulleys(const double* x, double* y) const {
  const int ne = 3 * n;
  Eigen::Map<const Eigen::VectorXd> xe(x, ne), xp(x + ne, np);
  Eigen::Map<Eigen::VectorXd> yp(y + ne, np);
  yp.noalias() = pulley_elem * xe;
  yp.noalias() += pulley_pulley * xp;
}

Eigen::MatrixXd BlockMatrix::to_dense() const {
  const int ne = 3 * n;
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(size(), size());
  for (int i = 0; i < n; ++i) {
    const int im = (i + n - 1) % n, ip = (i + 1) % n;
    d.block<3, 3>(3 * i, 3 * i) += diag[i];
    d.block<3, 3>(3 * i, 3 * im) += lower[i];
    d.block<3, 3>(3 * i, 3 * ip) += upper[i];
  }
  d.block(0, ne, ne, np) = elem_pulley;
  d.block(ne, 0, np, ne) = pulley_elem;
  d.block(ne, ne, np, np) = pulley_pulley;
  return d;
}

}  // namespace beltsim
