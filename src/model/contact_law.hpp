// Per-pair contact and friction laws shared by contact.cpp and friction.cpp, and read by the
// integrator's Newton aids (integrate/newton_aids.cpp); not part of the model's interface.
#pragma once

#include "model/forces.hpp"

namespace beltsim {

// normal contact of one element centre P (velocity V) with a pulley (centre c, radius R)
struct NormalLaw {
  double r = 0, p = 0, pdot = 0;   // distance to the centre, penetration, penetration rate
  double N = 0, N_el = 0;          // clamped normal force, its elastic part
  double delta = 0;                // damping ramp δ(p)
  Vec2 n, t;                       // outward normal, tangent (n rotated +90°)
  bool pushing = false;            // N > 0 (not clamped)
  Eigen::RowVector2d dN_dP, dN_dV; // filled by normal_law_derivatives
};
// returns false when the element is not inside the pulley's contact circle
bool normal_law(const Contact& c, const Vec2& P, const Vec2& V, const Vec2& centre, double R, NormalLaw& out);
void normal_law_derivatives(const Contact& c, const Vec2& V, NormalLaw& nl);

// friction of the same pair: force on the element -mu_eff·N·t̂, moment on the pulley r·mu_eff·N
struct FrictionLaw {
  double vT = 0;       // slip velocity of the element against the pulley surface [m/s]
  double mu_eff = 0;   // mu_i·sat(vT/dv)
  double dmu = 0;      // d mu_eff / d vT
};
FrictionLaw friction_law(double mu_i, double dv, const NormalLaw& nl, const Vec2& V, double omega);
// adds the friction terms of the pair to the element's and pulley's Jacobian rows
struct PairJacobian {
  Eigen::Matrix2d dF_dP, dF_dV;       // element force rows (x, y) w.r.t. its position, velocity
  Vec2 dF_dOmega;                     // element force w.r.t. the pulley speed
  Eigen::RowVector2d dM_dP, dM_dV;    // pulley moment w.r.t. the element's position, velocity
  double dM_dOmega;                   // pulley moment w.r.t. its own speed
};
void friction_jacobian(const NormalLaw& nl, const FrictionLaw& fl, const Vec2& V, double omega, PairJacobian& J);

}  // namespace beltsim
