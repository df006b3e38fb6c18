#include "integrate/ring_solver.hpp"

#include <cmath>

#include <Eigen/LU>

namespace beltsim {

bool RingSolver::factor(const Model& m, double alpha, double beta, const BlockMatrix& C, const BlockMatrix& K) {
  const int n = m.n_el(), np = m.n_p();
  const int nt = n - 1;  // elements 1..n-1 in T
  const int mb = 3 + np;
  if (n != n_ || np != np_) {
    n_ = n, np_ = np, mb_ = mb;
    Dinv_.resize(nt), Lam_.resize(nt), U_.resize(nt);
    E_.resize(3 * nt, mb), F_.resize(mb, 3 * nt), Y_.resize(3 * nt, mb), G_.resize(mb, mb);
    z_.resize(3 * nt), rb_.resize(mb), xb_.resize(mb);
  }
  const Mat3 Mel = Eigen::Vector3d(m.belt.mass, m.belt.mass, m.belt.rot_inertia).asDiagonal();
  auto block = [&](const Mat3& c, const Mat3& k) -> Mat3 { return -beta * c - k; };

  // border couplings: E (T rows × border cols), F (border rows × T cols), G. The pulley columns
  // of E and rows of F are written whole below; element 0's are zero but for two blocks
  E_.leftCols<3>().setZero();
  F_.topRows<3>().setZero();
  G_.setZero();
  G_.block<3, 3>(0, 0) = alpha * Mel + block(C.diag[0], K.diag[0]);
  // element 0 couples to element 1 (U_0, L_1) and to element n-1 (L_0, U_{n-1})
  F_.block<3, 3>(0, 0) += block(C.upper[0], K.upper[0]);
  F_.block<3, 3>(0, 3 * (nt - 1)) += block(C.lower[0], K.lower[0]);
  E_.block<3, 3>(0, 0) += block(C.lower[1], K.lower[1]);
  E_.block<3, 3>(3 * (nt - 1), 0) += block(C.upper[n - 1], K.upper[n - 1]);
  for (int j = 0; j < np; ++j) {
    for (int i = 1; i < n; ++i)
      for (int r = 0; r < 3; ++r) {
        E_(3 * (i - 1) + r, 3 + j) = -beta * C.elem_pulley(3 * i + r, j) - K.elem_pulley(3 * i + r, j);
        F_(3 + j, 3 * (i - 1) + r) = -beta * C.pulley_elem(j, 3 * i + r) - K.pulley_elem(j, 3 * i + r);
      }
    for (int r = 0; r < 3; ++r) {
      G_(r, 3 + j) = -beta * C.elem_pulley(r, j) - K.elem_pulley(r, j);
      G_(3 + j, r) = -beta * C.pulley_elem(j, r) - K.pulley_elem(j, r);
    }
    for (int l = 0; l < np; ++l) G_(3 + j, 3 + l) = -beta * C.pulley_pulley(j, l) - K.pulley_pulley(j, l);
    G_(3 + j, 3 + j) += alpha * m.mass_of(3 * n + j);
  }

  // block Thomas on T (local index t = i - 1 for element i)
  for (int t = 0; t < nt; ++t) {
    const int i = t + 1;
    Mat3 D = alpha * Mel + block(C.diag[i], K.diag[i]);
    if (t > 0) {
      const Mat3 L = block(C.lower[i], K.lower[i]);
      Lam_[t] = L * Dinv_[t - 1];
      D -= Lam_[t] * U_[t - 1];
    }
    // closed-form 3×3 inverse (cofactors): the blocks are diagonally dominant (see the header),
    // so no pivoting is needed, and this is several times cheaper than an LU with a solve
    bool invertible = false;
    double det = 0;
    D.computeInverseAndDetWithCheck(Dinv_[t], det, invertible, 0.0);
    if (!invertible || !std::isfinite(det) || std::abs(det) <= 1e-300) return false;
    U_[t] = (t + 1 < nt) ? block(C.upper[i], K.upper[i]) : Mat3::Zero();
  }
  // Y = T⁻¹·E, S = G - F·Y
  Y_ = E_;
  solve_T(Y_.data(), mb, 3 * nt);
  // S = G - F·Y in place; coefficient-wise (a 5×5 result: the blocked product costs more)
  G_.noalias() -= F_.lazyProduct(Y_);
  S_.compute(G_);
  return std::isfinite(S_.matrixLU().norm()) && std::abs(S_.determinant()) > 0;
}

void RingSolver::solve_T(double* z, int cols, int stride) const {
  const int nt = n_ - 1;
  using V3 = Eigen::Map<Eigen::Vector3d>;
  // the columns side by side, block by block: each column's arithmetic is that of a lone sweep,
  // but the independent columns overlap in the pipeline (a lone sweep waits on its previous block)
  for (int t = 1; t < nt; ++t)
    for (int c = 0; c < cols; ++c) {
      double* zc = z + c * stride;
      V3(zc + 3 * t) -= Lam_[t] * V3(zc + 3 * (t - 1));
    }
  for (int c = 0; c < cols; ++c) {
    double* zc = z + c * stride;
    V3(zc + 3 * (nt - 1)) = Dinv_[nt - 1] * V3(zc + 3 * (nt - 1)).eval();
  }
  for (int t = nt - 2; t >= 0; --t)
    for (int c = 0; c < cols; ++c) {
      double* zc = z + c * stride;
      V3(zc + 3 * t) = Dinv_[t] * (V3(zc + 3 * t) - U_[t] * V3(zc + 3 * (t + 1)));
    }
}

void RingSolver::solve(const double* r, double* x) {
  const int nt = n_ - 1;
  // border right-hand side: element 0 first, then the pulleys
  for (int k = 0; k < 3; ++k) rb_[k] = r[k];
  for (int j = 0; j < np_; ++j) rb_[3 + j] = r[3 * n_ + j];
  for (int k = 0; k < 3 * nt; ++k) z_[k] = r[3 + k];
  solve_T(z_.data());
  rb_.noalias() -= F_ * z_;
  xb_ = S_.solve(rb_);  // into a kept vector: the step loop allocates nothing
  const Eigen::VectorXd& xb = xb_;
  z_.noalias() -= Y_ * xb;
  for (int k = 0; k < 3; ++k) x[k] = xb[k];
  for (int k = 0; k < 3 * nt; ++k) x[3 + k] = z_[k];
  for (int j = 0; j < np_; ++j) x[3 * n_ + j] = xb[3 + j];
}

}  // namespace beltsim
