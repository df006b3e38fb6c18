// What a run is asked to do (plain data) and what follows from it alone: the frame times, the
// outputs' paths, an event's time, what a run cannot reach. The one check of it against its scene
// is sim/settings_check.hpp's.
#pragma once

#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "sim/frames.hpp"

namespace beltsim {

struct Scene;

// A change of the belt's friction coefficient at a known time (wetting, drying): the integrator
// lands exactly on t and restarts there. mu holds one value per element; NaN keeps the old one.
struct MuEvent {
  double t = 0;              // [s]
  std::vector<double> mu;    // the new μ per element (NaN: unchanged)
  // empty: mu replaces; else the share w in [0, 1] of the new μ each element takes when the event
  // comes, μ = μ_then + w·(mu - μ_then) (a wet/dry transition over a length, wet_share)
  std::string what = "mu";   // for events.csv: what changed, and how
  std::string text;
  std::vector<double> share;
};

// (each setting's key, unit, default, rule and more: sim/run_table.hpp)
struct RunSettings {
  double t_end = 1.0;                 // [s] (batch runs only)
  std::string integrator = "trbdf2";   // docs/accuracy.md, "The accuracy contract"
  double rtol = 1e-4;                 // relative tolerance of the error control
  double atol = -1;  // absolute, per natural unit of each component; -1 (Tolerances::kAtolUnset): = rtol
  double sample_dt = 1e-3;            // [s] interval of the time-series samples
  std::string out_dir = "out";
  // the probed elements (the paper's "selected" one): columns probe.* for one, probe<k>.* (k = 1,
  // 2, ...) for several; an element's SDE joins it to its predecessor
  std::vector<int> probes{0};
  // per-element snapshots (snapshots.csv) at these times [s] (sorted, >= 0) and/or every
  // snapshot_every [s] from t = 0 (0: none)
  std::vector<double> snapshot_times;
  double snapshot_every = 0;
  // [s] wall time after which an integration call (a batch run, sim:run_to) stops at the last
  // finished step or output, Advance::over_wall_limit set (0: no limit); max_wall in Lua
  double wall_limit = 0;
  // [s] the clock run_to measures its wall time with (the wall-time limit, the no-progress
  // watchdog, Advance::wall); empty: std::chrono::steady_clock. Tests set a fake one, so that a
  // collapse of the rate happens at a known moment.
  std::function<double()> wall_clock;
  bool keep_samples = false;          // keep the rows of timeseries.csv in memory (samples())
  bool progress = true;               // the progress line and scene:run's closing line (script/progress.hpp)
  bool allow_large = false;           // past the output limits (check_volume)
  std::vector<MuEvent> mu_events;     // in any order
  // frames (PNG and/or video) at their own times; relative paths are taken inside out_dir. The
  // factory (the renderer's, src/render) is called only when frames are asked for.
  std::optional<FrameSettings> frames;
  FrameSinkFactory frame_factory;
  // the whole state (a checkpoint, sim/simulation.hpp Simulation::save) at each frame time, as
  // OUT_DIR/states/state_NNNNN.ckpt (NNNNN the number of the frame drawn there), for
  // `beltsim render`. Frames with neither png nor video give only the times; without frames the
  // default frame settings' times (every 1/300 s from t = 0). One-step integrators only.
  bool keep_states = false;
  // estimate the run's own error against a companion solution at rtol/10 advanced in lockstep
  // (sim/run_check.hpp): about 3 times the run's cost (docs/accuracy.md). A checkpoint keeps
  // the run alone: a resumed run is not checked.
  bool check = false;
  // messages of a run while it runs (the check's estimate past 10×rtol), for the caller to show;
  // empty: none shown (parameters.csv and the result still hold them)
  std::function<void(const std::string&)> on_warning;
  // called once the output folder is claimed for this run, before anything in it is written (a
  // folder in use is refused before it): scene:run's and scene:start's word that the run replaces
  // an earlier one's outputs; empty: nothing
  std::function<void()> on_claimed;
};

// The times frames are drawn and states kept at, t_start + k·frame_dt(): the frames' settings, the
// default ones when states are kept without frames; none when neither is asked for.
std::optional<FrameSettings> frame_times(const RunSettings& settings);

// The one rule for a path a script or a console command gives beltsim to write: a relative one
// lies inside the run's output folder out_dir, an absolute one stays (frames.png, frames.video,
// sim:save, sim:show's and sim:plot's files, sim:modes' csv, r:summary's csv and plot). The path
// as seen from the folder beltsim runs in. (A run's `out` itself, and the paths beltsim reads,
// beltsim.resume's and Lua's own io, are taken from the folder beltsim runs in.)
std::string output_path(const std::string& out_dir, const std::string& path);
std::string output_path(const RunSettings& settings, const std::string& path);

// Why t cannot be the time of a timed event in a run that ends at t_end (infinity: a live
// simulation, which has no end): "must be > 0 s and finite (got -1 s)", "must be before t_end =
// 0.05 s (got 0.1 s)"; "" when it can.
std::string event_time_problem(double t, double t_end = std::numeric_limits<double>::infinity());

// why dir cannot be a run's output folder ("" when it can): an empty path, which would silently
// be the folder beltsim runs in
std::string out_dir_problem(const std::string& dir);

// What a run that ends at settings.t_end cannot reach is removed, one note for each, for the caller
// to print: timed μ events at or after t_end ("events: the event at 0.1 s (wet) is at or after
// t_end = 0.05 s: skipped"). When t_end was shortened from outside the script (`shortened_by`:
// "--t-end", a quick check of a script whose snapshots and frames come later), also the snapshot
// times after it, and the frames (with the kept states) when they start after it; the notes then
// name it. Otherwise those are the script's own contradiction, for check() to refuse. A time wrong
// by itself (negative, not finite) is kept for check() to refuse.
std::vector<std::string> drop_after_end(RunSettings& settings, const char* shortened_by = nullptr);

// The warning before a batch run whose sample interval is longer than the run (t_end, from
// `shortened_by` as drop_after_end's): its timeseries.csv would hold only the row at t = 0 ("" when
// it holds more). A warning, not an error: the run is valid (its end state is in the result and in
// parameters.csv) and a --t-end check of a long run may mean it, but a one-row time series is more
// often a sample given in ms (sample = 1 for 1 ms) and went unnoticed until the CSV was opened.
std::string sample_warning(const RunSettings& settings, const char* shortened_by = nullptr);

}  // namespace beltsim
