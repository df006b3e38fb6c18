// drive(): a whole run from t0 to t_end in one call, for tests, benchmarks and the
// work-precision study. It is the live schedule (integrate/timeline.hpp) run to t_end with the
// integrator landing on t_end: samples at t0 + k·sample_dt (and one at t_end when it is off
// that grid), further streams (frames) at their own t0 + k·dt, events landed on exactly.
#pragma once

#include <atomic>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "integrate/controller.hpp"
#include "integrate/integrator.hpp"
#include "integrate/stepper.hpp"
#include "integrate/system.hpp"

namespace beltsim {

struct DriveOptions {
  double t0 = 0, t_end = 1;
  double sample_dt = 1e-3;          // [s] samples at t0 + k·sample_dt and at t_end (0: none)
  std::vector<double> events;       // [s] times the integrator must land on exactly
  double h_max = 0;                 // [s] largest step (0: t_end - t0)
  const std::atomic<bool>* stop = nullptr;  // set from elsewhere (Ctrl-C) to end the run early
  // called on landing at each event time, after that time's sample: it may change the system
  // (a wetted stretch of belt) or the state; the integrator then restarts from there
  std::function<void(double t, Eigen::VectorXd& y)> on_event;
  // further output streams at their own exact times, each at t0 + k·dt <= t_end, in this order
  // at a shared time (frames; the plain run that several mode checks share, sim/mode_check.cpp)
  struct Stream {
    double t0;  // [s]
    double dt;  // [s]
    std::function<void(double t, const Eigen::VectorXd& y)> fn;
  };
  std::vector<Stream> streams;
};

struct DriveResult {
  WorkCounters work;
  double t_reached = 0;
  bool interrupted = false;
  double wall_seconds = 0;
};

using SampleFn = std::function<void(double t, const Eigen::VectorXd& y)>;
using ProgressFn = std::function<void(double t, const WorkCounters& w)>;

// y: initial state in, final state out. Throws DivergenceError (samples up to the failure have
// been delivered).
DriveResult drive(Integrator& integ, const DriveOptions& opt, Eigen::VectorXd& y, const SampleFn& sample,
                  const ProgressFn& progress = {});
// the same with a one-step method
DriveResult drive(const OdeSystem& sys, Stepper& stepper, const Tolerances& tol, const DriveOptions& opt,
                  Eigen::VectorXd& y, const SampleFn& sample, const ProgressFn& progress = {});

}  // namespace beltsim
