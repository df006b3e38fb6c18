#include "integrate/colouring.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace beltsim {

namespace {

// rows of each column and columns of each row, from the stored entries
void adjacency(const Eigen::SparseMatrix<double>& A, std::vector<std::vector<int>>& rows_of,
               std::vector<std::vector<int>>& cols_of) {
  rows_of.assign(static_cast<size_t>(A.cols()), {});
  cols_of.assign(static_cast<size_t>(A.rows()), {});
  for (Eigen::Index c = 0; c < A.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(A, c); it; ++it) {
      const int r = static_cast<int>(it.row()), k = static_cast<int>(it.col());
      rows_of[static_cast<size_t>(k)].push_back(r);
      cols_of[static_cast<size_t>(r)].push_back(k);
    }
}

}  // namespace

ColumnColouring colour_columns(const Eigen::SparseMatrix<double>& A) {
  std::vector<std::vector<int>> rows_of, cols_of;
  adjacency(A, rows_of, cols_of);
  const int n = static_cast<int>(A.cols());
  ColumnColouring out;
  out.colour.assign(static_cast<size_t>(n), -1);
  // forbidden[c] == k: colour c is taken by a column sharing a row with column k
  std::vector<int> forbidden(static_cast<size_t>(n) + 1, -1);
  for (int k = 0; k < n; ++k) {
    for (int r : rows_of[static_cast<size_t>(k)])
      for (int other : cols_of[static_cast<size_t>(r)]) {
        const int c = out.colour[static_cast<size_t>(other)];
        if (c >= 0) forbidden[static_cast<size_t>(c)] = k;
      }
    int c = 0;
    while (forbidden[static_cast<size_t>(c)] == k) ++c;
    out.colour[static_cast<size_t>(k)] = c;
    out.colours = std::max(out.colours, c + 1);
  }
  out.columns_of.assign(static_cast<size_t>(out.colours), {});
  for (int k = 0; k < n; ++k) out.columns_of[static_cast<size_t>(out.colour[static_cast<size_t>(k)])].push_back(k);
  return out;
}

bool valid_colouring(const Eigen::SparseMatrix<double>& A, const ColumnColouring& c) {
  std::vector<std::vector<int>> rows_of, cols_of;
  adjacency(A, rows_of, cols_of);
  if (c.colour.size() != static_cast<size_t>(A.cols())) return false;
  for (const std::vector<int>& cols : cols_of) {
    std::vector<char> seen(static_cast<size_t>(c.colours), 0);
    for (int k : cols) {
      const int col = c.colour[static_cast<size_t>(k)];
      if (col < 0 || col >= c.colours || seen[static_cast<size_t>(col)]) return false;
      seen[static_cast<size_t>(col)] = 1;
    }
  }
  return true;
}

long difference_jacobian(OdeProblem& sys, const ColumnColouring& c, double t, const double* y, const double* f0,
                         Eigen::SparseMatrix<double>& J, std::vector<double>& work) {
  const int n = sys.size();
  work.resize(2 * static_cast<size_t>(n));
  double* yp = work.data();
  double* fp = yp + n;
  std::copy(y, y + n, yp);
  const int* ptr = J.outerIndexPtr();
  const int* idx = J.innerIndexPtr();
  double* val = J.valuePtr();
  const double root_eps = std::sqrt(std::numeric_limits<double>::epsilon());
  for (const std::vector<int>& cols : c.columns_of) {
    for (int k : cols) yp[k] = y[k] + root_eps * std::max(std::abs(y[k]), sys.atol_scale(k));
    sys.rhs(t, yp, fp);
    for (int k : cols) {
      const double delta = yp[k] - y[k];  // the increment as represented
      for (int e = ptr[k]; e < ptr[k + 1]; ++e) {
        val[e] = (fp[idx[e]] - f0[idx[e]]) / delta;
        if (!std::isfinite(val[e])) return -1;
      }
      yp[k] = y[k];
    }
  }
  return c.colours;
}

}  // namespace beltsim
