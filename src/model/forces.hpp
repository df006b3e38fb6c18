// The force laws, one file each (sde.cpp, bending.cpp, contact.cpp, friction.cpp, pulley.cpp,
// tensioner.cpp, coupling.cpp).
// Each adds its generalized forces to f (length n_coord) and, when e_rate is not null, its power
// to the running energy integrals (EnergyIndex). The *_jacobian functions add ∂f/∂q to K and
// ∂f/∂v to C; every law's derivation is at the top of its file.
#pragma once

#include <cmath>
#include <limits>
#include <vector>

#include "model/block_matrix.hpp"
#include "model/drive.hpp"
#include "model/model.hpp"

namespace beltsim {

// The axis (cos φ, sin φ) of an element at angle φ, taken from the cosine and sine of the nearest
// multiple of 1/128 rad, φ_g, turned by δ = φ - φ_g (exact; |δ| <= 1/256) with Taylor's series of
// cos δ to δ⁴ and of sin δ to δ⁵, whose remainders (δ⁶/720 < 5e-18, δ⁷/5040 < 1e-20·δ) are far
// below a unit of rounding: a function of φ alone, within 2.2e-16 of cos φ and sin φ
// (Jacobian.AxisIsCosineAndSine). An element turns by less than 1/128 rad over most steps, so its
// anchor's cosine and sine (AxisMemo) serve many evaluations in a row: on the serpentine drive at
// speed the sines and cosines took a fifth of the instructions they took computed afresh.
// (each multiply-add written as one fused operation where the machine has it, __FMA__: the
// compiler's own fusing, which may differ between a loop it vectorises and one it does not, then
// finds nothing to fuse, and AxisMemo::update's loop gives axis()'s bits)
// turn_off_anchor: δ != 0 (at δ = 0 the sign of a zero sine may differ); turn: any δ
inline void turn_off_anchor(double c0, double s0, double d, double& c, double& s) {
  const double d2 = d * d;
#ifdef __FMA__
  const double cd = std::fma(-d2, std::fma(-d2, 1.0 / 24, 0.5), 1.0);
  const double sd = d * std::fma(-d2, std::fma(-d2, 1.0 / 120, 1.0 / 6), 1.0);
  const double ck = std::fma(c0, cd, -(s0 * sd)), sk = std::fma(s0, cd, c0 * sd);
#else
  const double cd = 1 - d2 * (0.5 - d2 * (1.0 / 24)), sd = d * (1 - d2 * (1.0 / 6 - d2 * (1.0 / 120)));
  const double ck = c0 * cd - s0 * sd, sk = s0 * cd + c0 * sd;
#endif
  c = ck, s = sk;
}
inline void turn(double c0, double s0, double d, double& c, double& s) {
  turn_off_anchor(c0, s0, d, c, s);
  if (d == 0) c = c0, s = s0;  // on the anchor: its cosine and sine (sin(-0.0) = -0.0 among them)
}
inline double axis_anchor(double phi) {
  return std::nearbyint(phi * 128) * (1.0 / 128);
}
inline Vec2 axis(double phi) {
  const double g = axis_anchor(phi);
  Vec2 e;
  turn(std::cos(g), std::sin(g), phi - g, e.x(), e.y());
  return e;
}
inline Vec2 perp(const Vec2& a) { return {-a.y(), a.x()}; }
inline double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
// angle difference in (-pi, pi]: phi grows by 2·pi per lap, the SDE sees only the bend
double wrap_angle(double a);

// The elements' axes e(φ_i) of the last evaluation and each element's anchor φ_g (axis, above)
// with its cosine and sine. sde_forces and sde_jacobian bring their span's axes up to date first
// (update: a new sine and cosine only for an angle that left its anchor's cell, which most do not
// between one evaluation and the next), then read them; the axes are axis()'s bits.
struct AxisMemo {
  std::vector<double> phi, c, s;  // per element: the angle, cos φ, sin φ
  std::vector<double> g, cg, sg;  // per element: the anchor φ_g, cos φ_g, sin φ_g
  // sizes it for n elements (a fresh one holds NaN, whose axis is NaN too); called before the
  // laws run, never by two threads at once
  void fit(int n) {
    if (phi.size() == static_cast<size_t>(n)) return;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    phi.assign(n, nan), c.assign(n, nan), s.assign(n, nan);
    g.assign(n, nan), cg.assign(n, nan), sg.assign(n, nan);
  }
  // the axes of elements lo..hi-1 at the angles of q, axis() bit for bit: a new anchor's cosine
  // and sine where an angle left its cell, then every axis turned from its anchor in one loop
  // without branches, which the compiler vectorises (sde.cpp); nothing when the angles are those
  // of the last update
  void update(const double* q, int lo, int hi);
};

// The elements lo..hi-1 one call of a law evaluates for (rhs.cpp splits a long belt in two
// halves that run at once): it writes the rows of those elements only, evaluating the SDE and
// bending pairs on the span's edges for them, and adds what it sums over elements (the pulleys'
// moments and ∂M/∂Ω, the energy rates) to the accumulators it is given. Each element receives its
// terms in the order the whole loop gives them (pair k as its end b, then pair k+1 as its end a),
// so its force rows are the same to the bit either way; the sums over elements are added up per
// half, which changes them in their last bits.
struct Span {
  int lo = 0, hi = 0;
  bool owns(int k) const { return k >= lo && k < hi; }
  bool whole(int n) const { return lo == 0 && hi == n; }
};
// the span of the whole belt, known at compile time: its ownership checks fold away, so a law's
// loop over the whole belt compiles to a plain loop
struct WholeBelt {
  static constexpr bool owns(int) { return true; }
};
// calls visit(i, own) for each pair (i-1, i) touching an element of the span, in the whole loop's
// order; own is WholeBelt{} for the whole belt, else the span
template <class Visit>
[[gnu::noinline]] void for_pairs_of_span(int n, const Span& s, Visit& visit) {
  if (s.hi == n && s.lo > 0) visit(0, s);  // its end a is element n-1, first in the whole loop
  for (int i = s.lo; i < s.hi; ++i) visit(i, s);
  if (s.hi < n) visit(s.hi, s);  // its end a is element hi-1
}
template <class Visit>
void for_pairs(int n, const Span& s, Visit&& visit) {
  if (!s.whole(n)) return for_pairs_of_span(n, s, visit);  // out of line: the whole loop stays lean
  for (int i = 0; i < n; ++i) visit(i, WholeBelt{});
}

// longitudinal SDE (paper eq. 5), sde.cpp; `memo` (may be null) keeps the axes between calls
// (with a memo, only the span's own elements are read from it and written to it)
void sde_forces(const Model& m, const double* q, const double* v, double* f, double* e_rate, AxisMemo* memo,
                const Span& span);
void sde_jacobian(const Model& m, const double* q, const double* v, BlockMatrix& K, BlockMatrix& C, AxisMemo* memo,
                  const Span& span);
double sde_potential(const Model& m, const double* q);
// signed axial force of SDE i (joining element i-1 to element i), positive in tension [N]
double sde_axial_force(const Model& m, const double* q, const double* v, int i);
// the same for every SDE at once (out[i] for SDE i, n values), each element's axis taken once
void sde_axial_forces(const Model& m, const double* q, const double* v, double* out);
// gap vector d of SDE i (end A of element i minus end B of element i-1) [m]
Vec2 sde_gap(const Model& m, const double* q, int i);
// the SDE whose middle (between the centres of its two elements) is nearest a point; the first
// such SDE in index order when two are as near
int sde_nearest(const Model& m, const double* q, const Vec2& point);
// the same for `count` points in one pass over the SDEs: out[k] for points[k]
void sde_nearest(const Model& m, const double* q, const Vec2* points, int count, int* out);

// torsional SDE (paper eq. 6), bending.cpp
void bending_forces(const Model& m, const double* q, const double* v, double* f, double* e_rate, const Span& span);
void bending_jacobian(const Model& m, const double* q, const double* v, BlockMatrix& K, BlockMatrix& C,
                      const Span& span);
double bending_potential(const Model& m, const double* q);

// belt–pulley contact (eq. 2) with friction (eqs. 3–4), contact.cpp + friction.cpp, from the pairs
// of one contact pass (contact_law.hpp: contact_pass, ContactPair)
struct ContactPair;
using ContactList = std::vector<ContactPair>;
// adds the pairs' forces to the elements' rows of f and their moments to f_pulley[j] (f + 3n for
// the whole belt; the moments of a kinematic pulley go to the energy of its drive instead), and
// the moments of their reactions about a tensioner arm's pivot to f_pulley[np + arm]
void contact_forces(const Model& m, const Drive& d, const double* q, const ContactList& pairs, double* f,
                    double* f_pulley, double* e_rate);
// f_t (may be null) receives ∂f/∂t through the prescribed speeds of kinematic pulleys;
// dM_dOmega[j] receives the sum over the pairs of pulley j's ∂M/∂Ω (null: added to C.pulley_pulley)
void contact_jacobian(const Model& m, const Drive& d, double t, const double* q, const double* v,
                      const ContactList& pairs, BlockMatrix& K, BlockMatrix& C, double* f_t, double* dM_dOmega);
double contact_potential(const Model& m, const double* q);

// tensioner arms, tensioner.cpp: the spring, damper and friction on each arm; the lever ∂c/∂psi
// of the arm's pulley centre; the terms a contact pair on the arm's pulley adds to the Jacobian
// through the moving centre (F, dF_dP, dF_dV: the pair's force on its element and its derivatives
// w.r.t. the element's relative position and velocity, J: its friction Jacobian)
struct PairJacobian;
inline Vec2 arm_lever(const Model& m, int a, const double* q) {
  const double psi = q[m.arm_coord(a)];
  return m.arms[a].length * Vec2(-std::sin(psi), std::cos(psi));
}
void arm_forces(const Model& m, const double* q, const double* v, double* f, double* e_rate);
void arm_jacobian(const Model& m, const double* q, const double* v, BlockMatrix& K, BlockMatrix& C);
void arm_pair_jacobian(const Model& m, int a, const double* q, const double* v, const Vec2& F,
                       const Eigen::Matrix2d& dF_dP, const Eigen::Matrix2d& dF_dV, const PairJacobian& J, int i,
                       BlockMatrix& K, BlockMatrix& C);
double arm_potential(const Model& m, const double* q);

// coupled rotors, coupling.cpp: the spring-damper (and one-way clutch) between each coupled pulley
// and its rotor; f_t (may be null) receives ∂f/∂t through a kinematic pulley's prescribed speed
void coupling_forces(const Model& m, const Drive& d, double t, const double* q, const double* v, double* f,
                     double* e_rate);
void coupling_jacobian(const Model& m, const Drive& d, double t, const double* v, BlockMatrix& K, BlockMatrix& C,
                       double* f_t);
double coupling_potential(const Model& m, const double* q);
// coupling c at (t, q, v): what the outputs give
struct CouplingState {
  double rotor_angle = 0;  // [rad]
  double rotor_speed = 0;  // [rad/s]
  double windup = 0;       // [rad] the spring's twist, pulley minus rotor (one-way: minus the clutch's hub)
  double spring = 0;       // [N·m] the spring-damper's torque on the rotor (one-way: on the hub)
  double transmitted = 0;  // [N·m] the torque the coupling puts on the rotor (one-way: the clutch's)
};
CouplingState coupling_state(const Model& m, const Drive& d, double t, const double* q, const double* v, int c);

// pulley equations (eq. 8): applied torques (on a coupled pulley's rotor) and gravity on the
// elements, pulley.cpp
void pulley_forces(const Model& m, const Drive& d, double t, const double* v, double* f, double* e_rate);
void pulley_jacobian(const Model& m, const Drive& d, double t, const double* v, BlockMatrix& C, double* f_t);
double applied_torque(const Model& m, const Drive& d, double t, const double* v, int j);
void gravity_forces(const Model& m, double* f);
double gravity_potential(const Model& m, const double* q);

}  // namespace beltsim
