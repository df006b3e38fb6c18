#include "model/sparse.hpp"

#include <vector>

namespace beltsim {

void assemble(const Model& m, double alpha, double beta, const BlockMatrix& C, const BlockMatrix& K, int rows,
              Eigen::SparseMatrix<double>& A) {
  const int n = m.n_el(), np = m.n_p(), ne = 3 * n;
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(27 * n + 6 * n * np + np * np + rows);
  auto block = [&](int bi, int bj, const Mat3& c, const Mat3& k) {
    for (int r = 0; r < 3; ++r)
      for (int s = 0; s < 3; ++s) t.emplace_back(3 * bi + r, 3 * bj + s, -beta * c(r, s) - k(r, s));
  };
  for (int i = 0; i < n; ++i) {
    block(i, i, C.diag[i], K.diag[i]);
    block(i, (i + n - 1) % n, C.lower[i], K.lower[i]);
    block(i, (i + 1) % n, C.upper[i], K.upper[i]);
  }
  for (int k = 0; k < ne; ++k) t.emplace_back(k, k, alpha * m.mass_of(k));
  if (rows > ne) {
    for (int j = 0; j < np; ++j) {
      for (int k = 0; k < ne; ++k) {
        t.emplace_back(k, ne + j, -beta * C.elem_pulley(k, j) - K.elem_pulley(k, j));
        t.emplace_back(ne + j, k, -beta * C.pulley_elem(j, k) - K.pulley_elem(j, k));
      }
      for (int l = 0; l < np; ++l)
        t.emplace_back(ne + j, ne + l, -beta * C.pulley_pulley(j, l) - K.pulley_pulley(j, l));
      t.emplace_back(ne + j, ne + j, alpha * m.mass_of(ne + j));
    }
  }
  A.resize(rows, rows);
  A.setFromTriplets(t.begin(), t.end());
}

}  // namespace beltsim
