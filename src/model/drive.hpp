// Drive: what a run may change while it integrates (MuJoCo keeps its controls in mjData, apart from
// the constant mjModel). The scene builds the initial drive (Scene::drive); a simulation holds its
// own copy and changes it at a pause or an event (a torque step, wetting a stretch of the belt),
// restarting the integrator there. The Model stays constant.
//
//   pulleys[j]    how pulley j is driven: a free pulley under an applied torque M(t, Ω), or a
//                 kinematic one whose speed Ω(t) is prescribed
//   mu[i]         the friction coefficient of element i (it travels with the belt)
//   spray         spray zones and what they have wetted (spray.hpp): μ of element i at t is
//                 mu_at(i, t), its own mu[i] unless a zone wets it or it is drying
//   restart_time  the time of the integrator's last (re)start: a law's step at exactly this time
//                 has happened (its value after the jump is used), while a step that ends exactly
//                 on a law's jump still sees the value before it
#pragma once

#include <vector>

#include "model/laws.hpp"
#include "model/model.hpp"
#include "model/spray.hpp"

namespace beltsim {

struct PulleyDrive {
  bool kinematic = false;  // true: Omega(t) = speed.eval(t, 0) is prescribed
  TimeSpeedLaw torque;     // applied torque M_d(t, Omega) of a free pulley [N·m]
  TimeSpeedLaw speed;      // prescribed speed of a kinematic pulley [rad/s]
};

struct Drive {
  std::vector<PulleyDrive> pulleys;  // one per pulley, in the model's order
  std::vector<double> mu;            // friction coefficient of each element, size belt.n
  Spray spray;                       // spray zones and the elements' wetting (none: no cost)
  double restart_time = -1e300;      // [s]

  // the friction coefficient of element i at t
  double mu_at(int i, double t) const { return spray.n_wet == 0 ? mu[i] : spray.mu(i, mu[i], t); }
  bool after_jump(double t) const { return t == restart_time; }
  bool kinematic(int j) const { return pulleys[j].kinematic; }
  // Omega of pulley j: the prescribed speed for a kinematic pulley, else the state value
  double omega(const Model& m, int j, double t, const double* v) const {
    const PulleyDrive& p = pulleys[j];
    return p.kinematic ? p.speed.eval(t, 0.0, after_jump(t)) : v[m.pulley_coord(j)];
  }
  // dOmega/dt of a kinematic pulley j (its prescribed acceleration) [rad/s²]
  double speed_rate(int j, double t) const { return pulleys[j].speed.d_time(t, 0.0); }
  // the diagonal of the mass matrix for coordinate k: the model's mass or inertia; 1 for a
  // kinematic pulley, whose row is its prescribed acceleration (rhs.cpp)
  // (inline: the solvers call it per coordinate, 1.8 % of the dry second's instructions out of line)
  double mass(const Model& m, int k) const {
    const int j = k - 3 * m.belt.n;
    if (j < 0 || j >= m.n_p()) return m.mass_of(k);
    return pulleys[j].kinematic ? 1.0 : m.mass_of(k);
  }
  // times at which some law has a kink (table breakpoints, ramp ends)
  std::vector<double> breakpoints() const;
  // times at which some law jumps (steps)
  std::vector<double> jumps() const;
};

}  // namespace beltsim
