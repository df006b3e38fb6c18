#include "model/sparse.hpp"

#include <vector>

namespace beltsim {

void assemble(const Model& m, const Drive& d, double alpha, double beta, const BlockMatrix& C, const BlockMatrix& K, int rows,
              Eigen::SparseMatrix<double>& A) {
  const int n = m.n_el(), np = m.n_border(), ne = 3 * n;
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(27 * n + 6 * n * np + np * np + rows);
  auto block = [&](int bi, int bj, const Mat3& c, const Mat3& k) {
    for (int r = 0; r < 3; ++r)
      for (int s = 0; s < 3; ++s) t.emplace_back(3 * bi + r, 3 * bj + s, -beta * c(r, s) - k(r, s));
  };
  for (int i = 0; i < n; ++i) {
    block(i, i, C.diag[i], K.diag[i]);
    block(i, before(i, n), C.lower[i], K.lower[i]);
    block(i, after(i, n), C.upper[i], K.upper[i]);
  }
  for (int k = 0; k < ne; ++k) t.emplace_back(k, k, alpha * d.mass(m, k));
  if (rows > ne) {
    for (int j = 0; j < np; ++j) {
      for (int k = 0; k < ne; ++k) {
        t.emplace_back(k, ne + j, -beta * C.elem_pulley(k, j) - K.elem_pulley(k, j));
        t.emplace_back(ne + j, k, -beta * C.pulley_elem(j, k) - K.pulley_elem(j, k));
      }
      for (int l = 0; l < np; ++l)
        t.emplace_back(ne + j, ne + l, -beta * C.pulley_pulley(j, l) - K.pulley_pulley(j, l));
      t.emplace_back(ne + j, ne + j, alpha * d.mass(m, ne + j));
    }
  }
  A.resize(rows, rows);
  A.setFromTriplets(t.begin(), t.end());
}

void assemble_ode_jacobian(const Model& m, const Drive& d, const BlockMatrix& K, const BlockMatrix& C,
                           const BristleJacobian* B, Eigen::SparseMatrix<double>& J) {
  const int n = m.n_el(), np = m.n_border(), ne = 3 * n, N = m.n_coord(), S = m.n_state();
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(2 * 27 * n + 4 * ne * np + 2 * np * np + 2 * S);
  for (int k = 0; k < S; ++k) t.emplace_back(k, k, 0.0);
  for (int k = 0; k < N; ++k) {
    const bool prescribed = k >= ne && k - ne < m.n_p() && d.kinematic(k - ne);
    if (!prescribed) t.emplace_back(k, N + k, 1.0);
  }
  auto block = [&](int bi, int bj, const Mat3& c, const Mat3& k) {
    for (int r = 0; r < 3; ++r) {
      const double inv_m = 1.0 / d.mass(m, 3 * bi + r);
      for (int s = 0; s < 3; ++s) {
        t.emplace_back(N + 3 * bi + r, 3 * bj + s, k(r, s) * inv_m);
        t.emplace_back(N + 3 * bi + r, N + 3 * bj + s, c(r, s) * inv_m);
      }
    }
  };
  for (int i = 0; i < n; ++i) {
    block(i, i, C.diag[i], K.diag[i]);
    block(i, before(i, n), C.lower[i], K.lower[i]);
    block(i, after(i, n), C.upper[i], K.upper[i]);
  }
  for (int j = 0; j < np; ++j) {
    const double inv_p = 1.0 / d.mass(m, ne + j);
    for (int k = 0; k < ne; ++k) {
      const double inv_m = 1.0 / d.mass(m, k);
      t.emplace_back(N + k, ne + j, K.elem_pulley(k, j) * inv_m);
      t.emplace_back(N + k, N + ne + j, C.elem_pulley(k, j) * inv_m);
      t.emplace_back(N + ne + j, k, K.pulley_elem(j, k) * inv_p);
      t.emplace_back(N + ne + j, N + k, C.pulley_elem(j, k) * inv_p);
    }
    for (int l = 0; l < np; ++l) {
      t.emplace_back(N + ne + j, ne + l, K.pulley_pulley(j, l) * inv_p);
      t.emplace_back(N + ne + j, N + ne + l, C.pulley_pulley(j, l) * inv_p);
    }
  }
  if (B) {
    const int zo = m.bristle_offset();
    for (int i = 0; i < n; ++i) {
      const int row = zo + i;
      t.emplace_back(row, row, B->dz[i]);
      for (int r = 0; r < 2; ++r) {
        t.emplace_back(row, 3 * i + r, B->dP[i][r]);
        t.emplace_back(row, N + 3 * i + r, B->dV[i][r]);
        t.emplace_back(N + 3 * i + r, row, B->F[i][r] / d.mass(m, 3 * i + r));
      }
      for (int b = 0; b < np; ++b) {
        t.emplace_back(row, ne + b, B->dq_b(i, b));
        t.emplace_back(row, N + ne + b, B->dv_b(i, b));
        t.emplace_back(N + ne + b, row, B->F_b(b, i) / d.mass(m, ne + b));
      }
    }
  }
  J.resize(S, S);
  J.setFromTriplets(t.begin(), t.end());
}

}  // namespace beltsim
