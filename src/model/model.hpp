// Model: the constant description of a belt drive, built once by the scene builder and never
// changed (MuJoCo's mjModel). What a run may change (the pulleys' laws, μ per element) is the
// Drive (drive.hpp); scratch of an evaluation is the Workspace (workspace.hpp). State vectors are
// plain arrays laid out as
//
//   y = [ q (n_coord) | v (n_coord) | e (n_energy) ]
//   q = [ x_0 y_0 phi_0 | ... | x_{n-1} y_{n-1} phi_{n-1} | theta_0 ... theta_{np-1} | psi_0 ... psi_{na-1}
//         | the couplings' rotor angles (each followed by its clutch hub's with a one-way clutch) ]
//   v = the time derivatives of q, in the same order (element velocities [m/s], [rad/s];
//       pulley speeds Omega_j [rad/s]; tensioner arm rates [rad/s]; rotor and hub speeds [rad/s]);
//   e = running integrals of power, present only when energy tracking is on (see EnergyIndex);
//   z = the elements' bristle deflections [m], present only under the LuGre friction law
//       (bristles.cpp): y = [ q | v | e | z ].
//
// The pulleys', the arms' and the couplings' angles are the border of the belt's ring pattern (n_border).
// SI units throughout; counter-clockwise positive (z out of the page), y up. The model has no defaults: a scene's
// come from the parameter table (scene/parameters.hpp) and the builder copies them in.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Core>

namespace beltsim {

using Vec2 = Eigen::Vector2d;

enum class WrapSide { inside, back };  // pulley inside the belt loop, or on the belt's back side

struct Pulley {
  std::string name;
  Vec2 centre{0, 0};         // [m], fixed (on a tensioner arm: where the arm holds it at t = 0)
  double radius = 0;         // [m], contact radius r_p of the pitch line
  double inertia = 0;        // [kg·m²] about its axis
  WrapSide wrap = WrapSide::inside;
  int arm = -1;              // the tensioner arm carrying its centre (Model::arms), -1: none
  int coupling = -1;         // the rotor coupled to it (Model::couplings), -1: none
};

// A spring-loaded tensioner arm (tensioner.cpp): pulley `pulley`'s centre turns about `pivot` at
// the arm's angle psi, c = pivot + length·(cos psi, sin psi). Its law is at the top of tensioner.cpp.
struct Arm {
  int pulley = 0;
  Vec2 pivot{0, 0};              // [m]
  double length = 0;             // [m] pivot to the pulley's centre
  double inertia = 0;            // [kg·m²] about the pivot, the pulley's mass included
  double stiffness = 0;          // k [N·m/rad]
  double free_angle = 0;         // psi_0 [rad]: the spring's moment is -k·(psi - psi_0)
  double damping = 0;            // c [N·m·s/rad]
  double friction_torque = 0;    // T_f [N·m]
  double friction_speed = 0;     // w_f [rad/s]: the friction torque's tanh width
  double asymmetric = 0;         // damping and friction times this while the belt pushes the arm back
  int press = 1;                 // the sense (+1 ccw) in which the spring presses the pulley on the belt
};

// A rotor behind a torsional spring-damper on a pulley (a decoupler), its law at the top of
// coupling.cpp. Two-way, the spring-damper joins the pulley to the rotor; one-way, it joins the
// pulley to the hub of an overrunning clutch that drives the rotor in the sense `sense` only. The
// pulley's applied torque law acts on the rotor.
struct Coupling {
  int pulley = 0;
  double inertia = 0;       // J_r [kg·m²] the rotor's
  double stiffness = 0;     // k [N·m/rad]
  double damping = 0;       // c [N·m·s/rad]
  bool one_way = false;
  int sense = 1;            // one way: the sense (+1 ccw) in which the clutch drives the rotor
  double hub_inertia = 0;   // one way: J_h [kg·m²] of the clutch's hub (with the spring's end)
  double lock_damping = 0;  // one way: c_L [N·m·s/rad] of the engaged clutch
  double drag_torque = 0;   // one way: T_d [N·m] the clutch's drag while it overruns
  int coord = 0;            // its rotor's place among the couplings' coordinates (the hub's is next)
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

// The friction law of every element–pulley pair (contact_law.hpp: friction_law; its formulas at
// the top of friction.cpp, LuGre's at the top of bristles.cpp). Every law scales with the
// element's own μ_i (Drive::mu), which is its kinetic coefficient.
enum class FrictionKind { threlfall, stribeck, lugre };
inline const char* friction_law_name(FrictionKind k) {
  return k == FrictionKind::stribeck ? "stribeck" : k == FrictionKind::lugre ? "lugre" : "threlfall";
}
struct Friction {
  double dv = 0;  // [m/s] slip speed at which mu reaches its kinetic value (the regularising band)
  FrictionKind law = FrictionKind::threlfall;
  // Stribeck's (unused by Threlfall's law)
  double static_ratio = 1;    // μ_s/μ_k: the peak at the band's edge over the kinetic value
  double stribeck_speed = 0;  // v_s [m/s]: the slip speed over which μ falls from μ_s to μ_k
  double exponent = 0;        // δ: the shape of that fall
  double viscous = 0;         // μ_v [s/m]: μ grows by μ_v·v_T
  // LuGre's (with the Stribeck curve above and its viscous term; Δv is then only the speed scale
  // of the integrators' error control)
  double bristle_stiffness = 0;  // σ0 [1/m]: μ = σ0·z + σ1·ż + μ_v·v_T
  double bristle_damping = 0;    // σ1 [s/m]
  double release_time = 0;       // τ [s]: out of contact the deflection relaxes as ż = -z/τ
};

// Running integrals carried in y when Model::track_energy is set; all in joules.
enum EnergyIndex {
  kWorkTorques = 0,  // work of the applied pulley torques (and of kinematic drives)
  kDissSdeAxial,     // dissipated by longitudinal SDE dampers
  kDissSdeBending,   // dissipated by torsional SDE dampers
  kDissContact,      // dissipated by contact damping (and by the N >= 0 clamp)
  kDissFriction,     // dissipated by friction between the belt and the pulleys
  kDissArms,         // dissipated by the tensioner arms' dampers and pivot friction
  kDissCouplings,    // dissipated by the couplings' dampers and one-way clutches
  kEnergyCount
};

// [rad/s] a pulley past this speed stops a run (BeltProblem::check: no drive reaches it, 1 km/s of
// belt on a 1 cm pulley), and a speed law that prescribes more is refused at the build
inline constexpr double kPulleySpeedMax = 1e5;

struct Model {
  std::vector<Pulley> pulleys;
  std::vector<Arm> arms;          // tensioner arms, each carrying one pulley
  std::vector<Coupling> couplings;  // rotors coupled to pulleys, each on one pulley
  Belt belt;
  Contact contact;
  Friction friction;               // the scene's law, every element's but those of a segment below
  // friction laws of belt segments (friction.segments): element i takes laws[law_of[i] - 1], or
  // `friction` where law_of[i] is 0; law_of is empty when the whole belt takes `friction`
  std::vector<Friction> laws;
  std::vector<unsigned char> law_of;
  double gravity = 0;             // [m/s²], acts along -y; 0 switches it off
  bool track_energy = false;

  int n_el() const { return belt.n; }
  int n_p() const { return static_cast<int>(pulleys.size()); }
  int n_arm() const { return static_cast<int>(arms.size()); }
  int n_coupling() const { return static_cast<int>(couplings.size()); }
  // the couplings' coordinates: a rotor each, a hub more with a one-way clutch
  int n_coupled() const {
    return couplings.empty() ? 0 : couplings.back().coord + (couplings.back().one_way ? 2 : 1);
  }
  int n_border() const { return n_p() + n_arm() + n_coupled(); }  // the coordinates beside the elements
  int n_coord() const { return 3 * belt.n + n_border(); }
  int n_energy() const { return track_energy ? kEnergyCount : 0; }
  const Friction& friction_of(int i) const {
    return law_of.empty() || law_of[i] == 0 ? friction : laws[law_of[i] - 1];
  }
  // some element's law is `kind`; every element's law is `kind`
  bool any_law(FrictionKind kind) const {
    if (friction.law == kind) return true;
    for (const Friction& f : laws)
      if (f.law == kind) return true;
    return false;
  }
  bool every_law(FrictionKind kind) const {
    if (law_of.empty()) return friction.law == kind;
    for (int i = 0; i < belt.n; ++i)
      if (friction_of(i).law != kind) return false;
    return true;
  }
  int n_bristle() const { return any_law(FrictionKind::lugre) ? belt.n : 0; }
  int bristle_offset() const { return 2 * n_coord() + n_energy(); }  // z_0's index in y
  int n_state() const { return 2 * n_coord() + n_energy() + n_bristle(); }
  // the bristle deflections in a state y (null when the law has none)
  const double* bristles(const double* y) const { return n_bristle() ? y + bristle_offset() : nullptr; }
  int pulley_coord(int j) const { return 3 * belt.n + j; }
  int arm_coord(int a) const { return 3 * belt.n + n_p() + a; }
  int rotor_coord(int c) const { return 3 * belt.n + n_p() + n_arm() + couplings[c].coord; }
  int hub_coord(int c) const { return rotor_coord(c) + 1; }  // one-way couplings only
  // pulley j's centre in the positions q, and its velocity (zero but on an arm)
  Vec2 centre(int j, const double* q) const {
    const Pulley& p = pulleys[j];
    if (p.arm < 0) return p.centre;
    const Arm& a = arms[p.arm];
    const double psi = q[arm_coord(p.arm)];
    return a.pivot + a.length * Vec2(std::cos(psi), std::sin(psi));
  }
  Vec2 centre_velocity(int j, const double* q, const double* v) const {
    const Pulley& p = pulleys[j];
    if (p.arm < 0) return Vec2::Zero();
    const Arm& a = arms[p.arm];
    const double psi = q[arm_coord(p.arm)];
    return a.length * v[arm_coord(p.arm)] * Vec2(-std::sin(psi), std::cos(psi));
  }
  // the mass or inertia of coordinate k: an element's mass [kg] or rotational inertia [kg·m²], a
  // pulley's, an arm's, a rotor's or a clutch hub's inertia (a kinematic pulley's row has unit mass
  // instead: Drive::mass)
  double mass_of(int k) const {
    if (k < 3 * belt.n) return (k % 3 == 2) ? belt.rot_inertia : belt.mass;
    if (k < 3 * belt.n + n_p()) return pulleys[k - 3 * belt.n].inertia;
    if (k < 3 * belt.n + n_p() + n_arm()) return arms[k - 3 * belt.n - n_p()].inertia;
    const int r = k - 3 * belt.n - n_p() - n_arm();
    for (const Coupling& c : couplings)
      if (r == c.coord) return c.inertia;
      else if (r == c.coord + 1 && c.one_way) return c.hub_inertia;
    return 0;
  }
};

}  // namespace beltsim
