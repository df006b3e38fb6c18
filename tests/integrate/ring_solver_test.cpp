// The O(n) ring-plus-border solver against a general sparse LU on the same matrix, at running
// states of the paper's drive (60 elements) and of the automotive drive (150, a back-side idler),
// for shifts s from 1e2 to 1e7 (step sizes 1e-2 .. 1e-7 s). Both are backward-stable direct
// solvers of the same system; their solutions agree to the conditioning of A times the rounding
// unit (measured ≤ 3e-11 relative); bound 1e-8.
#include <gtest/gtest.h>

#include <random>

#include <Eigen/SparseLU>

#include "integrate/ring_solver.hpp"
#include "model/rhs.hpp"
#include "model/sparse.hpp"
#include "scene/presets.hpp"

namespace beltsim {
namespace {

void expect_same_solution(const SceneDef& d, unsigned seed) {
  const Scene sc = build_scene(d);
  const Model& m = sc.model;
  const int N = m.n_coord();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::VectorXd y = sc.y0;
  for (int k = 0; k < N; ++k) y[N + k] = 0.5 * u(rng);  // a moving state: stick and slip mixed
  Jacobian J;
  J.resize(m);
  jacobian(m, 0.1, y.data(), J);
  RingSolver ring;
  Eigen::SparseMatrix<double> A;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  for (double s : {1e2, 1e4, 1e5, 1e7}) {
    ASSERT_TRUE(ring.factor(m, s * s, s, J.C, J.K));
    assemble(m, s * s, s, J.C, J.K, N, A);
    lu.compute(A);
    ASSERT_EQ(lu.info(), Eigen::Success);
    Eigen::VectorXd r(N);
    for (int k = 0; k < N; ++k) r[k] = u(rng);
    Eigen::VectorXd x(N);
    ring.solve(r.data(), x.data());
    const Eigen::VectorXd ref = lu.solve(r);
    EXPECT_LT((x - ref).norm(), 1e-8 * ref.norm()) << "s = " << s;
  }
}

TEST(RingSolver, MatchesSparseLuOnThePaperDrive) { expect_same_solution(presets::paper_dry(), 1); }
TEST(RingSolver, MatchesSparseLuOnTheAutomotiveDrive) { expect_same_solution(presets::automotive_wet(), 2); }

}  // namespace
}  // namespace beltsim
