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
  border_cols.assign(n, 0);
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
    each_col(border_cols[i], np, [&](int b) {
      elem_pulley.block<3, 1>(3 * i, b).setZero();
      pulley_elem.block<1, 3>(b, 3 * i).setZero();
    });
    border_cols[i] = 0;
  }
}

void BlockMatrix::multiply(const double* x, double* y) const {
  multiply_elements(x, y, 0, n);
  multiply_pulleys(x, y);
}

void BlockMatrix::multiply_elements(const double* x, double* y, int lo, int hi) const {
  using Vec3 = Eigen::Vector3d;
  for (int i = lo; i < hi; ++i) {
    const int im = before(i, n), ip = after(i, n);
    Eigen::Map<Vec3> yi(y + 3 * i);
    yi = diag[i] * Eigen::Map<const Vec3>(x + 3 * i) + lower[i] * Eigen::Map<const Vec3>(x + 3 * im) +
         upper[i] * Eigen::Map<const Vec3>(x + 3 * ip);
    each_col(border_cols[i], np, [&](int b) { yi += elem_pulley.block<3, 1>(3 * i, b) * x[3 * n + b]; });
  }
}

void BlockMatrix::multiply_pulleys(const double* x, double* y) const {
  const int ne = 3 * n;
  Eigen::Map<const Eigen::VectorXd> xp(x + ne, np);
  Eigen::Map<Eigen::VectorXd> yp(y + ne, np);
  // noalias: the product straight into the output, no temporary (no allocation)
  yp.noalias() = pulley_pulley * xp;
  for (int i = 0; i < n; ++i)
    each_col(border_cols[i], np, [&](int b) {
      yp[b] += pulley_elem.block<1, 3>(b, 3 * i).dot(Eigen::Map<const Eigen::Vector3d>(x + 3 * i));
    });
}

Eigen::MatrixXd BlockMatrix::to_dense() const {
  const int ne = 3 * n;
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(size(), size());
  for (int i = 0; i < n; ++i) {
    const int im = before(i, n), ip = after(i, n);
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
