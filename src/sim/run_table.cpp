#include "sim/run_table.hpp"

#include <cmath>
#include <limits>

#include "integrate/integrator.hpp"
#include "integrate/stepper.hpp"
#include "io/number_text.hpp"
#include "sim/run_settings.hpp"

namespace beltsim {

namespace {

using RK = RunKind;
constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
constexpr unsigned kBoth = kRunKey | kStartKey;

std::string positive_seconds(double v) {
  return v > 0 && std::isfinite(v) ? "" : "must be > 0 s and finite (got " + rounded_text(v) + " s)";
}

std::string probe_text(const RunSettings& rs) {
  std::string t;
  for (int p : rs.probes) t.append(t.empty() ? "" : " ").append(std::to_string(p));
  return t;
}

std::string snapshots_text(const RunSettings& rs) {
  if (rs.snapshot_times.empty() && rs.snapshot_every == 0) return "none";
  std::string t;
  if (rs.snapshot_every > 0) t = "every " + number_text(rs.snapshot_every) + " s";
  if (!rs.snapshot_times.empty()) {
    t.append(t.empty() ? "at" : "; at");
    for (double x : rs.snapshot_times) t.append(" ").append(number_text(x));
    t.append(" s");
  }
  return t;
}

std::string events_text(const RunSettings& rs) {
  std::string t = std::to_string(rs.mu_events.size());
  return t.append(rs.mu_events.size() == 1 ? " event" : " events").append(rs.mu_events.empty() ? "" : " (events.csv)");
}

std::string frames_text(const RunSettings& rs) {
  if (!rs.frames) return "none";
  const FrameSettings& f = *rs.frames;
  std::string t =
      number_text(f.fps) + " fps, slowdown " + number_text(f.slowdown) + ", from " + number_text(f.t_start) + " s";
  if (!f.png_dir.empty()) t.append(", png ").append(f.png_dir);
  if (!f.video_path.empty()) t.append(", video ").append(f.video_path);
  return t;
}

// the absolute tolerance the run uses (rtol when none was given)
std::string atol_text(const RunSettings& rs) {
  return number_text(Tolerances{rs.rtol, rs.atol}.absolute());
}

// The table. A setting the command line overrides has its option; one a checkpoint does not keep
// says why in its note.
// clang-format off
const RunSetting kRunSettings[] = {
    {"t_end", RK::number, "s", "`1`", kRunKey, "--t-end", "the end of a batch run",
     [](RunSettings& rs) -> RunSlot { return &rs.t_end; }, kNone, positive_seconds, nullptr, nullptr},
    {"integrator", RK::text, "", "`\"trbdf2\"`", kBoth | kSaved, "--integrator",
     "one of beltsim.integrators() (docs/integration.md)",
     [](RunSettings& rs) -> RunSlot { return &rs.integrator; }, kNone, nullptr, integrator_problem, nullptr},
    {"rtol", RK::number, "", "`1e-4`", kBoth | kSaved, "--rtol", "relative tolerance of the error control, in [1e-12, 1)",
     [](RunSettings& rs) -> RunSlot { return &rs.rtol; }, kNone, rtol_problem, nullptr, nullptr},
    {"atol", RK::number, "", "rtol", kBoth | kSaved, "",
     "absolute tolerance per natural size of each component (parameters.csv gives the one used)",
     [](RunSettings& rs) -> RunSlot { return &rs.atol; }, Tolerances::kAtolUnset, atol_problem, nullptr, atol_text},
    {"sample", RK::number, "s", "`1e-3`", kBoth | kSaved, "",
     "interval of the rows of timeseries.csv (steps end on them while they are at most half of it); a batch run "
     "whose `t_end` is shorter is warned of before it runs (its timeseries.csv holds only the row at t = 0)",
     [](RunSettings& rs) -> RunSlot { return &rs.sample_dt; }, kNone, positive_seconds, nullptr, nullptr},
    {"out", RK::text, "", "`\"out/<script>\"`", kBoth | kSaved, "--out", "the output folder",
     [](RunSettings& rs) -> RunSlot { return &rs.out_dir; }, kNone, nullptr, out_dir_problem, nullptr},
    {"probe", RK::other, "", "`0`", kBoth | kSaved, "",
     "the probed elements: an element number, a point {x, y} or a list of them (columns probe.*)",
     nullptr, kNone, nullptr, nullptr, probe_text},
    {"snapshots", RK::other, "s", "none", kBoth | kSaved, "",
     "`{ times = {...}, every = dt }`: every element at those times (snapshots.csv)",
     nullptr, kNone, nullptr, nullptr, snapshots_text},
    {"keep_samples", RK::flag, "", "`false`", kSaved, "",
     "keep the rows of timeseries.csv in memory (beltsim wp sets it; no key of a script's)",
     [](RunSettings& rs) -> RunSlot { return &rs.keep_samples; }, kNone, nullptr, nullptr, nullptr},
    {"progress", RK::flag, "", "`true`", kBoth, "",
     "the progress line on stderr and the closing line of scene:run and of sim:close() (not kept: beltsim.resume "
     "takes its own)",
     [](RunSettings& rs) -> RunSlot { return &rs.progress; }, kNone, nullptr, nullptr, nullptr},
    {"events", RK::other, "", "none", kRunKey, "",
     "μ changed at known times (a live simulation's are in its state, sim:wet)",
     nullptr, kNone, nullptr, nullptr, events_text},
    {"max_wall", RK::number, "s", "none", kBoth, "--max-wall",
     "wall-time limit of each integration call (not kept: a resumed simulation gets resume's own or --max-wall)",
     [](RunSettings& rs) -> RunSlot { return &rs.wall_limit; }, 0, positive_seconds, nullptr, nullptr},
    {"check", RK::flag, "", "`false`", kBoth, "--check",
     "estimate the run's own error against a companion at rtol/10 (not kept: a resumed run is not checked)",
     [](RunSettings& rs) -> RunSlot { return &rs.check; }, kNone, nullptr, nullptr, nullptr},
    {"allow_large", RK::flag, "", "`false`", kBoth | kSaved, "", "past the output limits (1e7 rows, 1e5 frames or states)",
     [](RunSettings& rs) -> RunSlot { return &rs.allow_large; }, kNone, nullptr, nullptr, nullptr},
    {"keep_states", RK::flag, "", "`false`", kBoth | kSaved, "",
     "keep the whole state at each frame time (states/state_NNNNN.ckpt)",
     [](RunSettings& rs) -> RunSlot { return &rs.keep_states; }, kNone, nullptr, nullptr, nullptr},
    {"frames", RK::other, "", "none", kBoth | kSaved, "",
     "PNG frames and/or video (docs/frames-and-video.md)", nullptr, kNone, nullptr, nullptr, frames_text},
};
// clang-format on

}  // namespace

RunSlot run_slot(const RunSetting& s, const RunSettings& rs) {
  // the accessor takes a mutable reference; it only takes an address here
  return s.slot ? s.slot(const_cast<RunSettings&>(rs)) : RunSlot{};
}

std::span<const RunSetting> run_settings() {
  return kRunSettings;
}

const RunSetting* find_run_setting(std::string_view key) {
  for (const RunSetting& s : kRunSettings)
    if (s.key == key) return &s;
  return nullptr;
}

std::vector<std::string> run_keys(bool batch) {
  std::vector<std::string> out;
  for (const RunSetting& s : kRunSettings)
    if (s.where & (batch ? kRunKey : kStartKey)) out.emplace_back(s.key);
  return out;
}

std::string run_value_text(const RunSetting& s, const RunSettings& rs) {
  if (s.csv) return s.csv(rs);
  const RunSlot v = run_slot(s, rs);
  // a number at its "not given" value reads as the docs' default (max_wall's 0: "none", not 0 s)
  if (auto* x = std::get_if<double*>(&v)) return **x == s.unset ? std::string(s.fallback) : value_text(**x);
  if (auto* b = std::get_if<bool*>(&v)) return **b ? "1" : "0";
  if (auto* t = std::get_if<std::string*>(&v)) return **t;
  return "";
}

std::string run_problem(const RunSetting& s, const RunSettings& rs, bool given) {
  const RunSlot v = run_slot(s, rs);
  if (auto* x = std::get_if<double*>(&v); x && s.number_problem && (given || !(**x == s.unset)))
    return s.number_problem(**x);
  if (auto* t = std::get_if<std::string*>(&v); t && s.text_problem) return s.text_problem(**t);
  return "";
}

void copy_run_setting(const RunSetting& s, const RunSettings& from, RunSettings& to) {
  const RunSlot a = run_slot(s, from), b = run_slot(s, to);
  if (auto* x = std::get_if<double*>(&a)) **std::get_if<double*>(&b) = **x;
  if (auto* f = std::get_if<bool*>(&a)) **std::get_if<bool*>(&b) = **f;
  if (auto* t = std::get_if<std::string*>(&a)) **std::get_if<std::string*>(&b) = **t;
}

std::string run_settings_markdown() {
  std::string md =
      "| key | unit | default | in | command line | checkpoint | meaning |\n|---|---|---|---|---|---|---|\n";
  for (const RunSetting& s : kRunSettings) {
    const char* in = (s.where & kRunKey) && (s.where & kStartKey) ? "run, start" : (s.where & kRunKey) ? "run" : "—";
    md.append("| `").append(s.key).append("` | ").append(s.unit.empty() ? "—" : s.unit);
    md.append(" | ").append(s.fallback).append(" | ").append(in).append(" | ");
    if (s.option.empty())
      md.append("—");
    else
      md.append("`").append(s.option).append("`");
    md.append(" | ").append(s.where & kSaved ? "kept" : "—").append(" | ").append(s.note).append(" |\n");
  }
  return md;
}

}  // namespace beltsim
