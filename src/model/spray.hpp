// Spray zones: water sprayed on the belt where it passes a circle, for a while. The law:
//
//   zone z sprays while it is enabled and from_z <= t < to_z; it wets the elements whose centre
//   lies inside its circle, |P_i - c_z| < R_z (the first zone in the list that holds one):
//     μ_i = μ_z
//   an element leaves the spray at t_w (it leaves the circle, or the zone stops spraying) moving
//   at v_w = |V_i(t_w)|, and dries linearly over the zone's drying length L of travel, its travel
//   since t_w taken at the speed it left with, v_w·(t - t_w):
//     μ_i(t) = μ_z + (μ_own,i - μ_z)·min(1, v_w·(t - t_w)/L)
//   and is dry (μ_i = μ_own,i, Drive::mu) from t_d = t_w + L/v_w on.
//
// Between these events μ_i is a function of time alone, so the Jacobian of a fixed μ stays exact
// and the state is unchanged. Each element's discrete state (ElementSpray) changes at an entry,
// an exit (a jump of μ: the integrator restarts there, the time located on the dense output by
// the run's schedule, src/sim/simulation.cpp) and at t_d (a kink: the integrator lands on it).
// Speeds that change while an element dries are not followed: its travel is the speed it left
// with times the time since.
#pragma once

#include <limits>
#include <vector>

#include "model/model.hpp"

namespace beltsim {

struct SprayZone {
  Vec2 centre{0, 0};         // [m]
  double radius = 0;         // [m]
  double mu = 0;             // the friction coefficient it gives the elements it wets
  double from = 0, to = 0;   // [s] it sprays for from <= t < to
  double drying_length = 0;  // [m] of travel over which a wetted element dries back to its own μ
  bool enabled = true;       // switched at a pause (sim:spray)
  bool on = false;           // spraying now: enabled and from <= t < to (set by spray_switch)
};

struct ElementSpray {
  int zone = -1;        // the zone spraying it now, -1: none
  bool drying = false;  // left a zone and not yet dry
  double t_in = 0;      // [s] when it entered its zone (or the zone started spraying on it)
  double mu_wet = 0;    // μ when it left
  double t_wet = 0;     // [s] when it left
  double rate = 0;      // [1/s] v_w / L: the fraction dried per second
  // [s] when it is dry (infinite for an element that left at rest)
  double t_dry() const { return rate > 0 ? t_wet + 1.0 / rate : std::numeric_limits<double>::infinity(); }
};

struct Spray {
  std::vector<SprayZone> zones;
  std::vector<ElementSpray> el;  // per element; empty when there are no zones
  int n_wet = 0;                 // elements in a zone or drying; 0: every μ is the element's own

  bool any() const { return !zones.empty(); }
  // μ of element i at t, its own μ being `own` (only called while n_wet > 0)
  double mu(int i, double own, double t) const {
    const ElementSpray& e = el[i];
    if (e.zone >= 0) return zones[e.zone].mu;
    if (!e.drying) return own;
    const double f = e.rate * (t - e.t_wet);
    return f >= 1 ? own : e.mu_wet + (own - e.mu_wet) * (f > 0 ? f : 0.0);
  }
};

// the zone spraying element i in the positions q (the first that is on and holds its centre), -1: none
int spray_zone_of(const Spray& s, const double* q, int i);
// whether some element's zone in q differs from its record (an entry or exit since the records)
bool spray_changed(const Spray& s, int n, const double* q);
// sets each zone's `on` for time t; returns the zones whose `on` changed
std::vector<int> spray_switch(Spray& s, double t);
// brings every element's record to the zones in (q, v) at t: those that entered take the zone's
// μ, those that left start drying. Returns whether a record changed.
bool spray_update(Spray& s, int n, double t, const double* q, const double* v);
// an element dry by t is dry (its record cleared); returns whether one was
bool spray_dry(Spray& s, double t);

}  // namespace beltsim
