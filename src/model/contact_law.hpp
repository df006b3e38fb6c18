// Per-pair contact and friction laws shared by contact.cpp and friction.cpp, and the contact pass
// that evaluates them for every element–pulley pair (contact_pass). The contact stage
// (contacts.hpp) runs it once per state and keeps its records, which the forces, the Jacobian,
// the integrator's Newton aids, the switching functions and the observables read.
// normal_law, friction_law and stribeck_law are defined here, inline: every right-hand side calls them for each
// element and pulley, so they are inlined into the contact pass. Their formulas and derivatives are
// at the top of contact.cpp and friction.cpp.
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
  Vec2 n = Vec2::Zero(), t = Vec2::Zero();  // outward normal, tangent (n rotated +90°)
  bool pushing = false;            // N > 0 (not clamped)
};
// ∂N/∂P and ∂N/∂V of a normal law (normal_law_derivatives; zero when clamped)
struct NormalJacobian {
  Eigen::RowVector2d dN_dP, dN_dV;
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
NormalJacobian normal_law_derivatives(const Contact& c, const Vec2& V, const NormalLaw& nl);

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
// ∂v_T/∂P of the slip velocity v_T = V·t - Ω·r above (∂t/∂P = -n·tᵀ/r, ∂r/∂P = nᵀ; friction.cpp's
// comment): -(V·n)/r·tᵀ - Ω·nᵀ; ∂v_T/∂V = tᵀ and ∂v_T/∂Ω = -r need no helper
inline Vec2 slip_velocity_dP(const NormalLaw& nl, const Vec2& V, double omega) {
  return -(V.dot(nl.n) / nl.r) * nl.t - omega * nl.n;
}
// Stribeck's law of the same pair (friction.cpp): μ_i·g(v_T)·sat(v_T/Δv) + μ_v·v_T with
// g(v) = 1 + (μ_s/μ_k - 1)·exp(-(|v|/v_s)^δ)
// g(v_T) - 1 = (μ_s/μ_k - 1)·exp(-powr), powr = (|v_T|/v_s)^δ, written to powr
inline double stribeck_peak(const Friction& f, double vT, double& powr) {
  powr = std::pow(std::abs(vT) / f.stribeck_speed, f.exponent);
  return (f.static_ratio - 1) * std::exp(-powr);
}
inline FrictionLaw stribeck_law(double mu_i, const Friction& f, const NormalLaw& nl, const Vec2& V, double omega) {
  FrictionLaw fl;
  fl.vT = V.dot(nl.t) - omega * nl.r;
  const double x = fl.vT / f.dv, a = std::abs(fl.vT);
  double powr;                                          // (|v_T|/v_s)^δ
  const double peak = stribeck_peak(f, fl.vT, powr);   // g - 1
  const double g = 1 + peak;
  if (std::abs(x) < 1.0) {
    fl.mu_eff = mu_i * g * x;
    fl.dmu = mu_i * (g - peak * f.exponent * powr) / f.dv;  // g'·sat + g·sat', g'·v = -(g - 1)·δ·powr
  } else {
    fl.mu_eff = std::copysign(mu_i * g, x);
    fl.dmu = -mu_i * peak * f.exponent * powr / a;
  }
  fl.mu_eff += f.viscous * fl.vT;
  fl.dmu += f.viscous;
  return fl;
}
// LuGre's law of the same pair (bristles.cpp): the element's bristle deflection z [m] and its
// rate, with g(v_T) = μ_i·(1 + (μ_s/μ_k - 1)·exp(-(|v_T|/v_s)^δ)) Stribeck's curve:
//   ż = v_T - σ0·|v_T|·z/g(v_T),   μ = σ0·z + σ1·ż + μ_v·v_T
// and the partial derivatives of both in v_T and z (with v·g'(v) = -(g - μ_i)·δ·(|v|/v_s)^δ).
// An element whose μ_i is 0 holds no bristle: ż = -z/τ, μ = μ_v·v_T.
struct Bristle {
  double zdot = 0, dzdot_dv = 0, dzdot_dz = 0;  // ż and its derivatives [1, 1/s]
  double mu = 0, dmu_dv = 0, dmu_dz = 0;        // μ and its derivatives [s/m, 1/m]
};
inline Bristle bristle_law(double mu_i, const Friction& f, double vT, double z) {
  Bristle b;
  if (mu_i <= 0) {
    b.zdot = -z / f.release_time;
    b.dzdot_dz = -1 / f.release_time;
    b.mu = f.viscous * vT, b.dmu_dv = f.viscous;
    return b;
  }
  double powr;                                                 // (|v_T|/v_s)^δ
  const double g = mu_i * (1 + stribeck_peak(f, vT, powr));    // Stribeck's curve
  const double s0 = f.bristle_stiffness, a = std::abs(vT), sg = (vT > 0) - (vT < 0);
  b.zdot = vT - s0 * a * z / g;
  b.dzdot_dz = -s0 * a / g;
  b.dzdot_dv = 1 - s0 * z * sg * (g + f.exponent * powr * (g - mu_i)) / (g * g);  // d(|v|/g)/dv
  b.mu = s0 * z + f.bristle_damping * b.zdot + f.viscous * vT;
  b.dmu_dv = f.bristle_damping * b.dzdot_dv + f.viscous;
  b.dmu_dz = s0 + f.bristle_damping * b.dzdot_dz;
  return b;
}
inline FrictionLaw lugre_law(double mu_i, const Friction& f, double z, const NormalLaw& nl, const Vec2& V,
                             double omega) {
  FrictionLaw fl;
  fl.vT = V.dot(nl.t) - omega * nl.r;
  const Bristle b = bristle_law(mu_i, f, fl.vT, z);
  fl.mu_eff = b.mu;
  fl.dmu = b.dmu_dv;  // at a fixed deflection: z is a state of its own
  return fl;
}
// adds the friction terms of the pair to the element's and pulley's Jacobian rows
struct PairJacobian {
  Eigen::Matrix2d dF_dP, dF_dV;       // element force rows (x, y) w.r.t. its position, velocity
  Vec2 dF_dOmega;                     // element force w.r.t. the pulley speed
  Eigen::RowVector2d dM_dP, dM_dV;    // pulley moment w.r.t. the element's position, velocity
  double dM_dOmega;                   // pulley moment w.r.t. its own speed
};
void friction_jacobian(const NormalLaw& nl, const NormalJacobian& dn, const FrictionLaw& fl, const Vec2& V, double omega,
                       PairJacobian& J);

// One element–pulley pair of a contact pass. On a tensioner arm's pulley the laws take the
// element's position and velocity relative to the pulley's moving centre (Model::centre).
struct ContactPair {
  int i = 0, j = 0;        // element, pulley
  bool touching = false;   // the element's centre is inside the pulley's contact circle (p > 0)
  double omega = 0;        // the pulley's speed at the evaluation [rad/s]
  double mu = 0;           // touching: the element's μ at the evaluation (Drive::mu_at)
  NormalLaw nl;            // touching: the normal law (its derivatives are the Jacobian's);
                           // otherwise only nl.r and nl.p (<= 0) are set
  FrictionLaw fl;          // touching: the friction law (its force is mu_eff·N, zero when clamped)
};

// The contact pass: the pairs of the span's elements with every pulley, pulley by pulley and in
// element order within a pulley (the order every sum over pairs takes), appended to `out` after
// clearing it. Pairs::touching keeps the pairs in contact only; Pairs::all keeps every pair (the
// switching functions need the distance of those out of contact too).
enum class Pairs { touching, all };
// (the law is chosen once per pass, outside the loop over pairs)
template <class Law>
inline void contact_pass_with(const Model& m, const Drive& d, double t, const double* q, const double* v,
                              const Span& span, ContactList& out, Pairs which, Law&& law) {
  out.clear();
  for (int j = 0; j < m.n_p(); ++j) {
    const Pulley& pl = m.pulleys[j];
    const double omega = d.omega(m, j, t, v);
    // on a tensioner arm the centre moves: the laws see the element relative to it
    const Vec2 centre = m.centre(j, q), vc = m.centre_velocity(j, q, v);
    const double R2 = pl.radius * pl.radius;
    for (int i = span.lo; i < span.hi; ++i) {
      const Vec2 P(q[3 * i], q[3 * i + 1]);
      // most pairs are apart: dismissed by normal_law's own test before a record is built
      if (which == Pairs::touching && (P - centre).squaredNorm() >= R2) continue;
      const Vec2 V = Vec2(v[3 * i], v[3 * i + 1]) - vc;
      ContactPair c;
      c.touching = normal_law(m.contact, P, V, centre, pl.radius, c.nl);
      if (!c.touching) {
        if (which == Pairs::touching) continue;
        c.nl.r = (P - centre).norm();
        c.nl.p = pl.radius - c.nl.r;
      } else {
        c.mu = d.mu_at(i, t);
        c.fl = law(i, c.mu, c.nl, V, omega);
      }
      c.i = i, c.j = j, c.omega = omega;
      out.push_back(c);
    }
  }
}
// z: the bristle deflections (Model::bristles; null but under LuGre's law, and for callers that
// read only the normal laws, which then see LuGre's friction at zero deflection)
inline void contact_pass(const Model& m, const Drive& d, double t, const double* q, const double* v, const double* z,
                         const Span& span, ContactList& out, Pairs which = Pairs::touching) {
  const Friction& f = m.friction;
  if (!m.law_of.empty()) {
    // belt segments with laws of their own: the law is the element's, chosen per pair
    contact_pass_with(m, d, t, q, v, span, out, which,
                      [&m, z](int i, double mu_i, const NormalLaw& nl, const Vec2& V, double omega) {
                        const Friction& fi = m.friction_of(i);
                        switch (fi.law) {
                          case FrictionKind::threlfall: return friction_law(mu_i, fi.dv, nl, V, omega);
                          case FrictionKind::stribeck: return stribeck_law(mu_i, fi, nl, V, omega);
                          default: return lugre_law(mu_i, fi, z ? z[i] : 0.0, nl, V, omega);
                        }
                      });
  } else if (f.law == FrictionKind::threlfall) {
    contact_pass_with(m, d, t, q, v, span, out, which,
                      [dv = f.dv](int, double mu_i, const NormalLaw& nl, const Vec2& V, double omega) {
                        return friction_law(mu_i, dv, nl, V, omega);
                      });
  } else if (f.law == FrictionKind::stribeck) {
    contact_pass_with(m, d, t, q, v, span, out, which,
                      [&f](int, double mu_i, const NormalLaw& nl, const Vec2& V, double omega) {
                        return stribeck_law(mu_i, f, nl, V, omega);
                      });
  } else {
    contact_pass_with(m, d, t, q, v, span, out, which,
                      [&f, z](int i, double mu_i, const NormalLaw& nl, const Vec2& V, double omega) {
                        return lugre_law(mu_i, f, z ? z[i] : 0.0, nl, V, omega);
                      });
  }
}
// the same for a state y = [q | v | e | z]
inline void contact_pass(const Model& m, const Drive& d, double t, const double* y, const Span& span, ContactList& out,
                         Pairs which = Pairs::touching) {
  contact_pass(m, d, t, y, y + m.n_coord(), m.bristles(y), span, out, which);
}

}  // namespace beltsim
