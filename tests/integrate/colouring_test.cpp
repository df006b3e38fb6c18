// Column colouring and the coloured difference-quotient Jacobian of the CVODE peer (cvode-fd):
// the colouring of a known pattern, a valid colouring of the belt's pattern, and the difference
// quotients against the analytic Jacobian on the paper's dry drive.
#include "integrate/colouring.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "integrate/belt_system.hpp"
#include "integrate/driver.hpp"
#include "integrate/stepper.hpp"
#include "support/presets.hpp"

namespace beltsim {
namespace {

Eigen::SparseMatrix<double> pattern(int n, const std::vector<std::pair<int, int>>& entries) {
  std::vector<Eigen::Triplet<double>> t;
  for (auto [r, c] : entries) t.emplace_back(r, c, 1.0);
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(t.begin(), t.end());
  return A;
}

// tridiagonal: columns k and k+3 share no row, so three colours, k mod 3 (the greedy order finds
// exactly that); a diagonal matrix needs one; a full row forces every column apart
TEST(Colouring, KnownPatterns) {
  std::vector<std::pair<int, int>> tri, diag, arrow;
  const int n = 10;
  for (int k = 0; k < n; ++k) {
    diag.emplace_back(k, k);
    tri.emplace_back(k, k);
    if (k > 0) tri.emplace_back(k, k - 1), tri.emplace_back(k - 1, k);
    arrow.emplace_back(k, k), arrow.emplace_back(0, k);
  }
  const ColumnColouring c3 = colour_columns(pattern(n, tri));
  EXPECT_EQ(c3.colours, 3);
  for (int k = 0; k < n; ++k) EXPECT_EQ(c3.colour[static_cast<size_t>(k)], k % 3);
  EXPECT_TRUE(valid_colouring(pattern(n, tri), c3));
  EXPECT_EQ(colour_columns(pattern(n, diag)).colours, 1);
  EXPECT_EQ(colour_columns(pattern(n, arrow)).colours, n);
  // a colouring that puts neighbours together is refused
  ColumnColouring bad = c3;
  bad.colour[1] = 0;
  EXPECT_FALSE(valid_colouring(pattern(n, tri), bad));
}

struct Compare {
  double worst = 0;  // largest |J_fd − J| of a column relative to that column's largest |J|
  int worst_col = -1;
};

Compare compare(BeltSystem& sys, double t, const Eigen::VectorXd& y, long* rhs_taken = nullptr) {
  Eigen::SparseMatrix<double> Ja, Jd;
  sys.linear.sparse_jacobian(t, y.data(), Ja);
  Ja.makeCompressed();
  Jd = Ja;
  const ColumnColouring c = colour_columns(Ja);
  EXPECT_TRUE(valid_colouring(Ja, c));
  Eigen::VectorXd f0(y.size());
  sys.problem.rhs(t, y.data(), f0.data());
  std::vector<double> work;
  const long taken = difference_jacobian(sys.problem, c, t, y.data(), f0.data(), Jd, work);
  if (rhs_taken) *rhs_taken = taken;
  Compare out;
  for (int k = 0; k < Ja.outerSize(); ++k) {
    double big = 0, diff = 0;
    for (int e = Ja.outerIndexPtr()[k]; e < Ja.outerIndexPtr()[k + 1]; ++e) {
      big = std::max(big, std::abs(Ja.valuePtr()[e]));
      diff = std::max(diff, std::abs(Jd.valuePtr()[e] - Ja.valuePtr()[e]));
    }
    if (big == 0) continue;
    if (diff / big > out.worst) out.worst = diff / big, out.worst_col = k;
  }
  return out;
}

// Tolerance: a forward difference with step δ errs by |f''|·δ/2 (truncation) plus ε·|f|/δ
// (rounding). δ = √ε·max(|y|, typical) ≈ 1.5e-9 m for positions, 1.5e-8 m/s for velocities. The
// sharpest curvature is the contact law c1·p² + c2·p: f''/f' ≤ 2·c1/c2 ≈ 9.3e3 1/m, so ≤ 7e-6 of
// the entry (the geometry's, with curvature radius r_p ≈ 0.1 m, ~1e-8); rounding is ≲ 1e-7 of a
// column's largest entry (|f| ≲ 1e6 m/s² against entries ≳ 1e9 1/s²). So each column must agree
// to 2e-5 of its largest entry (measured: 1.5e-8 at rest, 1.4e-6 moving). A wrong colouring
// (two columns of one colour sharing a row) or a wrong step divisor gives errors of order 1.
// A state within δ of a kink (|v_T| = Δv, contact onset) would break the bound: the states used
// here have none (the moving one was checked by this bound).
TEST(Colouring, DifferenceJacobianMatchesTheAnalyticOne) {
  constexpr double tol = 2e-5;
  const Scene sc = build_scene(presets::paper_dry());
  BeltSystem sys(sc.model, sc.drive);
  long taken = 0;
  const Compare at_rest = compare(sys, 0, sc.y0, &taken);
  EXPECT_LT(at_rest.worst, tol) << sys.problem.describe(at_rest.worst_col);
  // one right-hand side per colour; the two pulley-speed rows touch every element column, so
  // the belt's pattern needs about as many colours as columns (docs/integration.md)
  EXPECT_GT(taken, 0);
  EXPECT_LE(taken, sys.problem.size());
  // moving: the drive after 0.05 s, elements in stick and slip on both pulleys
  Eigen::VectorXd y = sc.y0;
  DriveOptions opt;
  opt.t_end = 0.05;
  opt.sample_dt = 0.05;
  opt.events = sc.drive.breakpoints();
  auto st = make_stepper("esdirk32");
  drive(sys, *st, Tolerances{1e-6, -1}, opt, y, [](double, const Eigen::VectorXd&) {});
  const Compare moving = compare(sys, 0.05, y);
  EXPECT_LT(moving.worst, tol) << sys.problem.describe(moving.worst_col);
}

}  // namespace
}  // namespace beltsim
