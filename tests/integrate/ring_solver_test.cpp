// The O(n) ring-plus-border solver against a general sparse LU on the same matrix, at running
// states of the paper's drive (60 elements), of the automotive drive (150, a back-side idler) and
// of the paper's drive refined to 600 and 2 400 elements (the ring split in two chains), for
// shifts s from 1e2 to 1e7 (step sizes 1e-2 .. 1e-7 s). Both are backward-stable direct solvers
// of the same system; their solutions agree to the conditioning of A times the rounding unit
// (measured ≤ 3e-11 relative); bound 1e-8.
#include <gtest/gtest.h>

#include <cstring>
#include <random>

#include <Eigen/SparseLU>

#include "integrate/belt_system.hpp"
#include "integrate/ring_solver.hpp"
#include "model/rhs.hpp"
#include "model/sparse.hpp"
#include "support/presets.hpp"

namespace beltsim {
namespace {

Eigen::VectorXd moving_state(const Scene& sc, std::mt19937& rng) {
  const int N = sc.model.n_coord();
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::VectorXd y = sc.y0;
  for (int k = 0; k < N; ++k) y[N + k] = 0.5 * u(rng);  // a moving state: stick and slip mixed
  return y;
}

SceneDef refined(int n) {
  SceneDef d = presets::paper_dry();
  d.belt.elements = n;
  return d;
}

void expect_same_solution(const SceneDef& d, unsigned seed) {
  const Scene sc = build_scene(d);
  const Model& m = sc.model;
  const Drive& dr = sc.drive;
  const int N = m.n_coord();
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  const Eigen::VectorXd y = moving_state(sc, rng);
  Jacobian J;
  J.resize(m);
  jacobian(m, dr, 0.1, y.data(), J);
  RingSolver ring;
  Eigen::SparseMatrix<double> A;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  for (double s : {1e2, 1e4, 1e5, 1e7}) {
    ASSERT_TRUE(ring.factor(m, dr, s * s, s, J.C, J.K));
    assemble(m, dr, s * s, s, J.C, J.K, N, A);
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
// a tensioner arm: one more border row and column (its angle), coupled to the idler's elements,
// its speed and itself; on a ring split in two as well
TEST(RingSolver, MatchesSparseLuWithATensionerArm) {
  expect_same_solution(presets::automotive_tensioner(), 5);
  SceneDef d = presets::automotive_tensioner();
  d.belt.elements = 600;
  expect_same_solution(d, 6);
}
// coupled rotors: border rows and columns joined only to their pulleys (a one-way coupling's hub
// and rotor to each other), beside an arm; on a free and on a kinematic pulley; on a ring split in
// two as well (600 elements)
TEST(RingSolver, MatchesSparseLuWithCoupledRotors) {
  for (const int n : {150, 600}) {
    SceneDef d = presets::automotive_tensioner();
    d.belt.elements = n;
    d.pulleys[0].torque = TimeSpeedLaw{};
    d.pulleys[0].kinematic = true;
    d.pulleys[0].speed.constant = -60;
    d.pulleys[0].coupling.emplace().inertia = 1e-3;
    d.pulleys[0].coupling->stiffness = 200;
    CouplingDef& c = d.pulleys[2].coupling.emplace();
    c.inertia = 2e-3, c.stiffness = 15, c.damping = 0.01, c.one_way = true;
    expect_same_solution(d, 7);
  }
}
TEST(RingSolver, MatchesSparseLuOnASplitRing) {
  static_assert(600 >= kHalvesElements && 60 < kHalvesElements);
  expect_same_solution(refined(600), 3);
  expect_same_solution(refined(601), 4);  // odd: chains of 299 and 300 elements
}

// The split ring's two chains give the same bits whether they run at once on two threads, one
// after the other in TwoWay without a worker, or without TwoWay (ring_solver.hpp), and a solve
// may overwrite its right-hand side.
TEST(RingSolver, SplitGivesTheSameBitsOnOneOrTwoThreads) {
  const Scene sc = build_scene(refined(600));
  const Model& m = sc.model;
  const Drive& dr = sc.drive;
  const int N = m.n_coord();
  std::mt19937 rng(5);
  const Eigen::VectorXd y = moving_state(sc, rng);
  Jacobian J;
  J.resize(m);
  jacobian(m, dr, 0.1, y.data(), J);
  Eigen::VectorXd r(N);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int k = 0; k < N; ++k) r[k] = u(rng);
  TwoWay with_worker(true), without(false);
  std::vector<Eigen::VectorXd> xs;
  for (TwoWay* two : {&with_worker, &without, static_cast<TwoWay*>(nullptr)}) {
    RingSolver ring;
    for (int rep = 0; rep < 50; ++rep) {  // repeated: the worker must not lose a generation
      ASSERT_TRUE(ring.factor(m, dr, 1e10, 1e5, J.C, J.K, two));
      Eigen::VectorXd x = r;
      ring.solve(x.data(), x.data());
      if (rep == 0) xs.push_back(x);
      ASSERT_EQ(0, std::memcmp(x.data(), xs.back().data(), sizeof(double) * N)) << "repetition " << rep;
    }
  }
  EXPECT_EQ(0, std::memcmp(xs[0].data(), xs[1].data(), sizeof(double) * N)) << "two threads against one";
  EXPECT_EQ(0, std::memcmp(xs[0].data(), xs[2].data(), sizeof(double) * N)) << "two threads against none";
}

// BeltLinearSolver's solve of (s·I - J)·u = r for the first-order system, J = ∂F/∂y from
// sparse_jacobian, at 60 elements (one core) and 600 (the halves and the split ring): the
// componentwise backward error max_i |(s·u - J·u - r)_i| / (|s·u| + |J|·|u| + |r|)_i of a stable
// direct solve is a small multiple of the rounding unit (measured: at most 4.4e-13, at s = 1e2); bound 1e-11.
// Under LuGre's law the bristles' rows are eliminated first (model/bristles.hpp): the same bound,
// with deflections up to the static limit.
// the largest residual of (s·I - J)·x = r, J the ODE Jacobian assembled whole, each row relative
// to the sum of the magnitudes it adds
double shifted_residual(BeltSystem& sys, const Eigen::SparseMatrix<double>& J, double s, std::mt19937& rng) {
  const int M = static_cast<int>(J.rows());
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::VectorXd r(sys.problem.size()), x(sys.problem.size());
  for (int k = 0; k < sys.problem.size(); ++k) r[k] = u(rng);
  sys.linear.solve(r.data(), x.data());
  const Eigen::VectorXd res = s * x.head(M) - J * x.head(M) - r.head(M);
  const Eigen::VectorXd scale = (s * x.head(M)).cwiseAbs() + J.cwiseAbs() * x.head(M).cwiseAbs() + r.head(M).cwiseAbs();
  return res.cwiseAbs().cwiseQuotient(scale).maxCoeff();
}

// One solver taken through states with different contacts (as an integration takes it) solves
// each state's system as the whole Jacobian gives it: the element–pulley entries are cleared and
// multiplied where their writers mark them (BlockMatrix::border_cols), and an entry written but not
// marked, or one left from an earlier state, fails this. The reference is a new system's
// Jacobian, assembled whole (sparse_jacobian reads every entry). Scenes with every writer: the
// contact pairs, a tensioner arm's column, LuGre's bristles, on one chain and on a split ring.
TEST(RingSolver, ReusedAcrossStatesSolvesEachStatesSystem) {
  std::vector<SceneDef> defs{presets::automotive_tensioner(), refined(60), refined(600)};
  defs[1].friction.law = FrictionKind::lugre;
  for (const SceneDef& d : defs) {
    const Scene sc = build_scene(d);
    const Model& m = sc.model;
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> w(-1, 1);
    BeltSystem reused(sc.model, sc.drive);
    for (int k = 0; k < 3; ++k) {
      Eigen::VectorXd y = moving_state(sc, rng);
      const int N = m.n_coord();
      for (int i = 0; i < m.n_el(); ++i) y[3 * i + 1] += 2e-4 * w(rng);  // contacts made and lost
      for (int i = 0; i < m.n_bristle(); ++i) y[m.bristle_offset() + i] = w(rng) * 1.3 / m.friction.bristle_stiffness;
      for (int a = 0; a < m.n_arm(); ++a) y[N + m.arm_coord(a)] = 2 * w(rng);
      BeltSystem fresh(sc.model, sc.drive);
      Eigen::SparseMatrix<double> J;
      ASSERT_TRUE(fresh.linear.sparse_jacobian(0.1, y.data(), J));
      ASSERT_TRUE(reused.linear.prepare_jacobian(0.1, y.data()));
      for (double s : {1e2, 1e5}) {
        ASSERT_TRUE(reused.linear.factor(s));
        EXPECT_LT(shifted_residual(reused, J, s, rng), 1e-11) << m.n_el() << " elements, state " << k << ", s = " << s;
      }
    }
  }
}

TEST(RingSolver, BeltLinearSolverSolvesTheShiftedSystem) {
  for (const bool bristles : {false, true})
  for (int n : {60, 600}) {
    SceneDef d = refined(n);
    if (bristles) d.friction.law = FrictionKind::lugre;
    const Scene sc = build_scene(d);
    const Model& m = sc.model;
    const Drive& dr = sc.drive;
    std::mt19937 rng(7);
    Eigen::VectorXd y = moving_state(sc, rng);
    std::uniform_real_distribution<double> w(-1, 1);
    for (int i = 0; i < m.n_bristle(); ++i) y[m.bristle_offset() + i] = w(rng) * 1.3 / m.friction.bristle_stiffness;
    BeltSystem sys(m, dr);
    Eigen::SparseMatrix<double> J;
    ASSERT_TRUE(sys.linear.sparse_jacobian(0.1, y.data(), J));
    ASSERT_TRUE(sys.linear.prepare_jacobian(0.1, y.data()));
    for (double s : {1e2, 1e5}) {
      ASSERT_TRUE(sys.linear.factor(s));
      EXPECT_LT(shifted_residual(sys, J, s, rng), 1e-11) << n << " elements, s = " << s << (bristles ? ", LuGre" : "");
    }
  }
}

}  // namespace
}  // namespace beltsim
