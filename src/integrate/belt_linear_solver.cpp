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
  const int zo = model_.bristle_offset();
  for (int i = 0; i < model_.n_bristle(); ++i) f_t[zo + i] = J_.B.t[i];
}

bool BeltLinearSolver::sparse_jacobian(double t, const double* y, Eigen::SparseMatrix<double>& J) {
  jacobian(model_, drive_, t, y, J_, &ws_);
  assemble_ode_jacobian(model_, drive_, J_.K, J_.C, model_.n_bristle() ? &J_.B : nullptr, J);
  return true;
}

bool BeltLinearSolver::factor(double s) {
  s_ = s;
  const int N = model_.n_coord();
  mass_.resize(N);
  for (int k = 0; k < N; ++k) mass_[k] = drive_.mass(model_, k);
  TwoWay* two = ws_.halves ? &ws_.halves->two : nullptr;
  if (!model_.n_bristle()) {
    K_ = &J_.K;
    return solver_.factor(model_, drive_, s * s, s, J_.C, J_.K, two);
  }
  bristle_eliminate(model_, J_.B, s, J_.K, J_.C, K_eff_, C_eff_, D_);
  K_ = &K_eff_;
  return solver_.factor(model_, drive_, s * s, s, C_eff_, K_eff_, two);
}

void BeltLinearSolver::solve(const double* r, double* u) {
  const int N = model_.n_coord();
  const double s = s_;
  rhs_.resize(N);
  kr_.resize(N);
  const BlockMatrix& K = *K_;
  const double* r_z = r + model_.bristle_offset();
  if (model_.n_bristle()) {
    // Z·D·r_z joins M·r_v: kept in kr_ until the rows add K·r_q
    fz_.setZero(N);
    bristle_load(model_, J_.B, D_, r_z, fz_.data());
  }
  auto rows = [&](int lo, int hi) {
    for (int k = lo; k < hi; ++k) rhs_[k] = s * mass_[k] * r[N + k] + kr_[k];
    if (model_.n_bristle())
      for (int k = lo; k < hi; ++k) rhs_[k] += s * fz_[k];
  };
  if (!ws_.halves) {
    K.multiply(r, kr_.data());
    rows(0, N);
  } else {
    // each half multiplies the rows of K it assembled (read by this thread, they would have to
    // come over from the other core's cache and go back for the next Jacobian)
    const int n = model_.n_el();
    ws_.halves->two.run([&](int p) {
      const HalfRange e = half_range(n, p);
      K.multiply_elements(r, kr_.data(), e.lo, e.hi);
      rows(3 * e.lo, 3 * e.hi);
    });
    K.multiply_pulleys(r, kr_.data());
    rows(3 * n, N);
  }
  uv_.resize(N);
  solver_.solve(rhs_.data(), uv_.data());
  for (int k = 0; k < N; ++k) {
    u[N + k] = uv_[k];
    u[k] = (r[k] + uv_[k]) / s;
  }
  for (int k = 2 * N; k < model_.bristle_offset(); ++k) u[k] = r[k] / s;
  if (model_.n_bristle()) bristle_back(model_, J_.B, D_, r_z, u, u + N, u + model_.bristle_offset());
}

}  // namespace beltsim
