// Per-pair contact and friction laws shared by contact.cpp and friction.cpp, and read by the
// integrator's Newton aids (integrate/newton_aids.cpp); not part of the model's interface.
// normal_law and friction_law are defined here, inline: every right-hand side calls them for each
// element and pulley, and inlined into contact_forces they took the dry second at rtol 7e-4 from
// 0.28–0.29 to 0.26–0.27 s (alternating runs; the same numbers to the last bit). Their formulas and
// derivatives are at the top of contact.cpp and friction.cpp.
#pragma once

#include <algorithm>
#include <cmath>

#include "model/forces.hpp"

namespace beltsim {

// normal contact of one element centre P (velocity V) with a pulley (centre c, radius R)
struct NormalLaw {
  double r = 0, p = 0, pdot = 0;   // distance to the centre, penetration, penetration rate
  double N = 0, N_el = 0;          // clamped normal force, its elastic part
  double N_free = 0;               // the normal force before the clamp (N = max(N_free, 0))
  double delta = 0;                // damping ramp δ(p)
  Vec2 n, t;                       // outward normal, tangent (n rotated +90°)
  bool pushing = false;            // N > 0 (not clamped)
  Eigen::RowVector2d dN_dP, dN_dV; // filled by normal_law_derivatives
};
// returns false when the element is not inside the pulley's contact circle
inline bool normal_law(const Contact& c, const Vec2& P, const Vec2& V, const Vec2& centre, double R, NormalLaw& o) {
  const Vec2 rv = P - centre;
  const double r2 = rv.squaredNorm();
  if (r2 >= R * R) return false;
  o.r = std::sqrt(r2);
  o.n = rv / o.r;
  o.t = perp(o.n);
  o.p = R - o.r;
  o.pdot = -o.n.dot(V);
  o.delta = std::min(o.p / c.p_max, 1.0);
  o.N_el = (c.c1 * o.p + c.c2) * o.p;
  o.N_free = o.N_el + o.delta * c.b * o.pdot;
  o.pushing = o.N_free > 0;
  o.N = o.pushing ? o.N_free : 0.0;
  return true;
}
void normal_law_derivatives(const Contact& c, const Vec2& V, NormalLaw& nl);

// friction of the same pair: force on the element -mu_eff·N·t̂, moment on the pulley r·mu_eff·N
struct FrictionLaw {
  double vT = 0;       // slip velocity of the element against the pulley surface [m/s]
  double mu_eff = 0;   // mu_i·sat(vT/dv)
  double dmu = 0;      // d mu_eff / d vT
};
inline FrictionLaw friction_law(double mu_i, double dv, const NormalLaw& nl, const Vec2& V, double omega) {
  FrictionLaw fl;
  fl.vT = V.dot(nl.t) - omega * nl.r;
  const double x = fl.vT / dv;
  if (std::abs(x) < 1.0) {
    fl.mu_eff = mu_i * x;
    fl.dmu = mu_i / dv;
  } else {
    fl.mu_eff = std::copysign(mu_i, x);
    fl.dmu = 0.0;
  }
  return fl;
}
// adds the friction terms of the pair to the element's and pulley's Jacobian rows
struct PairJacobian {
  Eigen::Matrix2d dF_dP, dF_dV;       // element force rows (x, y) w.r.t. its position, velocity
  Vec2 dF_dOmega;                     // element force w.r.t. the pulley speed
  Eigen::RowVector2d dM_dP, dM_dV;    // pulley moment w.r.t. the element's position, velocity
  double dM_dOmega;                   // pulley moment w.r.t. its own speed
};
void friction_jacobian(const NormalLaw& nl, const FrictionLaw& fl, const Vec2& V, double omega, PairJacobian& J);

}  // namespace beltsim
