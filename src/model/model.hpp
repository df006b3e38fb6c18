// Model: the static description of a belt drive, built once by the scene builder and never
// changed while integrating (MuJoCo's mjModel). State vectors are plain arrays laid out as
//
//   y = [ q (n_coord) | v (n_coord) | e (n_energy) ]
//   q = [ x_0 y_0 phi_0 | x_1 y_1 phi_1 | ... | x_{n-1} y_{n-1} phi_{n-1} | theta_0 ... theta_{np-1} ]
//   v = the time derivatives of q, in the same order (element velocities [m/s], [rad/s];
//       pulley speeds Omega_j [rad/s]);
//   e = running integrals of power, present only when energy tracking is on (see EnergyIndex).
//
// SI units throughout; counter-clockwise positive (z out of the page), y up.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "model/laws.hpp"

namespace beltsim {

using Vec2 = Eigen::Vector2d;

enum class WrapSide { inside, back };  // pulley inside the belt loop, or on the belt's back side

struct Pulley {
  std::string name;
  Vec2 centre{0, 0};         // [m], fixed
  double radius = 0.1;       // [m], contact radius r_p of the pitch line
  double inertia = 0.025;    // [kg·m²] about its axis
  WrapSide wrap = WrapSide::inside;
  bool kinematic = false;    // true: Omega(t) = speed.eval(t, 0) is prescribed
  TimeSpeedLaw torque;       // applied torque M_d(t, Omega) for a free pulley
  TimeSpeedLaw speed;        // prescribed speed for a kinematic pulley
};

// Per-SDE belt properties (already converted from rigidities, see scene/validate).
struct Belt {
  int n = 0;                 // number of elements
  double pitch = 0;          // l: centre-to-centre spacing along the route at rest [m]
  double rigid_length = 0;   // l_e: length of an element's rigid rod [m]
  double mass = 0;           // m = rho·l [kg]
  double rot_inertia = 0;    // I_z = m·l_e²/12 [kg·m²]
  double k = 0;              // longitudinal SDE stiffness [N/m^e_tra]
  double c = 0;              // longitudinal SDE damping [N·s/m]
  double kt = 0;             // torsional SDE stiffness [N·m/rad^e_tor]
  double ct = 0;             // torsional SDE damping [N·m·s/rad]
  double e_tra = 1;          // exponent of the longitudinal spring (>= 1)
  double e_tor = 1;          // exponent of the torsional spring (>= 1)
};

struct Contact {
  double c1 = 3.0256e9;  // [N/m²]
  double c2 = 6.5e5;     // [N/m]
  double b = 300;        // [N·s/m]
  double p_max = 1e-3;   // [m] depth of full damping
};

struct Friction {
  double dv = 1e-5;      // [m/s] slip speed at which mu reaches its kinetic value
};

// Running integrals carried in y when Model::track_energy is set; all in joules.
enum EnergyIndex {
  kWorkTorques = 0,   // work of the applied pulley torques (and of kinematic drives)
  kDissSdeAxial,      // dissipated by longitudinal SDE dampers
  kDissSdeBending,    // dissipated by torsional SDE dampers
  kDissContact,       // dissipated by contact damping (and by the N >= 0 clamp)
  kDissFriction,      // dissipated by friction
  kEnergyCount
};

struct Model {
  std::vector<Pulley> pulleys;
  Belt belt;
  Contact contact;
  Friction friction;
  double gravity = 9.81;          // [m/s²], acts along -y; 0 switches it off
  std::vector<double> mu;         // friction coefficient of each element, size belt.n
  bool track_energy = false;

  int n_el() const { return belt.n; }
  int n_p() const { return static_cast<int>(pulleys.size()); }
  int n_coord() const { return 3 * belt.n + n_p(); }
  int n_energy() const { return track_energy ? kEnergyCount : 0; }
  int n_state() const { return 2 * n_coord() + n_energy(); }
  int pulley_coord(int j) const { return 3 * belt.n + j; }
  int energy_offset() const { return 2 * n_coord(); }
  // diagonal of the mass matrix for coordinate k (kinematic pulleys get 1: their rows are
  // prescribed, see rhs.cpp)
  // (inline: the solvers call it per coordinate, 1.8 % of the dry second's instructions out of line)
  double mass_of(int k) const {
    if (k < 3 * belt.n) return (k % 3 == 2) ? belt.rot_inertia : belt.mass;
    const Pulley& p = pulleys[k - 3 * belt.n];
    return p.kinematic ? 1.0 : p.inertia;
  }
  // The time of the integrator's last (re)start: a step of a law at exactly this time has
  // happened (its value after the jump is used), while a step that ends exactly on a law's jump
  // still sees the value before it. Set by the simulation at every restart; not part of the
  // model's description (checkpoints restart at their time).
  double restart_time = -1e300;
  bool after_jump(double t) const { return t == restart_time; }
  // Omega of pulley j: the prescribed speed for a kinematic pulley, else the state value
  double omega(int j, double t, const double* v) const {
    const Pulley& p = pulleys[j];
    return p.kinematic ? p.speed.eval(t, 0.0, after_jump(t)) : v[pulley_coord(j)];
  }
  // dOmega/dt of a kinematic pulley j (its prescribed acceleration) [rad/s²]
  double speed_rate(int j, double t) const { return pulleys[j].speed.d_time(t, 0.0); }
  // times at which some law of the model has a kink (table breakpoints, ramp ends)
  std::vector<double> breakpoints() const;
  // times at which some law of the model jumps (steps)
  std::vector<double> jumps() const;
};

}  // namespace beltsim
