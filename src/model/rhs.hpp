// The right-hand side ẏ = F(t, y) of the first-order system and its Jacobian.
//   q̇ = v,   M·v̇ = f(t, q, v),   ė = power of each energy channel (when tracked)
// with f the sum of the force laws in forces.hpp and M diagonal (Model::mass_of).
#pragma once

#include <vector>

#include "model/block_matrix.hpp"
#include "model/forces.hpp"
#include "model/model.hpp"
#include "model/two_way.hpp"

namespace beltsim {

// A belt of kHalvesElements elements or more (two_way.hpp) is evaluated in two halves at once
// when the caller gives Halves: the worker thread and each half's sums over elements (forces.hpp,
// Span).
struct Halves {
  explicit Halves(const Model& m);
  TwoWay two;
  // half p's sums: np pulley moments, the energy rates, np ∂M/∂Ω
  double* sum(int p) { return storage_.data() + first_ + p * stride_; }

 private:
  std::vector<double> storage_;
  int first_ = 0, stride_ = 0;
};

// writes dy (length n_state) for y at time t; `axes` (may be null) keeps the elements' axes
// between evaluations (forces.hpp); `halves` (may be null) splits a long belt in two
void rhs(const Model& m, double t, const double* y, double* dy, AxisMemo* axes = nullptr, Halves* halves = nullptr);

// ∂f/∂q, ∂f/∂v and ∂f/∂t at (t, y). The energy rows are not part of it: they are pure
// quadratures that feed nothing back, and the integrators treat them as such (W-method).
struct Jacobian {
  BlockMatrix K, C;
  Eigen::VectorXd f_t;
  void resize(const Model& m);
};
void jacobian(const Model& m, double t, const double* y, Jacobian& J, AxisMemo* axes = nullptr,
              Halves* halves = nullptr);

// generalized forces only (length n_coord), for tests and diagnostics
void forces(const Model& m, double t, const double* y, double* f);

// total mechanical energy [J]: kinetic + SDE + bending + contact + gravity
struct Energy {
  double kinetic = 0, sde = 0, bending = 0, contact = 0, gravity = 0;
  double total() const { return kinetic + sde + bending + contact + gravity; }
};
Energy energy(const Model& m, double t, const double* y);

}  // namespace beltsim
