// Model: the constant description of a belt drive, built once by the scene builder and never
// changed (MuJoCo's mjModel). What a run may change (the pulleys' laws, μ per element) is the
// Drive (drive.hpp); scratch of an evaluation is the Workspace (workspace.hpp). State vectors are
// plain arrays laid out as
//
//   y = [ q (n_coord) | v (n_coord) | e (n_energy) ]
//   q = [ x_0 y_0 phi_0 | x_1 y_1 phi_1 | ... | x_{n-1} y_{n-1} phi_{n-1} | theta_0 ... theta_{np-1} ]
//   v = the time derivatives of q, in the same order (element velocities [m/s], [rad/s];
//       pulley speeds Omega_j [rad/s]);
//   e = running integrals of power, present only when energy tracking is on (see EnergyIndex).
//
// SI units throughout; counter-clockwise positive (z out of the page), y up. The model has no defaults: a scene's
// come from the parameter table (scene/parameters.hpp) and the builder copies them in.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace beltsim {

using Vec2 = Eigen::Vector2d;

enum class WrapSide { inside, back };  // pulley inside the belt loop, or on the belt's back side

struct Pulley {
  std::string name;
  Vec2 centre{0, 0};         // [m], fixed
  double radius = 0;         // [m], contact radius r_p of the pitch line
  double inertia = 0;        // [kg·m²] about its axis
  WrapSide wrap = WrapSide::inside;
};

// Per-SDE belt properties (converted from rigidities by the scene build, scene/scene.cpp).
struct Belt {
  int n = 0;                 // number of elements
  double pitch = 0;          // l: centre-to-centre spacing along the route at rest [m]
  double rigid_length = 0;   // l0: an element's rest length, its rigid rod [m]
  double mass = 0;           // m = rho·l0 [kg]
  double rot_inertia = 0;    // I_z = m·l0²/12 [kg·m²]
  double k = 0;              // longitudinal SDE stiffness [N/m^e_tra]
  double c = 0;              // longitudinal SDE damping [N·s/m]
  double kt = 0;             // torsional SDE stiffness [N·m/rad^e_tor]
  double ct = 0;             // torsional SDE damping [N·m·s/rad]
  double e_tra = 1;          // exponent of the longitudinal spring (>= 1)
  double e_tor = 1;          // exponent of the torsional spring (>= 1)
};

struct Contact {
  double c1 = 0;     // [N/m²]
  double c2 = 0;     // [N/m]
  double b = 0;      // [N·s/m]
  double p_max = 0;  // [m] depth of full damping
};

struct Friction {
  double dv = 0;  // [m/s] slip speed at which mu reaches its kinetic value
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
  double gravity = 0;             // [m/s²], acts along -y; 0 switches it off
  bool track_energy = false;

  int n_el() const { return belt.n; }
  int n_p() const { return static_cast<int>(pulleys.size()); }
  int n_coord() const { return 3 * belt.n + n_p(); }
  int n_energy() const { return track_energy ? kEnergyCount : 0; }
  int n_state() const { return 2 * n_coord() + n_energy(); }
  int pulley_coord(int j) const { return 3 * belt.n + j; }
  // the mass or inertia of coordinate k: an element's mass [kg] or rotational inertia [kg·m²], a
  // pulley's inertia (a kinematic pulley's row has unit mass instead: Drive::mass)
  double mass_of(int k) const {
    if (k < 3 * belt.n) return (k % 3 == 2) ? belt.rot_inertia : belt.mass;
    return pulleys[k - 3 * belt.n].inertia;
  }
};

}  // namespace beltsim
