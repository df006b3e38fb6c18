// What users observe of a state: per element, per pulley and per span, in SI units with one sign
// convention. The time-series CSV, the snapshots, the frames and the live simulation (Lua
// `sim:element`, `sim:pulley`, the console) all read these functions, so they show the same
// numbers.
//
// Signs: counter-clockwise positive for angles, speeds and torques (the model's convention).
// Contact quantities of an element are taken along the belt's direction of travel on the pulley
// it rides: friction > 0 pulls the belt forward, slip > 0 means the belt moves faster than the
// pulley's rim. An element rides the pulley it penetrates deepest.
//
// Contact state: the arc of its pulley an element is in (classify_contact, the one criterion).
// Creep theory (Reynolds, Grashof; Johnson, Contact Mechanics §8.3): in steady running a belt
// runs onto a pulley with the tension of the incoming span and sticks to the rim (the adhesion
// arc: no tension change, so no friction is needed); before it leaves, the tension changes to
// that of the outgoing span over the gross-slip arc, where the friction is saturated at μN, all
// in one direction, and the belt creeps against the rim as its strain changes. On that arc
// dT/dθ = ±μ·(T − m'v²), so its angle is ln((T1 − m'v²)/(T2 − m'v²))/μ (Euler–Eytelwein).
// The simplified Threlfall law (friction.cpp) makes the friction μ·N·sat(v_T/Δv): saturated
// exactly when |v_T| > Δv (for Threlfall's exponential μ(1 − exp(−|v|/Δv)) it would be a few
// Δv). So:
//   "free"   off the pulleys (or N = 0);
//   "slip"   in the gross-slip arc: the run of elements, counted back from where the belt leaves
//            the pulley's contact arc, whose friction is saturated (|slip| > Δv) in one direction.
//            One element inside the band between two saturated ones does not end the run (with
//            coarse elements each takes a tension step of μN·l and one of them dips through the
//            band as the belt passes). Nor does the belt lifting off: the last element inside
//            the band, and a backward run at the exit no longer than the lift-off zone that stops
//            there (not as the element behind it, not even across a dip), and an element inside
//            the band behind such a run. Past the tangent point
//            an element's centre runs straight along the span yet is still inside the contact
//            circle for sqrt(2·R·p) (p the wrap's penetration), and against the rim point at its
//            radius r it moves at ω·a²/r − ω·r (a the wrap's radius): backwards, up to about
//            2ω·p, from that path's geometry, with no tension change behind it. Measured on
//            scripts/serpentine.lua's free idler (0.2 to 0.3 s, 200 elements, a zone of 3.5 mm
//            against a pitch of 5.8 mm): its last element saturated in 47 of 201 samples, all
//            backwards, down to -65 mm/s at N = 0.1 to 24 N, while the inner elements stayed
//            within 9e-6 m/s at N = 73 to 96 N. Without this rule the idler read a gross-slip
//            arc of 4.7 % of its wrap on average and the tensioner 7.3 % (11 % each at 400
//            elements); with it 0 and 0 (2.4 and 2.0 % at 400 elements);
//            and elsewhere on the arc (its entry, its middle), every run of more than three
//            elements (or the lift-off zone's count, when larger) saturated in the gross-slip
//            arc's direction (in either, on an arc without one): where a wet stretch or a torque
//            pulse lands, the belt slips there too (a wet stretch arriving on the tutorial's
//            crankshaft: 15 saturated elements at its entry carrying 180 N of tension change read
//            as sticking before);
//   "stick"  the rest of the contact arc: the adhesion arc. Micro-slip inside the band (friction
//            below μN, which a Δv of 1e-5 m/s turns into a stiff spring) is sticking, and so is
//            the short saturated slip of an element settling onto the rim where the belt runs on
//            (one to three elements, either direction, measured: it takes the entry's tension
//            overshoot, not the span-to-span change), and a run against the gross-slip arc's
//            direction (that overshoot settling back: on a 480-element driven pulley twelve
//            elements); their `slip` still shows it.
// Measured (tests/physics, a two-pulley drive): the slip arc approaches R·ln(T1/T2)/μ as the
// elements are refined, while |slip| > Δv alone counts the entry's settling too, and
// |F| >= 0.98·μN counts sticking elements whose slip hovers at the band's edge.
#pragma once

#include <vector>

#include "model/contacts.hpp"
#include "model/drive.hpp"
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
  double penetration = 0;        // [m] depth of its centre in the pulley it rides: R - r (0 when free)
  double mu = 0;                 // friction coefficient of the element now
  int pulley = -1;               // the pulley it rides, -1 when free
  ContactState state = ContactState::free;  // classify_contact
};

struct PulleyObs {
  double omega = 0;        // [rad/s]
  double angle = 0;        // [rad] turned since t = 0
  double torque = 0;       // [N·m] applied (for a kinematic pulley: what the drive supplies)
  double belt_torque = 0;  // [N·m] moment of the belt's friction on it
  double hub_load = 0;     // [N] magnitude of the belt's resultant force on it
  double arm_angle = 0;    // [rad] its tensioner arm's angle (NaN without an arm)
  double arm_rate = 0;     // [rad/s] the arm's angular speed (NaN without an arm)
  // with a coupled rotor (NaN without): its angle [rad] and speed [rad/s], the decoupler spring's
  // windup [rad] (pulley minus rotor, or minus the one-way clutch's hub) and the torque the
  // coupling puts on the rotor [N·m]; `torque` is then the applied torque on the rotor
  double rotor_angle = 0, rotor_speed = 0, windup = 0, coupling_torque = 0;
  Vec2 hub{0, 0};          // [N] that force as a vector
  // arcs [m] of belt length: the elements in each state on this pulley, each standing for one
  // pitch l of belt (classify_contact); contact_arc = slip_arc + stick_arc
  double contact_arc = 0, slip_arc = 0, stick_arc = 0;
  // The belt's speed on this pulley's wrap, v_belt [m/s] along the travel (wrap_speeds), as creep
  // theory has it: on the adhesion arc the belt moves with the pitch line, v_pitch = ω·(R − p̄)
  // along the travel (p̄ the mean penetration of the wrap's inner elements, whose neighbours both
  // ride it too: the first and last are partly lifted off; of all of them when none is inner); on
  // the gross-slip arc each element moves at v_pitch + its slip. v_belt is their mean:
  //   v_belt = v_pitch + (sum of the slip over the gross-slip arc)/n,  n the elements riding it;
  // NaN while none rides it, and with it slip_speed, creep and creep_pitch. Not the whole loop's
  // mean speed: the belt runs faster on a tight span than on a slack one (by (T1 − T2)/EA, more
  // than a pulley's creep), and a free idler on a tight span read the driver's sign against it.
  // A saturated slip that the criterion calls sticking (an element settling onto the rim where the
  // belt runs on, the last one lifting off) is not creep: those elements count at v_pitch.
  // (Not a CSV column: slip_speed plus the rim's speed.)
  double belt_speed = 0;
  // 1 - v_rim/v_belt: v_rim = ω·R along the travel (R the pulley's contact radius). > 0: the pulley
  // lags the belt on it (driven), < 0: it leads (driver); NaN while |v_belt| <= Δv. Includes the
  // radial part: the belt's pitch line rides at R - p̄, not R.
  double creep = 0;
  // v_belt - v_rim [m/s], both along the travel as in creep: the gross-slip arc's slip summed / n,
  // less the radial part ω·p̄
  double slip_speed = 0;
  // creep without the radial part: 1 - v_pitch/v_belt = (sum of the slip over the gross-slip
  // arc)/(n·v_belt), i.e. slip_arc/contact_arc times that arc's mean slip over v_belt; NaN while
  // |v_belt| <= Δv. Its sign in steady running: the gross-slip arc's friction is saturated, all
  // one way, and it is what changes the tension from the incoming span's to the outgoing one's:
  // along the travel the friction on the belt is -dT/ds. On a driver the tension falls, the rim
  // pulls the belt forward, so the rim is the faster: slip < 0, creep_pitch < 0 (the rim keeps
  // the speed of the tight side, which it took on the adhesion arc; the belt slows as it
  // contracts). On a driven pulley the tension rises: slip > 0, creep_pitch > 0 (the rim keeps
  // the slack side's speed). A wrap without a gross-slip arc reads 0: a free idler (the same
  // tension either side), or a lightly loaded pulley between two of its elements' slips.
  double creep_pitch = 0;
  // v_belt - v_pitch [m/s] along the travel: the slip summed over the gross-slip arc / n, the
  // creep_pitch's speed (creep_pitch·v_belt) and of its sign; 0 on a wrap without a gross-slip
  // arc, NaN while no element rides the pulley. The frames' header shows it
  double slip_pitch = 0;
  // the mean friction coefficient of the elements in contact with it now (NaN when none): the
  // wrap's μ, so that e^{mu·θ} is Euler–Eytelwein's e^{∫μ dθ} on a wrap whose elements differ
  // (a wetted stretch, a spray zone's drying elements)
  double mu = 0;
};

// What one element feels from the pulleys, in the pulleys' own frame (sums over its pairs in the
// contact records of its state, model/contacts.hpp)
struct ElementContact {
  double normal = 0;      // |N| summed over pulleys [N]
  double friction = 0;    // signed tangential friction force on the element, along t̂ [N]
  double slip = 0;        // v_T against the pulley it touches [m/s]; NaN when free
  double penetration = 0;  // its penetration p into that pulley [m]; 0 when free
  int pulley = -1;        // index of the pulley touched (the deepest), -1 when free
};
// Asked about one element or one pulley of a state, these read the contact records of the state
// (fill_contacts, model/contacts.hpp), which the caller fills once for every question about it.
// Element i's contact sums
ElementContact element_contact(const ContactRecords& contacts, int i);
// belt torque on pulley j (moment of the friction reactions) [N·m] and hub load vector [N]
double belt_torque(const ContactRecords& contacts, int j, Vec2* hub_load);
// pulley j of the state y (y = [q | v | e | z]) at t, whose contact records are `contacts`
PulleyObs observe_pulley(const Model& m, const Drive& d, double t, const double* y, const ContactRecords& contacts,
                         int j);
// every pulley at once: fills `contacts` with the records of (t, y) and reads them
void observe_pulleys(const Model& m, const Drive& d, double t, const double* y, ContactRecords& contacts,
                     std::vector<PulleyObs>& out);

// Everything observed of one state: each element and each pulley.
struct Observation {
  double t = 0;
  double belt_speed = 0;  // [m/s] mean speed of the elements along their axes (the travel direction)
  std::vector<ElementObs> elements;
  std::vector<PulleyObs> pulleys;
  // observe()'s working space, kept so that a sample allocates nothing
  std::vector<double> work;             // the SDEs' axial forces
  ContactRecords contacts;              // the contact records of the state observed
  std::vector<ElementContact> contact;  // each element's sums over its pairs
};
// sense[j]: +1 when the belt goes round pulley j anticlockwise, -1 clockwise (Scene::senses());
// fills out.contacts with the records of (t, y) and reads them for every element and pulley
void observe(const Model& m, const Drive& d, const std::vector<int>& sense, double t, const double* y,
             Observation& out);

// The contact state of every element and the arcs of every pulley from the elements' pulley,
// normal force and slip (the criterion above; the exit is the last element in the direction the
// belt moves: along the element numbers, or against them when belt_speed < 0).
// observe() and blend_contact() call it; nothing else decides what slips.
void classify_contact(const Model& m, Observation& o);

// Every pulley's belt_speed, creep, slip_speed and creep_pitch (PulleyObs) from its speed and its
// wrap's elements: their pulley, state, slip and penetration. observe() and blend_contact() call it.
void wrap_speeds(const Model& m, const std::vector<int>& sense, Observation& o);

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
// state and the arcs follow the blended slip (classify_contact), and so do the pulleys' creep and
// slip speed (wrap_speeds; sense as observe's).
// A kinematic pulley's drive torque is recomputed from the blended belt torque.
void blend_contact(const Model& m, const Drive& d, const std::vector<int>& sense, double theta, const Observation& a,
                   const Observation& b, Observation& at);

}  // namespace beltsim
