// The error of a run's answer as issue 42 §1 measures it, in one place: for a group of channels
// (the pulley speeds, the span tensions) the largest difference over the samples from a more
// accurate solution, relative to that solution's largest magnitude of each channel over the run:
//   error = max over channels c of  max_k |x_c(t_k) - x_ref,c(t_k)| / max_k |x_ref,c(t_k)|
// `beltsim wp` measures it against a reference run (sim/work_precision.hpp), a run's check
// against its companion solution (sim/run_check.hpp), sample by sample as they come.
#pragma once

#include <cstddef>
#include <vector>

namespace beltsim {

struct Drive;
struct Model;
struct Scene;

class ErrorMeter {
 public:
  // floor: the least scale of a channel, in its unit (0: none); a run's check measures a pulley's
  // speed against at least the 1 rad/s its absolute tolerance is per (integrate/belt_problem.hpp)
  explicit ErrorMeter(size_t channels = 0, double floor = 0)
      : scale_(channels, floor), worst_(channels, 0.0), last_(channels, 0.0) {}
  // one sample: x and ref hold the channels' values (size channels())
  void add(const double* x, const double* ref);
  // the error over the samples so far (0 before any); a channel whose reference is 0 throughout
  // is measured in its own unit
  double error() const;
  // the same for the last sample alone (still relative to the largest magnitude over the run)
  double error_last() const;
  size_t channels() const { return scale_.size(); }

 private:
  double relative(const std::vector<double>& diff) const;
  std::vector<double> scale_, worst_, last_;
};

// The channels a run's error is measured on, read from a state as timeseries.csv writes them:
// each pulley's speed [rad/s] (a kinematic one's prescribed speed), in the model's order, then
// each route span's tension [N] (span_force)
void speeds_and_tensions(const Scene& sc, const Drive& drive, double t, const double* y, std::vector<double>& speeds,
                         std::vector<double>& tensions);

}  // namespace beltsim
