// What users observe of a state: per element, per pulley and per span, in SI units with one sign
// convention. The time-series CSV, the frames and the live simulation (Lua `sim:element`,
// `sim:pulley`, the console) all read these functions, so they show the same numbers.
//
// Signs: counter-clockwise positive for angles, speeds and torques (the model's convention).
// Contact quantities of an element are taken along the belt's direction of travel on the pulley
// it rides: friction > 0 pulls the belt forward, slip > 0 means the belt moves faster than the
// pulley's rim. An element rides the pulley it penetrates deepest.
//
// Contact state: "free" off the pulleys (or with N = 0); "slip" when |slip| > Δv, i.e. outside
// the friction band of the simplified Threlfall law, where the friction is saturated at μN and
// the element slides; "stick" inside the band (micro-slip |v_T| <= Δv, friction below μN).
#pragma once

#include <vector>

#include "model/model.hpp"

namespace beltsim {

enum class ContactState { free, stick, slip };
const char* contact_state_name(ContactState s);  // "free", "stick", "slip"

struct ElementObs {
  double x = 0, y = 0, phi = 0;  // [m], [m], [rad] centre and axis angle
  double tension = 0;            // [N] mean axial force of its two SDEs (tension positive)
  double sde_force = 0;          // [N] axial force of its own SDE (joining it to its predecessor)
  double normal = 0;             // [N] normal force of the pulleys on it
  double friction = 0;           // [N] friction force along the travel (NaN when free)
  double slip = 0;               // [m/s] belt speed minus rim speed along the travel (NaN when free)
  double mu = 0;                 // friction coefficient of the element now
  int pulley = -1;               // the pulley it rides, -1 when free
  ContactState state = ContactState::free;
};

struct PulleyObs {
  double omega = 0;        // [rad/s]
  double angle = 0;        // [rad] turned since t = 0
  double torque = 0;       // [N·m] applied (for a kinematic pulley: what the drive supplies)
  double belt_torque = 0;  // [N·m] moment of the belt's friction on it
  double hub_load = 0;     // [N] magnitude of the belt's resultant force on it
  Vec2 hub{0, 0};          // [N] that force as a vector
};

// sense[j]: +1 when the belt goes round pulley j anticlockwise, -1 clockwise (Scene::senses())
ElementObs observe_element(const Model& m, const std::vector<int>& sense, double t, const double* y, int i);
PulleyObs observe_pulley(const Model& m, double t, const double* y, int j);

// Everything observed of one state: each element and each pulley.
struct Observation {
  double t = 0;
  std::vector<ElementObs> elements;
  std::vector<PulleyObs> pulleys;
};
void observe(const Model& m, const std::vector<int>& sense, double t, const double* y, Observation& out);

// The contact quantities of a state inside an integrator's step, from the step's two ends.
//
// Why: an element that sticks has its tangential velocity within Δv = 1e-5 m/s of the rim's, and
// its friction force is whatever keeps it there: a stiff, quasi-static quantity (μN/(m·Δv) ≈
// 5e9 1/s). At the ends of a step the stage equations hold and these forces are right; a state
// interpolated inside the step (dense output, third order) misses Δv by far more, and the
// friction recomputed from it is noise of the size of μN. Measured on the paper's dry drive at
// 0.5–0.6 s (esdirk32, rtol 1e-4): the driver's belt torque is 68.3–71.5 N·m at every step end
// (equal to I·Ω̇ − M there) and anything from −75 to +226 N·m at the steps' midpoints.
//
// So `at` (observed from the interpolated state: positions, speeds, tensions, all smooth) gets its
// elements' normal force, friction and slip, and its pulleys' belt torque and hub load,
// interpolated linearly in time between `a` (the step's start) and `b` (its end), theta =
// (t - t_a)/(t_b - t_a); an element off the pulleys at either end, or on different pulleys at the
// two (contact made or lost in the step), keeps what its interpolated state gives. The contact
// state follows the blended slip.
// A kinematic pulley's drive torque is recomputed from the blended belt torque.
void blend_contact(const Model& m, double theta, const Observation& a, const Observation& b, Observation& at);

}  // namespace beltsim
