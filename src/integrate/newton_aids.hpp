// Newton aids for the belt's implicit stages. They serve the integrator (BeltNewtonAids::reseat,
// local_solve, predict and branches, see system.hpp), not the model: the right-hand side is piecewise
// smooth (contact onset, p = p_max, N = 0 and the friction band |v_T| < Δv), and a Newton step
// taken at a slipping element sees a constant friction force, jumps right across the band and
// cycles. The aids read the contact and friction laws (model/contact_law.hpp) but add no force;
// their derivations are at the top of newton_aids.cpp.
#pragma once

#include <cstdint>
#include <vector>

#include "model/contacts.hpp"
#include "model/drive.hpp"
#include "model/model.hpp"

namespace beltsim {

// Every aid reads the records of the contact stage (model/contacts.hpp) of the iterate it is given,
// in pass order.

// a hash of the branch every element–pulley pair is on (out of contact, clamped, p < p_max,
// sticking or slipping either way): two states with the same hash have the same smooth piece of
// the contact and friction laws, so a Jacobian taken at one serves Newton at the other
uint64_t contact_branches(const Model& m, const ContactView& pairs);
// Newton aid for the friction band (see newton_aids.cpp): every element in contact that slips at
// (q, v) and would slip the other way at (q + dq, v + dv) is put into the band, where the
// correction takes it (its velocity correction dv changes so that its slip velocity there is zero)
// or at the iterate (its velocity v changes). Returns the number of elements moved.
enum class Reseat { correction, iterate };
int friction_reseat(const Model& m, const Drive& d, const ContactView& pairs, const double* q, double* v,
                    const double* dq, double* dv, Reseat where);
// Newton aid (see newton_aids.cpp): g is the stage residual's velocity part (m/s) at (q, v); each
// element in contact gets the tangential velocity change that zeroes its own tangential residual
// with everything else held (an exact piecewise-linear solve). Returns the number moved; 0 under
// a friction law other than Threlfall's (its solve needs sat's monotone band).
struct LocalSolveScratch {
  std::vector<int> pair;                                            // one pulley's pressing pairs
  std::vector<double> u0, lin, B, r, off, w, grad, dir, dz, cp, den;  // per pressing pair
  double J = 0, lin_omega = 0, omega = 0;                           // the pulley's (J = 0: held)
};
int friction_local_solve(const Model& m, const Drive& d, const ContactView& pairs, double s, double* q, double* v,
                         const double* g, LocalSolveScratch& w);
// Newton aid for the stop (see newton_aids.cpp): the largest distance, in friction bands, by which
// the velocity correction dv (linearised) carries an element's slip velocity at (q, v) past an edge
// of the band |v_T| < Δv, out of the piece it is on (0: every element stays on its piece; the
// pairs' friction laws give v_T at (q, v); LuGre's bristles have no band and are left out).
double friction_overshoot(const Model& m, const Drive& d, const ContactView& pairs, const double* q, const double* dv);
// the largest rate at which an element's slip velocity grows on a falling friction curve with
// everything else held, -μ'·N/m over the pairs in contact (see newton_aids.cpp); 0 when none falls
double falling_friction_rate(const Model& m, const ContactView& pairs);
// on[i]: the first pulley element i presses on in the pass (-1: none)
void pressed_pulleys(const Model& m, const ContactView& pairs, std::vector<int>& on);

// Newton's starting point for a stage dt after the state (q, v) at t (see newton_aids.cpp): each
// element pressing on a pulley turns about the pulley's centre with its own angular velocity
// about it, carrying its velocity round with it (relative to the centre and its motion, on a
// tensioner arm, which turns at its rate); every other element moves on in a straight line;
// pulley, arm, rotor and hub angles advance at their rates. Velocities keep their size, but on a
// pulley whose speed is prescribed an element keeps its slip (it gains the pulley's change of
// speed times its radius). pairs: the records of the contact stage of (q, v) at t, read before
// anything moves.
struct PredictScratch;
void kinematic_predict(const Model& m, const Drive& d, double t, double dt, const ContactView& pairs, double* q,
                       double* v, PredictScratch& w);

// Newton's starting point for belts whose elements travel half a pitch or more in a stage (see
// newton_aids.cpp): kinematic_predict, then each such element takes the state the belt had at t
// at the place the element travels to (a steadily running drive's state is stationary in space,
// so the slip arcs and the wrap ends stay where they are while the elements pass through them).
// w holds copies of the state at t between calls, so the step loop allocates nothing once sized.
struct PredictScratch {
  std::vector<double> q0, v0;
  std::vector<int> on;      // the pulley each element presses on at t (-1: none)
  std::vector<double> dom;  // each pulley's prescribed change of speed over the stage (0: none)
  // each pulley's centre and its velocity at t (c0, vc0) and at t + dt (c1, vc1): they differ on
  // a tensioner arm, which the prediction turns at its rate
  std::vector<Vec2> c0, vc0, c1, vc1;
};
void convective_predict(const Model& m, const Drive& d, double t, double dt, const ContactView& pairs, double* q,
                        double* v, PredictScratch& w);

}  // namespace beltsim
