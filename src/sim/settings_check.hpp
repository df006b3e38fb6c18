// The one check of a run's settings (sim/run_settings.hpp) against its scene, and the limits on
// what a run may write: Simulation's constructor, a batch run and a checkpoint's reader check
// through here. It reads the run-settings table (sim/run_table.hpp), the outputs' columns and the
// companion check's tolerance, each of which includes the settings' plain data.
#pragma once

#include <string>

#include "sim/run_settings.hpp"

namespace beltsim {

struct Scene;

// Checks settings for a run of sc: the output folder (out_dir_problem), integrator and tolerances, sample interval,
// probes, snapshot times, events (one μ per element, event_time_problem), frames (validate(FrameSettings), a renderer
// to draw them; frames that draw nothing only with keep_states). A batch run (batch) also checks t_end and what must
// come before it (frames.t_start, snapshot times, events). Each number and text by its rule in the run-settings table
// (sim/run_table.hpp). Throws ParameterError (scene/validate.hpp) with the key's path and the reason, the value in its
// words; the caller names the table (run, start).
void check(const Scene& sc, const RunSettings& rs, bool batch);

// The outputs a run writes from t0 to t1, estimated before it runs: the rows of timeseries.csv and
// snapshots.csv with the bytes a row takes, and the states kept (keep_states) with the bytes one
// takes (state_bytes, the simulation's estimate: Simulation::kept_state_bytes; 0 for none).
struct OutputVolume {
  double rows = 0, row_bytes = 0;                    // timeseries.csv
  double snapshot_rows = 0, snapshot_row_bytes = 0;  // snapshots.csv
  double states = 0, state_bytes = 0;                // states/
  double bytes() const { return rows * row_bytes + snapshot_rows * snapshot_row_bytes + states * state_bytes; }
};
OutputVolume output_volume(const Scene& scene, const RunSettings& settings, double t0, double t1,
                           double state_bytes = 0);

// past this the outputs of a run are warned of before it runs (volume_warning): beltsim summary
// reads a GB of timeseries.csv in about 75 s and beltsim plot in about 110 s (measured: 3.3 s and
// 5.0 s for 44.6 MB, 72 750 rows of per_length_dry.lua), a pandas frame of it takes about 0.5 GB
// of memory (59 million values), and a kept state at 2400 elements is 2.2 MB, 660 MB per simulated
// second: outputs past it are more likely a sample interval or keep_states given by mistake than meant
inline constexpr double kLargeOutputs = 1e9;  // [bytes]
// The warning before a run that writes v (to t1) into out_dir: when the outputs will pass
// kLargeOutputs (`written`: the bytes they hold now) or more than the `free` bytes of the folder's
// file system (-1: unknown), what they will be, of what, and what to do; "" otherwise
std::string volume_warning(const OutputVolume& v, double t1, double written, double free, const std::string& out_dir);

// Refuses (ParameterError on the key, with the figures) to integrate from t0 to t1 when that would
// write more than 1e7 samples (a timeseries.csv of gigabytes) or render more than 1e5 frames (an
// hour of video at 30 fps) or keep more than 1e5 states, unless settings.allow_large.
// refuses an every() callback that a run from t0 to t1 would call more than 1e7 times (a period
// far below what the run resolves makes it crawl without a word), unless allow_large is set
void check_calls(const RunSettings& rs, double t0, double t1, double every_dt);
void check_volume(const Scene& scene, const RunSettings& settings, double t0, double t1);

}  // namespace beltsim
