// A run: Scene → integrator → observers (time-series CSV, parameters file, progress).
// This is what `beltsim run` and the Lua `scene:run{}` call.
#pragma once

#include <atomic>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "integrate/system.hpp"
#include "scene/scene.hpp"
#include "sim/frames.hpp"

namespace beltsim {

// A change of the belt's friction coefficient at a known time (wetting, drying): the stepper
// lands exactly on t and restarts there. mu holds one value per element; NaN keeps the old one.
struct MuEvent {
  double t = 0;              // [s]
  std::vector<double> mu;
};

struct RunSettings {
  double t_end = 1.0;                 // [s]
  std::string integrator = "esdirk32";
  double rtol = 1e-4;                 // relative tolerance of the error control
  double atol = -1;                   // absolute, per natural unit of each component; < 0: = rtol
  double sample_dt = 1e-3;            // [s] interval of the time-series samples
  std::string out_dir = "out";
  int probe_element = 0;              // the paper's "selected" element; its SDE joins it to its predecessor
  bool progress = true;               // report on stderr for runs longer than a second
  double wall_limit = 0;              // [s] stop the run after this much wall time (0: no limit)
  bool keep_samples = false;          // keep the rows of timeseries.csv in RunResult::samples
  std::vector<MuEvent> mu_events;     // in any order
  // frames (PNG and/or video) at their own times; relative paths are taken inside out_dir. The
  // factory (the renderer's, src/render) is called only when frames are asked for.
  std::optional<FrameSettings> frames;
  FrameSinkFactory frame_factory;
};

struct RunResult {
  double t_reached = 0;
  bool interrupted = false;
  double wall_seconds = 0;
  WorkCounters work;
  std::vector<double> omega;          // final pulley speeds [rad/s], in the model's order
  std::string csv_path, parameters_path;
  bool over_wall_limit = false;       // stopped by RunSettings::wall_limit
  std::vector<std::vector<double>> samples;  // with keep_samples: the CSV rows
  long frames = 0;                    // frames rendered
};

// Writes DIR/timeseries.csv and DIR/parameters.csv. Throws DivergenceError (after flushing what
// was written), std::invalid_argument for unknown integrators, std::runtime_error for I/O.
RunResult run(const Scene& scene, const RunSettings& settings, const std::atomic<bool>* stop = nullptr);

// the column names of timeseries.csv for a scene (documented in the README)
std::vector<std::string> timeseries_columns(const Scene& scene);

}  // namespace beltsim
