// The driver: steps from t0 to t_end, lands exactly on event times (kinks and jumps of the
// model's laws: torque table breakpoints, wetting), and reports the solution at fixed sample
// times by dense output (cubic Hermite on the step's end values and slopes), so samples never
// depend on where the steps fell and never shorten a step.
#pragma once

#include <atomic>
#include <functional>
#include <stdexcept>
#include <vector>

#include <Eigen/Core>

#include "integrate/controller.hpp"
#include "integrate/stepper.hpp"
#include "integrate/system.hpp"

namespace beltsim {

// A run that could not continue: NaN/Inf, runaway, or a step size that collapsed.
struct DivergenceError : std::runtime_error {
  DivergenceError(double time, const std::string& what) : std::runtime_error(what), t(time) {}
  double t;
};

struct DriveOptions {
  double t0 = 0, t_end = 1;
  double sample_dt = 1e-3;          // [s] samples at t0 + k·sample_dt and at t_end
  std::vector<double> events;       // [s] times the stepper must land on exactly
  double h_max = 0;                 // [s] largest step (0: t_end - t0)
  const std::atomic<bool>* stop = nullptr;  // set from elsewhere (Ctrl-C) to end the run early
  // called on landing at each event time, after that time's sample: it may change the system
  // (a wetted stretch of belt) or the state; the stepper then restarts from there
  std::function<void(double t, Eigen::VectorXd& y)> on_event;
  // a second output stream at its own exact times (frames): frame_t0 + k·frame_dt <= t_end,
  // delivered by the same dense output as the samples (0 or no frame function: none)
  double frame_dt = 0;
  double frame_t0 = 0;
  std::function<void(double t, const Eigen::VectorXd& y)> frame;
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
DriveResult drive(OdeSystem& sys, Stepper& stepper, const Tolerances& tol, const DriveOptions& opt,
                  Eigen::VectorXd& y, const SampleFn& sample, const ProgressFn& progress = {});

// cubic Hermite interpolation on [t0, t0 + h]
void hermite(double theta, double h, const Eigen::VectorXd& y0, const Eigen::VectorXd& f0,
             const Eigen::VectorXd& y1, const Eigen::VectorXd& f1, Eigen::VectorXd& out);

}  // namespace beltsim
