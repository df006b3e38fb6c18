// The one check of a run's settings and the limits on what a run writes (sim/settings_check.hpp).
#include "sim/settings_check.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "integrate/integrator.hpp"
#include "io/number_text.hpp"
#include "scene/scene.hpp"
#include "scene/validate.hpp"
#include "sim/outputs.hpp"
#include "sim/run_check.hpp"
#include "sim/run_table.hpp"

namespace beltsim {

void check(const Scene& sc, const RunSettings& rs, bool batch) {
  const Model& m = sc.model;
  // the numbers and texts by their own rules (run_table.hpp); a live simulation has no end
  for (const RunSetting& s : run_settings())
    if (batch || (s.where & kStartKey) || !(s.where & kRunKey))
      if (const std::string bad = run_problem(s, rs, false); !bad.empty()) {
        throw ParameterError(std::string(s.key), bad);  // (the value in its words, "got -1 s")
      }
  if (batch) {
    if (rs.frames && rs.frames->t_start > rs.t_end)
      throw ParameterError("frames.t_start", "must be <= t_end = " + rounded_text(rs.t_end) + " s (got " +
                                                 rounded_text(rs.frames->t_start) + " s)");
    for (size_t k = 0; k < rs.snapshot_times.size(); ++k)
      if (rs.snapshot_times[k] > rs.t_end)
        throw ParameterError(
            "snapshots.times[" + std::to_string(k + 1) + "]",
            "must be <= t_end = " + rounded_text(rs.t_end) + " s (got " + rounded_text(rs.snapshot_times[k]) + " s)");
  }
  if (rs.check && check_rtol(rs) < kRtolMin)
    throw ParameterError("check", "the companion solution runs at rtol/" + rounded_text(kCheckTighten) +
                                      ", which must be >= " + rounded_text(kRtolMin) + " (got rtol " +
                                      rounded_text(rs.rtol) + ")");
  if (rs.probes.empty()) throw ParameterError("probe", "at least one element to probe");
  for (size_t k = 0; k < rs.probes.size(); ++k)
    if (rs.probes[k] < 0 || rs.probes[k] >= m.n_el())
      throw ParameterError("probe", "the probe element must be in 0.." + std::to_string(m.n_el() - 1) + " (got " +
                                        std::to_string(rs.probes[k]) +
                                        (rs.probes.size() > 1 ? " for probe " + std::to_string(k + 1) : std::string()) +
                                        ")");
  for (size_t k = 0; k < rs.snapshot_times.size(); ++k) {
    const double t = rs.snapshot_times[k];
    if (!(t >= 0 && std::isfinite(t)))
      throw ParameterError("snapshots.times[" + std::to_string(k + 1) + "]",
                           "must be >= 0 s and finite (got " + rounded_text(t) + " s)");
    if (k > 0 && !(t > rs.snapshot_times[k - 1]))
      throw ParameterError("snapshots.times[" + std::to_string(k + 1) + "]",
                           "the times must increase (got " + rounded_text(t) + " s after " +
                               rounded_text(rs.snapshot_times[k - 1]) + " s)");
  }
  if (!(rs.snapshot_every >= 0 && std::isfinite(rs.snapshot_every)))
    throw ParameterError("snapshots.every", "must be > 0 s and finite (got " + rounded_text(rs.snapshot_every) + " s)");
  for (const MuEvent& ev : rs.mu_events) {
    const std::string bad = event_time_problem(ev.t, batch ? rs.t_end : std::numeric_limits<double>::infinity());
    if (!bad.empty()) throw ParameterError("events", "an event's time " + bad);
    if (static_cast<int>(ev.mu.size()) != m.n_el())
      throw ParameterError("events", "an event's μ needs one value per element");
  }
  if (rs.frames) {
    validate(*rs.frames, rs.keep_states);
    if (rs.frames->draws() && !rs.frame_factory)
      throw ParameterError("frames", "asked for, but this program has no renderer");
  }
}

void check_calls(const RunSettings& rs, double t0, double t1, double every_dt) {
  constexpr double kMaxCalls = 1e7;
  const double calls = (t1 - t0) / every_dt;
  if (rs.allow_large || !(calls > kMaxCalls)) return;
  throw ParameterError("every", "a callback every " + rounded_text(every_dt) + " s would be called " +
                                    rounded_text(calls) + " times from " + rounded_text(t0) + " s to " +
                                    rounded_text(t1) + " s; the limit is " + rounded_text(kMaxCalls) +
                                    " calls: call it less often, or set allow_large = true");
}

void check_volume(const Scene& sc, const RunSettings& rs, double t0, double t1) {
  if (rs.allow_large || !(t1 > t0)) return;
  constexpr double kMaxRows = 1e7, kMaxFrames = 1e5;
  const double rows = (t1 - t0) / rs.sample_dt;
  std::ostringstream m;
  if (rows > kMaxRows) {
    const double bytes = rows * static_cast<double>(timeseries_columns(sc, rs.probes.size()).size()) * 13;
    m << rounded_text(t1 - t0) << " s at a sample every " << rounded_text(rs.sample_dt) << " s would write "
      << rounded_text(rows) << " rows (about " << rounded_text(bytes / 1e9) << " GB of timeseries.csv); the limit is "
      << rounded_text(kMaxRows) << " rows: sample less often, or set allow_large = true";
    throw ParameterError("sample", m.str());
  }
  const double snaps =
      static_cast<double>(rs.snapshot_times.size()) + (rs.snapshot_every > 0 ? (t1 - t0) / rs.snapshot_every : 0.0);
  if (snaps * sc.model.n_el() > kMaxRows) {
    m << rounded_text(snaps) << " snapshots of " << sc.model.n_el() << " elements would write "
      << rounded_text(snaps * sc.model.n_el()) << " rows of snapshots.csv; the limit is " << rounded_text(kMaxRows)
      << ": take fewer, or set allow_large = true";
    throw ParameterError("snapshots", m.str());
  }
  if (const std::optional<FrameSettings> f = frame_times(rs)) {
    const double frames = std::max(0.0, t1 - std::max(t0, f->t_start)) / f->frame_dt();
    if (frames > kMaxFrames && f->draws()) {
      m << rounded_text(t1 - t0) << " s at " << rounded_text(f->fps) << " fps and slowdown "
        << rounded_text(f->slowdown) << " would render " << rounded_text(frames) << " frames ("
        << rounded_text(frames / f->fps / 3600) << " h of video); the limit is " << rounded_text(kMaxFrames)
        << ": lower the slowdown, or set allow_large = true";
      throw ParameterError("frames", m.str());
    }
    if (frames > kMaxFrames) {
      m << rounded_text(t1 - t0) << " s at a state every " << rounded_text(f->frame_dt())
        << " s (the frame times) would keep " << rounded_text(frames) << " states; the limit is "
        << rounded_text(kMaxFrames) << ": lower frames.slowdown or frames.fps, or set allow_large = true";
      throw ParameterError("keep_states", m.str());
    }
  }
}

}  // namespace beltsim
