// Pulley laws: the applied torque M(t, Ω) [N·m] of a free pulley, or the prescribed speed Ω(t)
// [rad/s] of a kinematic one, as a sum of terms (docs/lua-api.md, "Laws", lists them with the same
// formulas; laws.cpp evaluates them and their derivatives, formulas at its top).
//
//   value(t, Ω) = constant + per_speed·Ω + table(t) + speed_table(Ω)
//               + Σ ramps(t) + Σ sines(t) + Σ harmonics(t) + fn(t, Ω)
//
// The tables interpolate linearly and hold their end values outside; the sum of two laws is a law
// (their tables merge exactly onto the union of breakpoints). `fn` is code the model cannot see
// into (a Lua function, src/script/lua_law.cpp): its derivatives are finite differences.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace beltsim {

// from for t < t0, to for t > t1; between them a linear or a cosine (zero-slope ends) blend.
// t0 == t1 is a step: a jump at t0 (the value at exactly t0 is `from` unless the caller asks for
// the value after the jump, see TimeSpeedLaw::value).
struct Ramp {
  double t0 = 0, t1 = 0;      // [s], t0 <= t1
  double from = 0, to = 0;    // the law's unit
  bool cosine = false;
  bool is_step() const { return t0 == t1; }
};

// mean + amplitude·sin(2π·frequency·t + phase)
struct Sine {
  double mean = 0, amplitude = 0;  // the law's unit
  double frequency = 0;            // [Hz]
  double phase = 0;                // [rad]
};

// amplitude·sin(order·mean_speed·t + phase): a firing order of a crankshaft turning at mean_speed
struct Harmonic {
  double order = 1;       // k (> 0; half orders for four-stroke engines)
  double amplitude = 0;   // the law's unit
  double phase = 0;       // [rad]
  double mean_speed = 0;  // ω_m [rad/s]
};

// An error inside a law's own code (a Lua function that raised or returned no number): stops the
// run (the outputs are closed, Simulation::run_to).
struct LawError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Lua code a run called (a law, a live simulation's callback) was interrupted by Ctrl-C (or SIGTERM,
// SIGHUP): the run stops where it stands, as at a stop signal between its steps (Simulation::run_to:
// end.status interrupted, the outputs kept open). The message names the code ("pulley 'driven'.torque
// (function at s.lua:3) at t = ...: s.lua:5: interrupted!"). A LawError to the callers that know
// only those (a law called outside a run: the scene's build, the linearisation).
struct StoppedInCode : LawError {
  using LawError::LawError;
};

// A law given as code. value() may throw LawError.
class LawFunction {
 public:
  virtual ~LawFunction() = default;
  virtual double value(double t, double omega) const = 0;
  virtual std::string describe() const = 0;  // "function (file:line)" for messages and events.csv
  // calls made so far (one per value(); a test counts them)
  virtual long calls() const = 0;
};

struct TimeSpeedLaw {
  double constant = 0.0;            // [N·m] or [rad/s]
  double per_speed = 0.0;           // [N·m·s/rad]; zero for a prescribed speed
  std::vector<double> t;            // [s], strictly increasing
  std::vector<double> value;        // table(t): same unit as constant, one per t
  std::vector<double> omega;        // [rad/s], strictly increasing
  std::vector<double> omega_value;  // speed_table(Ω): same unit as constant, one per omega
  std::vector<Ramp> ramps;
  std::vector<Sine> sines;
  std::vector<Harmonic> harmonics;
  std::shared_ptr<const LawFunction> fn;

  bool is_zero() const;
  // the value at (t, Ω); at a step's own time the value after the jump when `after_jump`
  double eval(double time, double omega_now, bool after_jump = false) const;
  // ∂/∂Ω (analytic; central differences for fn)
  double d_omega(double time, double omega_now) const;
  // ∂/∂t (right-hand derivative at kinks; the jumps of steps are not in it)
  double d_time(double time, double omega_now) const;
  // ∂²/∂t² of a law of time alone (a prescribed speed's Ω''), right-hand at kinks
  double d_time2(double time) const;
  // the times where the value or its derivative in time jumps (table breakpoints, ramp ends)
  std::vector<double> kinks() const;
  // the times where the value itself jumps (steps)
  std::vector<double> jumps() const;
  // this + other
  TimeSpeedLaw& operator+=(const TimeSpeedLaw& other);

  // the time table alone
  double table(double time) const;
  double table_slope(double time) const;  // right-hand derivative at breakpoints
};

// linear interpolation in a table (x increasing), the end values held outside; its slope
// (right-hand at breakpoints, 0 outside)
double interpolate(const std::vector<double>& x, const std::vector<double>& y, double at);
double interpolate_slope(const std::vector<double>& x, const std::vector<double>& y, double at);

}  // namespace beltsim
