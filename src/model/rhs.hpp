// The right-hand side ẏ = F(t, y) of the first-order system and its Jacobian.
//   q̇ = v,   M·v̇ = f(t, q, v, z),   ė = power of each energy channel (when tracked),
//   ż = the bristles' deflection rates (under LuGre's law, bristles.cpp)
// with f the sum of the force laws in forces.hpp and M diagonal (Drive::mass).
#pragma once

#include <vector>

#include "model/block_matrix.hpp"
#include "model/bristles.hpp"
#include "model/drive.hpp"
#include "model/forces.hpp"
#include "model/model.hpp"
#include "model/workspace.hpp"

namespace beltsim {

// writes dy (length n_state) for y at time t under the drive d; w (may be null: a workspace of
// its own, for tests) holds the evaluation's scratch (workspace.hpp) and receives the contact
// records of (t, y), filled here whatever w held (contacts.hpp)
void rhs(const Model& m, const Drive& d, double t, const double* y, double* dy, Workspace* w = nullptr);

// ∂f/∂q, ∂f/∂v and ∂f/∂t at (t, y), and under LuGre's law the bristles' rows and columns. The
// energy rows are not part of it: they are pure quadratures that feed nothing back, and the
// integrators treat them as such (W-method). The contact terms come from w's contact records of
// (t, y) (contacts_at: the right-hand side's at the same state, else filled here).
struct Jacobian {
  BlockMatrix K, C;
  Eigen::VectorXd f_t;
  BristleJacobian B;  // sized under LuGre's law only
  void resize(const Model& m);
};
void jacobian(const Model& m, const Drive& d, double t, const double* y, Jacobian& J, Workspace* w = nullptr);

// generalized forces only (length n_coord), for tests and diagnostics
void forces(const Model& m, const Drive& d, double t, const double* y, double* f);

// total mechanical energy [J]: kinetic + SDE + bending + contact + gravity + tensioner springs +
// coupling springs
struct Energy {
  double kinetic = 0, sde = 0, bending = 0, contact = 0, gravity = 0, arm = 0, coupling = 0;
  double total() const { return kinetic + sde + bending + contact + gravity + arm + coupling; }
};
Energy energy(const Model& m, const Drive& d, double t, const double* y);

}  // namespace beltsim
