// LuGre's bristles (bristles.cpp): each element's deflection z_i is a state of its own under
// Model::friction.law = lugre, y = [ q | v | e | z ]. Its rate, and the derivatives that couple it
// to the forces, for the right-hand side, the Jacobian and the integrators' linear solves.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "model/block_matrix.hpp"
#include "model/contacts.hpp"
#include "model/drive.hpp"
#include "model/forces.hpp"
#include "model/model.hpp"

namespace beltsim {

// ∂ż/∂y of every element's deflection and ∂f/∂z, the columns the deflections add to ∂f/∂y
// (nb = Model::n_border: the pulleys, the tensioner arms and the coupled rotors)
struct BristleJacobian {
  std::vector<double> dz;           // ∂ż_i/∂z_i [1/s]
  std::vector<Vec2> dP, dV;         // ∂ż_i/∂(x_i, y_i) [1/s], ∂ż_i/∂(ẋ_i, ẏ_i) [1]
  Eigen::MatrixXd dq_b, dv_b;       // n × nb: ∂ż_i/∂(border positions), ∂ż_i/∂(border velocities)
  std::vector<Vec2> F;              // ∂f_i/∂z_i: the element's force (x, y) [N/m]
  Eigen::MatrixXd F_b;              // nb × n: ∂f_b/∂z_i, the pulleys' and arms' moments [N]
  std::vector<double> t;            // ∂ż_i/∂t through a kinematic pulley's prescribed speed [m/s²]
  void resize(int n_el, int n_border);
  // every entry zero but ∂ż/∂z = -1/τ of an element under LuGre's law out of contact
  void clear(const Model& m);
};

// ż of every element from the records of its state's contact stage (contacts.hpp; elements out
// of contact relax)
void bristle_rates(const Model& m, const double* z, const ContactView& pairs, double* dz);
// writes the entries of the elements in contact in `pairs` to B (cleared by the caller)
void bristle_jacobian(const Model& m, const Drive& d, double t, const double* q, const double* v, const double* z,
                      const ContactView& pairs, BristleJacobian& B);

// The bristles eliminated from a linear solve with s·I - ∂F/∂y (bristles.cpp): with
// D_i = 1/(s - ∂ż_i/∂z_i), u_z = D·(r_z + H_q·u_q + H_v·u_v), which leaves the mechanical rows
// with K' = K + Z·D·H_q, C' = C + Z·D·H_v (Z = ∂f/∂z) and the right-hand side M·r_v + Z·D·r_z.
// eliminate: K', C' (copies of K, C with the terms added) and D
void bristle_eliminate(const Model& m, const BristleJacobian& B, double s, const BlockMatrix& K, const BlockMatrix& C,
                       BlockMatrix& K_eff, BlockMatrix& C_eff, std::vector<double>& D);
// adds Z·D·r_z to f (length n_coord)
void bristle_load(const Model& m, const BristleJacobian& B, const std::vector<double>& D, const double* r_z, double* f);
// u_z from r_z and the mechanical solution u_q, u_v
void bristle_back(const Model& m, const BristleJacobian& B, const std::vector<double>& D, const double* r_z,
                  const double* u_q, const double* u_v, double* u_z);

}  // namespace beltsim
