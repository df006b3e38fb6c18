// The one check of a run's settings and the limits on what a run writes (sim/settings_check.hpp).
#include "sim/settings_check.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "integrate/integrator.hpp"
#include "io/number_text.hpp"
#include "io/suggest.hpp"
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

namespace {

// The bytes a value of timeseries.csv and snapshots.csv takes with its comma, in motion: 15.7 to 17.0
// (the file's bytes over its rows and columns) in 30 runs of four scenes (scripts/paper_dry.lua,
// serpentine.lua, per_length_dry.lua at 60 to 10000 elements, fine_belt_window.lua), 0.1 to 100 s:
// most are 17 significant digits ("-68.83646674077144,"), a few short (0, nan, a μ of 1, a torque
// of -70). The first row, at rest, is no measure of the rest: 249 bytes where the rows in motion
// take 612 (per_length_dry.lua). A row of snapshots.csv holds 8 such values besides its time,
// element, pulley and state (131 bytes measured on the paper's drive).
constexpr double kValueBytes = 17;
constexpr double kSnapshotValues = 8;

// a size for a message, to two significant digits or the whole units: "629 bytes", "250 kB",
// "2.2 MB", "6.2 GB", "1234 GB"
std::string size_text(double bytes) {
  if (bytes < 1e3) return rounded_text(std::round(bytes)) + " bytes";
  const double scale = bytes < 1e6 ? 1e3 : bytes < 1e9 ? 1e6 : 1e9;
  const double x = bytes / scale;
  const int whole = x < 1 ? 1 : static_cast<int>(std::floor(std::log10(x))) + 1;
  return rounded_text(x, std::max(2, whole)) + (scale == 1e3 ? " kB" : scale == 1e6 ? " MB" : " GB");
}

}  // namespace

OutputVolume output_volume(const Scene& sc, const RunSettings& rs, double t0, double t1, double state_bytes) {
  OutputVolume v;
  if (!(t1 > t0)) return v;
  v.rows = (t1 - t0) / rs.sample_dt;
  v.row_bytes = static_cast<double>(timeseries_columns(sc, rs.probes.size()).size()) * kValueBytes;
  const double snaps = static_cast<double>(std::count_if(rs.snapshot_times.begin(), rs.snapshot_times.end(),
                                                         [&](double t) { return t >= t0 && t <= t1; })) +
                       (rs.snapshot_every > 0 ? (t1 - t0) / rs.snapshot_every : 0.0);
  v.snapshot_rows = snaps * sc.model.n_el();
  v.snapshot_row_bytes = kSnapshotValues * kValueBytes;
  if (const std::optional<FrameSettings> f = frame_times(rs); f && rs.keep_states) {
    v.states = std::max(0.0, t1 - std::max(t0, f->t_start)) / f->frame_dt();
    v.state_bytes = state_bytes;
  }
  return v;
}

std::string volume_warning(const OutputVolume& v, double t1, double written, double free, const std::string& out_dir) {
  const double more = v.bytes(), total = written + more;
  const bool large = total > kLargeOutputs, no_room = free >= 0 && more > free;
  if (!large && !no_room) return "";
  std::vector<std::string> parts, fewer;
  if (v.rows * v.row_bytes > 0.01 * more) {
    parts.push_back("timeseries.csv: " + rounded_text(std::round(v.rows)) + " rows of about " + size_text(v.row_bytes));
    fewer.push_back("sample less often (sample)");
  }
  if (v.snapshot_rows * v.snapshot_row_bytes > 0.01 * more) {
    parts.push_back("snapshots.csv: " + rounded_text(std::round(v.snapshot_rows)) + " rows of about " +
                    size_text(v.snapshot_row_bytes));
    fewer.push_back("take fewer snapshots");
  }
  if (v.states * v.state_bytes > 0.01 * more) {
    parts.push_back("states/: " + rounded_text(std::round(v.states)) + " kept states of about " +
                    size_text(v.state_bytes));
    fewer.push_back("keep fewer states (frames.fps, frames.slowdown)");
  }
  std::string m = "the outputs in " + out_dir + " will grow by about " + size_text(more) +
                  " by t = " + rounded_text(t1) + " s (" + join(parts, "; ") + ")";
  if (large)
    m += (written > 0.01 * total ? ", to about " + size_text(total) : std::string()) + ", past " +
         size_text(kLargeOutputs) + ": if that is more than meant, stop the run (Ctrl-C) and " + or_list(fewer);
  if (no_room)
    m += std::string(large ? "; and that is" : ": that is") + " more than the " + size_text(free) +
         " free on the file system that holds it: the run will stop with an error when the disk is full (the "
         "outputs up to then kept); give it a folder with room (--out, out = ...) or free some space";
  return m;
}

void check_volume(const Scene& sc, const RunSettings& rs, double t0, double t1) {
  if (rs.allow_large || !(t1 > t0)) return;
  constexpr double kMaxRows = 1e7, kMaxFrames = 1e5;
  const OutputVolume v = output_volume(sc, rs, t0, t1);
  std::ostringstream m;
  if (v.rows > kMaxRows) {
    m << rounded_text(t1 - t0) << " s at a sample every " << rounded_text(rs.sample_dt) << " s would write "
      << rounded_text(v.rows) << " rows (about " << size_text(v.rows * v.row_bytes)
      << " of timeseries.csv); the limit is " << rounded_text(kMaxRows)
      << " rows: sample less often, or set allow_large = true";
    throw ParameterError("sample", m.str());
  }
  if (v.snapshot_rows > kMaxRows) {
    m << rounded_text(v.snapshot_rows / sc.model.n_el()) << " snapshots of " << sc.model.n_el()
      << " elements would write " << rounded_text(v.snapshot_rows) << " rows of snapshots.csv; the limit is "
      << rounded_text(kMaxRows) << ": take fewer, or set allow_large = true";
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
