#include "sim/run_settings.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "integrate/integrator.hpp"
#include "integrate/stepper.hpp"
#include "io/number_text.hpp"
#include "scene/scene.hpp"
#include "sim/run_check.hpp"
#include "sim/outputs.hpp"

namespace beltsim {

std::string event_time_problem(double t, double t_end) {
  if (!(t > 0 && std::isfinite(t))) return "must be > 0 s and finite (got " + rounded_text(t) + " s)";
  if (!(t < t_end)) return "must be before t_end = " + rounded_text(t_end) + " s (got " + rounded_text(t) + " s)";
  return "";
}

std::string output_path(const RunSettings& settings, const std::string& path) {
  return (std::filesystem::path(settings.out_dir) / path).string();
}

std::optional<FrameSettings> frame_times(const RunSettings& rs) {
  if (rs.frames) return rs.frames;
  if (rs.keep_states) return FrameSettings{};
  return std::nullopt;
}

std::string out_dir_problem(const std::string& dir) {
  return dir.empty() ? "an empty path (leave it out for out/<script>, or give '.' for the folder beltsim runs in)" : "";
}

void check(const Scene& sc, const RunSettings& rs, bool batch) {
  const Model& m = sc.model;
  if (const std::string bad = out_dir_problem(rs.out_dir); !bad.empty()) throw std::invalid_argument("out: " + bad);
  if (batch) {
    if (!(rs.t_end > 0 && std::isfinite(rs.t_end)))
      throw std::invalid_argument("t_end: must be > 0 s and finite (got " + rounded_text(rs.t_end) + " s)");
    if (rs.frames && rs.frames->t_start > rs.t_end)
      throw std::invalid_argument("frames.t_start: must be <= t_end = " + rounded_text(rs.t_end) + " s (got " +
                                  rounded_text(rs.frames->t_start) + " s)");
    for (size_t k = 0; k < rs.snapshot_times.size(); ++k)
      if (rs.snapshot_times[k] > rs.t_end)
        throw std::invalid_argument("snapshots.times[" + std::to_string(k + 1) + "]: must be <= t_end = " +
                                    rounded_text(rs.t_end) + " s (got " + rounded_text(rs.snapshot_times[k]) + " s)");
  }
  check_integrator(rs.integrator);
  check_tolerances(Tolerances{rs.rtol, rs.atol});
  if (rs.check && check_rtol(rs) < kRtolMin)
    throw std::invalid_argument("check: the companion solution runs at rtol/" + rounded_text(kCheckTighten) +
                                ", which must be >= " +
                                rounded_text(kRtolMin) + " (got rtol " + rounded_text(rs.rtol) + ")");
  if (!(rs.sample_dt > 0 && std::isfinite(rs.sample_dt)))
    throw std::invalid_argument("sample: the sample interval must be > 0 s and finite (got " +
                                rounded_text(rs.sample_dt) + " s)");
  if (rs.probes.empty()) throw std::invalid_argument("probe: at least one element to probe");
  for (size_t k = 0; k < rs.probes.size(); ++k)
    if (rs.probes[k] < 0 || rs.probes[k] >= m.n_el())
      throw std::invalid_argument("probe: the probe element must be in 0.." + std::to_string(m.n_el() - 1) + " (got " +
                                  std::to_string(rs.probes[k]) +
                                  (rs.probes.size() > 1 ? " for probe " + std::to_string(k + 1) : std::string()) + ")");
  for (size_t k = 0; k < rs.snapshot_times.size(); ++k) {
    const double t = rs.snapshot_times[k];
    if (!(t >= 0 && std::isfinite(t)))
      throw std::invalid_argument("snapshots.times[" + std::to_string(k + 1) + "]: must be >= 0 s and finite (got " +
                                  rounded_text(t) + " s)");
    if (k > 0 && !(t > rs.snapshot_times[k - 1]))
      throw std::invalid_argument("snapshots.times[" + std::to_string(k + 1) + "]: the times must increase (got " +
                                  rounded_text(t) + " s after " + rounded_text(rs.snapshot_times[k - 1]) + " s)");
  }
  if (!(rs.snapshot_every >= 0 && std::isfinite(rs.snapshot_every)))
    throw std::invalid_argument("snapshots.every: must be > 0 s and finite (got " + rounded_text(rs.snapshot_every) +
                                " s)");
  for (const MuEvent& ev : rs.mu_events) {
    const std::string bad = event_time_problem(ev.t, batch ? rs.t_end : std::numeric_limits<double>::infinity());
    if (!bad.empty()) throw std::invalid_argument("events: an event's time " + bad);
    if (static_cast<int>(ev.mu.size()) != m.n_el())
      throw std::invalid_argument("events: an event's μ needs one value per element");
  }
  if (rs.frames) {
    validate(*rs.frames, rs.keep_states);
    if (rs.frames->draws() && !rs.frame_factory)
      throw std::invalid_argument("frames: asked for, but this program has no renderer");
  }
}

std::vector<std::string> drop_after_end(RunSettings& rs, const char* shortened_by) {
  std::vector<std::string> notes;
  const std::string end =
      "t_end = " + rounded_text(rs.t_end) + " s" + (shortened_by ? std::string(" (from ") + shortened_by + ")" : "");
  std::vector<MuEvent> kept;
  for (const MuEvent& ev : rs.mu_events) {
    if (event_time_problem(ev.t, rs.t_end).empty() || !event_time_problem(ev.t).empty()) {
      kept.push_back(ev);
      continue;
    }
    notes.push_back("events: the event at " + rounded_text(ev.t) + " s (" + ev.what + ") is at or after " + end +
                    ": skipped");
  }
  rs.mu_events = std::move(kept);
  if (!shortened_by) return notes;
  std::vector<double> times;
  for (double t : rs.snapshot_times) {
    if (t > rs.t_end && std::isfinite(t)) {
      notes.push_back("snapshots: the snapshot at " + rounded_text(t) + " s is after " + end + ": skipped");
      continue;
    }
    times.push_back(t);
  }
  rs.snapshot_times = std::move(times);
  if (rs.frames && rs.frames->t_start > rs.t_end && std::isfinite(rs.frames->t_start)) {
    notes.push_back("frames: they start at " + rounded_text(rs.frames->t_start) + " s, after " + end + ": none drawn" +
                    (rs.keep_states ? " and no states kept" : ""));
    rs.frames.reset();
    rs.keep_states = false;
  }
  return notes;
}

void check_calls(const RunSettings& rs, double t0, double t1, double every_dt) {
  constexpr double kMaxCalls = 1e7;
  const double calls = (t1 - t0) / every_dt;
  if (rs.allow_large || !(calls > kMaxCalls)) return;
  throw std::invalid_argument("every: a callback every " + rounded_text(every_dt) + " s would be called " +
                              rounded_text(calls) + " times from " + rounded_text(t0) + " s to " + rounded_text(t1) +
                              " s; the limit is " + rounded_text(kMaxCalls) +
                              " calls: call it less often, or set allow_large = true");
}

void check_volume(const Scene& sc, const RunSettings& rs, double t0, double t1) {
  if (rs.allow_large || !(t1 > t0)) return;
  constexpr double kMaxRows = 1e7, kMaxFrames = 1e5;
  const double rows = (t1 - t0) / rs.sample_dt;
  std::ostringstream m;
  if (rows > kMaxRows) {
    const double bytes = rows * static_cast<double>(timeseries_columns(sc, rs.probes.size()).size()) * 13;
    m << "sample: " << rounded_text(t1 - t0) << " s at a sample every " << rounded_text(rs.sample_dt)
      << " s would write " << rounded_text(rows) << " rows (about " << rounded_text(bytes / 1e9)
      << " GB of timeseries.csv); the limit is " << rounded_text(kMaxRows)
      << " rows: sample less often, or set allow_large = true";
    throw std::invalid_argument(m.str());
  }
  const double snaps = static_cast<double>(rs.snapshot_times.size()) +
                       (rs.snapshot_every > 0 ? (t1 - t0) / rs.snapshot_every : 0.0);
  if (snaps * sc.model.n_el() > kMaxRows) {
    m << "snapshots: " << rounded_text(snaps) << " snapshots of " << sc.model.n_el() << " elements would write "
      << rounded_text(snaps * sc.model.n_el()) << " rows of snapshots.csv; the limit is " << rounded_text(kMaxRows)
      << ": take fewer, or set allow_large = true";
    throw std::invalid_argument(m.str());
  }
  if (const std::optional<FrameSettings> f = frame_times(rs)) {
    const double frames = std::max(0.0, t1 - std::max(t0, f->t_start)) / f->frame_dt();
    if (frames > kMaxFrames && f->draws()) {
      m << "frames: " << rounded_text(t1 - t0) << " s at " << rounded_text(f->fps) << " fps and slowdown "
        << rounded_text(f->slowdown) << " would render " << rounded_text(frames) << " frames ("
        << rounded_text(frames / f->fps / 3600) << " h of video); the limit is " << rounded_text(kMaxFrames)
        << ": lower the slowdown, or set allow_large = true";
      throw std::invalid_argument(m.str());
    }
    if (frames > kMaxFrames) {
      m << "keep_states: " << rounded_text(t1 - t0) << " s at a state every " << rounded_text(f->frame_dt())
        << " s (the frame times) would keep " << rounded_text(frames) << " states; the limit is "
        << rounded_text(kMaxFrames) << ": lower frames.slowdown or frames.fps, or set allow_large = true";
      throw std::invalid_argument(m.str());
    }
  }
}

}  // namespace beltsim
