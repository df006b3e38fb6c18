// The one check of a run's settings (sim/run_settings.hpp) against its scene, and the limits on
// what a run may write: Simulation's constructor, a batch run and a checkpoint's reader check
// through here. It reads the run-settings table (sim/run_table.hpp), the outputs' columns and the
// companion check's tolerance, each of which includes the settings' plain data.
#pragma once

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

// Refuses (ParameterError on the key, with the figures) to integrate from t0 to t1 when that would
// write more than 1e7 samples (a timeseries.csv of gigabytes) or render more than 1e5 frames (an
// hour of video at 30 fps) or keep more than 1e5 states, unless settings.allow_large.
// refuses an every() callback that a run from t0 to t1 would call more than 1e7 times (a period
// far below what the run resolves makes it crawl without a word), unless allow_large is set
void check_calls(const RunSettings& rs, double t0, double t1, double every_dt);
void check_volume(const Scene& scene, const RunSettings& settings, double t0, double t1);

}  // namespace beltsim
