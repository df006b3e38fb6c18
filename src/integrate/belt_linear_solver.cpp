#include "integrate/belt_linear_solver.hpp"

#include "model/sparse.hpp"

namespace beltsim {

BeltLinearSolver::BeltLinearSolver(const Model& m, const Drive& d, Workspace& ws) : model_(m), drive_(d), ws_(ws) {
  J_.resize(m);
}

bool BeltLinearSolver::prepare_jacobian(double t, const double* y) {
  jacobian(model_, drive_, t, y, J_, &ws_);
  return true;
}

void BeltLinearSolver::time_derivative(double* f_t) const {
  const int N = model_.n_coord();
  for (int k = 0; k < N; ++k) f_t[N + k] = J_.f_t[k] / drive_.mass(model_, k);
}

bool BeltLinearSolver::sparse_jacobian(double t, const double* y, Eigen::SparseMatrix<double>& J) {
  jacobian(model_, drive_, t, y, J_, &ws_);
  assemble_ode_jacobian(model_, drive_, J_.K, J_.C, J);
  return true;
}

bool BeltLinearSolver::factor(double s) {
  s_ = s;
  return solver_.factor(model_, drive_, s * s, s, J_.C, J_.K, ws_.halves ? &ws_.halves->two : nullptr);
}

void BeltLinearSolver::solve(const double* r, double* u) {
  const int N = model_.n_coord();
  const double s = s_;
  rhs_.resize(N);
  kr_.resize(N);
  auto rows = [&](int lo, int hi) {
    for (int k = lo; k < hi; ++k) rhs_[k] = s * drive_.mass(model_, k) * r[N + k] + kr_[k];
  };
  if (!ws_.halves) {
    J_.K.multiply(r, kr_.data());
    rows(0, N);
  } else {
    // each half multiplies the rows of K it assembled (read by this thread, they would have to
    // come over from the other core's cache and go back for the next Jacobian)
    const int n = model_.n_el();
    ws_.halves->two.run([&](int p) {
      const HalfRange e = half_range(n, p);
      J_.K.multiply_elements(r, kr_.data(), e.lo, e.hi);
      rows(3 * e.lo, 3 * e.hi);
    });
    J_.K.multiply_pulleys(r, kr_.data());
    rows(3 * n, N);
  }
  uv_.resize(N);
  solver_.solve(rhs_.data(), uv_.data());
  for (int k = 0; k < N; ++k) {
    u[N + k] = uv_[k];
    u[k] = (r[k] + uv_[k]) / s;
  }
  for (int k = 2 * N; k < model_.n_state(); ++k) u[k] = r[k] / s;
}

}  // namespace beltsim
