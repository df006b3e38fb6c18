#include "sim/run_settings.hpp"

#include <cmath>
#include <filesystem>

#include "io/number_text.hpp"

namespace beltsim {

std::string event_time_problem(double t, double t_end) {
  if (!(t > 0 && std::isfinite(t))) return "must be > 0 s and finite (got " + rounded_text(t) + " s)";
  if (!(t < t_end)) return "must be before t_end = " + rounded_text(t_end) + " s (got " + rounded_text(t) + " s)";
  return "";
}

std::string output_path(const std::string& out_dir, const std::string& path) {
  return (std::filesystem::path(out_dir) / path).string();
}

std::string output_path(const RunSettings& settings, const std::string& path) {
  return output_path(settings.out_dir, path);
}

std::optional<FrameSettings> frame_times(const RunSettings& rs) {
  if (rs.frames) return rs.frames;
  if (rs.keep_states) return FrameSettings{};
  return std::nullopt;
}

std::string out_dir_problem(const std::string& dir) {
  return dir.empty() ? "an empty path (leave it out for out/<script>, or give '.' for the folder beltsim runs in)" : "";
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

std::string sample_warning(const RunSettings& rs, const char* shortened_by) {
  if (!(rs.sample_dt > rs.t_end) || !std::isfinite(rs.t_end)) return "";
  return "run.sample = " + rounded_text(rs.sample_dt) + " s is longer than t_end = " + rounded_text(rs.t_end) + " s" +
         (shortened_by ? std::string(" (from ") + shortened_by + ")" : std::string()) +
         ": timeseries.csv will hold only the row at t = 0 (the interval is in seconds: 1 ms is sample = 0.001)";
}

}  // namespace beltsim
