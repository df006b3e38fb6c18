// Coupled pulleys: a rotor behind a torsional spring-damper (a decoupler), optionally through an
// overrunning (one-way) clutch.
//
// Coupling c on pulley j (angle θ_p, speed ω_p; a kinematic pulley's ω_p is its prescribed speed)
// carries a rotor (θ_r, ω_r, inertia J_r), coordinates of the state (Model::rotor_coord). The
// pulley's applied torque law M(t, ω_r) acts on the rotor (an alternator's load is on its rotor).
//
// Two-way: the spring-damper joins the pulley to the rotor,
//   T = k·(θ_p - θ_r) + c·(ω_p - ω_r)                 on the rotor, -T on the pulley
//   J_r·ω̇_r = T + M(t, ω_r)
//   ∂T/∂θ_p = k, ∂T/∂θ_r = -k, ∂T/∂ω_p = c, ∂T/∂ω_r = -c.
//
// One-way (an overrunning alternator decoupler: the spring in series with a one-way clutch): the
// spring-damper joins the pulley to the clutch's hub (θ_h, ω_h, inertia J_h, Model::hub_coord),
// and the clutch drives the rotor from the hub in the sense s (±1) only:
//   T_s = k·(θ_p - θ_h) + c·(ω_p - ω_h)               on the hub, -T_s on the pulley
//   x   = s·(ω_h - ω_r)                               the hub overtaking the rotor
//   T_c = s·c_L·σ(x),  σ(x) = (x - w + √(x² + w²))/2, w = 2·T_d/c_L
//                                                     on the rotor, -T_c on the hub
//   J_h·ω̇_h = T_s - T_c,   J_r·ω̇_r = T_c + M(t, ω_r)
// σ is smooth (C∞): σ(0) = 0, σ → x - w/2 for x ≫ w (engaged: a stiff viscous lock, the clutch
// slips x ≈ |T_c|/c_L), σ → -w/2 for x ≪ -w (overrunning: the drag torque T_d against the rotor).
// σ'(x) = (1 + x/√(x² + w²))/2 ∈ (0, 1), so
//   ∂T_c/∂ω_h = c_L·σ'(x),  ∂T_c/∂ω_r = -c_L·σ'(x).
// The rotor's angle enters nothing here: after overrunning the clutch engages again as soon as the
// hub catches the rotor's speed, whatever the angle between them.
//
// Potential k·(θ_p - θ_r)²/2 (two-way) or k·(θ_p - θ_h)²/2 (one-way); dissipated power c·δ̇² and
// c_L·σ(x)·x ≥ 0 (EnergyIndex's kDissCouplings). On a kinematic pulley ∂/∂ω_p goes to ∂f/∂t through
// ω_p'(t) and the drive supplies the power T·ω_p.
#include "model/forces.hpp"

namespace beltsim {

namespace {
struct ClutchLaw {
  double T = 0, dT_dx = 0;  // c_L·σ(x) and c_L·σ'(x)
};
ClutchLaw clutch_law(const Coupling& c, double x) {
  const double w = 2 * c.drag_torque / c.lock_damping;
  const double r = std::sqrt(x * x + w * w);
  return {0.5 * c.lock_damping * (x - w + r), 0.5 * c.lock_damping * (1 + x / r)};
}
}  // namespace

CouplingState coupling_state(const Model& m, const Drive& d, double t, const double* q, const double* v, int c) {
  const Coupling& cp = m.couplings[c];
  CouplingState s;
  const int j = cp.pulley, kr = m.rotor_coord(c);
  const double theta_p = q[m.pulley_coord(j)], omega_p = d.omega(m, j, t, v);
  s.rotor_angle = q[kr], s.rotor_speed = v[kr];
  const double theta_e = cp.one_way ? q[kr + 1] : q[kr], omega_e = cp.one_way ? v[kr + 1] : v[kr];
  s.windup = theta_p - theta_e;
  s.spring = cp.stiffness * s.windup + cp.damping * (omega_p - omega_e);
  s.transmitted = cp.one_way ? cp.sense * clutch_law(cp, cp.sense * (v[kr + 1] - v[kr])).T : s.spring;
  return s;
}

void coupling_forces(const Model& m, const Drive& d, double t, const double* q, const double* v, double* f,
                     double* e_rate) {
  for (int c = 0; c < m.n_coupling(); ++c) {
    const Coupling& cp = m.couplings[c];
    const int j = cp.pulley, kp = m.pulley_coord(j), kr = m.rotor_coord(c), ke = cp.one_way ? kr + 1 : kr;
    const double omega_p = d.omega(m, j, t, v);
    const double rel = omega_p - v[ke];
    const double Ts = cp.stiffness * (q[kp] - q[ke]) + cp.damping * rel;
    f[ke] += Ts;
    if (d.kinematic(j)) {
      if (e_rate) e_rate[kWorkTorques] += Ts * omega_p;  // the drive holds the speed against the spring
    } else {
      f[kp] -= Ts;
    }
    if (e_rate) e_rate[kDissCouplings] += cp.damping * rel * rel;
    if (!cp.one_way) continue;
    const double x = cp.sense * (v[ke] - v[kr]);
    const double Tc = cp.sense * clutch_law(cp, x).T;
    f[kr] += Tc;
    f[ke] -= Tc;
    if (e_rate) e_rate[kDissCouplings] += Tc * cp.sense * x;
  }
}

void coupling_jacobian(const Model& m, const Drive& d, double t, const double* v, BlockMatrix& K, BlockMatrix& C,
                       double* f_t) {
  const int ne = 3 * m.n_el();
  for (int c = 0; c < m.n_coupling(); ++c) {
    const Coupling& cp = m.couplings[c];
    const int j = cp.pulley, r = m.rotor_coord(c) - ne, e = cp.one_way ? r + 1 : r;
    const bool kinematic = d.kinematic(j);
    // the spring-damper between the pulley (border j) and e (the rotor, or the clutch's hub)
    K.pulley_pulley(e, j) += cp.stiffness;
    K.pulley_pulley(e, e) -= cp.stiffness;
    C.pulley_pulley(e, e) -= cp.damping;
    if (kinematic) {
      if (f_t) f_t[ne + e] += cp.damping * d.speed_rate(j, t);
    } else {
      C.pulley_pulley(e, j) += cp.damping;
      K.pulley_pulley(j, j) -= cp.stiffness;
      K.pulley_pulley(j, e) += cp.stiffness;
      C.pulley_pulley(j, j) -= cp.damping;
      C.pulley_pulley(j, e) += cp.damping;
    }
    if (!cp.one_way) continue;
    const double g = clutch_law(cp, cp.sense * (v[ne + e] - v[ne + r])).dT_dx;
    C.pulley_pulley(r, e) += g;
    C.pulley_pulley(r, r) -= g;
    C.pulley_pulley(e, e) -= g;
    C.pulley_pulley(e, r) += g;
  }
}

double coupling_potential(const Model& m, const double* q) {
  double u = 0;
  for (int c = 0; c < m.n_coupling(); ++c) {
    const Coupling& cp = m.couplings[c];
    const int kr = m.rotor_coord(c);
    const double dth = q[m.pulley_coord(cp.pulley)] - q[cp.one_way ? kr + 1 : kr];
    u += 0.5 * cp.stiffness * dth * dth;
  }
  return u;
}

}  // namespace beltsim
