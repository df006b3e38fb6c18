// `beltsim modes SCRIPT`: the modes of the script's drive about an operating point, or over the
// crankshaft's speed (a Campbell diagram) (commands.hpp, sim/modes.hpp, docs/modes.md).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>

#include "app/commands.hpp"
#include "io/csv_writer.hpp"
#include "io/number_text.hpp"
#include "io/suggest.hpp"
#include "io/output_dir.hpp"
#include "plot/campbell_plot.hpp"
#include "render/mode_frames.hpp"
#include "script/docall.hpp"
#include "script/interpreter.hpp"
#include "script/signals.hpp"
#include "sim/campbell.hpp"
#include "sim/mode_check.hpp"
#include "sim/simulation.hpp"

namespace beltsim::app {

namespace fs = std::filesystem;

using script::stop_flag;
using script::stop_signal;
using script::stopped_status;

namespace {

// "A:B:N": N speeds from A to B evenly spaced (N >= 2), or one speed "A"; each > 0 (the pulley
// turning the way the belt goes round it)
std::vector<double> speeds(const std::string& text) {
  std::vector<std::string> parts;
  std::stringstream in(text);
  for (std::string p; std::getline(in, p, ':');) parts.push_back(p);
  if ((parts.size() != 1 && parts.size() != 3) || text.back() == ':')
    throw UsageError("--rpm takes FROM:TO:COUNT (e.g. 800:6000:14), got '" + text + "'");
  const double a = number("--rpm", parts[0]), b = parts.size() == 1 ? a : number("--rpm", parts[1]);
  const int n = parts.size() == 1 ? 1 : whole_number("--rpm", parts[2], 2);
  if (!(a > 0 && b > 0)) throw UsageError("--rpm takes speeds > 0 rpm, got '" + text + "'");
  std::vector<double> out;
  for (int k = 0; k < n; ++k) out.push_back(n == 1 ? a : a + (b - a) * k / (n - 1));
  return out;
}

std::vector<double> orders(const std::string& text) {
  std::vector<double> out;
  std::stringstream in(text);
  for (std::string p; std::getline(in, p, ',');) {
    const double o = number("--orders", p);
    if (!(o > 0)) throw UsageError("--orders takes positive engine orders (e.g. 2,4), got '" + p + "'");
    out.push_back(o);
  }
  if (out.empty() || text.back() == ',')
    throw UsageError("--orders takes positive engine orders separated by commas (e.g. 2,4), got '" + text + "'");
  return out;
}

void print_table(const Scene& sc, const ModeAnalysis& a) {
  std::printf("t = %s s, belt speed %.3g m/s, %d states: %zu modes\n", number_text(a.t).c_str(), a.belt_speed, a.states,
              a.modes.size());
  std::printf("%5s %10s %8s  %s\n", "mode", "f [Hz]", "zeta", "where the kinetic energy is");
  for (size_t k = 0; k < a.modes.size(); ++k)
    std::printf("%5zu %10.2f %8.4f  %s\n", k + 1, a.modes[k].frequency, a.modes[k].damping,
                where_text(a.groups, a.modes[k].participation).c_str());
  if (a.period == 0) {
    // a drive at rest holds no energy a mode could grow from (but a torque that grows with speed):
    // a negative ζ there is the eigensolver's on a stiff matrix (a user's trial: 300 elements at
    // rest, ζ -0.56 at 84 Hz, which the mode's check in time found at 131 Hz, ζ 0.05)
    std::string growing;
    for (size_t k = 0; k < a.modes.size(); ++k)
      if (a.modes[k].damping < 0) growing += (growing.empty() ? "" : ", ") + std::to_string(k + 1);
    const bool one = growing.find(',') == std::string::npos;
    if (!growing.empty())
      std::fprintf(stderr,
                   "beltsim modes: warning: mode%s %s grow%s (zeta < 0) about a state at rest, which holds no energy "
                   "for a mode to grow from unless a torque grows with its pulley's speed: likely the eigensolver's "
                   "error on this stiff matrix; --check %s integrates %s in time (docs/modes.md)\n",
                   one ? "" : "s", growing.c_str(), one ? "s" : "", growing.c_str(), one ? "it" : "them");
    return;
  }
  // a running belt: the modes of its motion over one element passing (docs/modes.md, A running drive)
  std::printf(
      "modes of the drive's motion over one element passing (%.3g ms, %.4g elements a second); over it the motion "
      "repeats itself within %.2g %% of a pitch and %.2g %% of the belt's speed\n",
      1e3 * a.period, 1 / a.period, 100 * a.position_defect, 100 * a.velocity_defect);
  // modes whose Floquet multiplier is real and negative: at exactly half the passing rate, where
  // the passing locks a mode near it (docs/modes.md, Modes at half the passing rate)
  std::string locked;
  const double half = 0.5 / a.period;
  for (size_t k = 0; k < a.modes.size(); ++k)
    if (std::abs(a.modes[k].frequency - half) <= 1e-9 * half)
      locked += (locked.empty() ? "" : ", ") + std::to_string(k + 1);
  if (!locked.empty())
    std::printf(
        "mode%s %s at half the passing rate, %.2f Hz: a real negative Floquet multiplier (the motion flips "
        "sign from one passing to the next), where the passing locks a mode of the drive near that frequency "
        "(a parametric resonance of the element belt); the drive as modelled rings there, and a belt of more "
        "elements passes faster and frees it (docs/modes.md)\n",
        locked.find(',') == std::string::npos ? "" : "s", locked.c_str(), half);
  if (a.velocity_defect > kSteadyVelocity || a.position_defect > kSteadyPosition)
    std::fprintf(stderr,
                 "beltsim modes: warning: the drive is not steady at t = %s s: over one element passing its motion "
                 "is off its own repeat by %.2g %% of a pitch and %.2g %% of the belt's speed (steady: below %.2g and "
                 "%.2g %%); the modes are those of that passing's motion: take a time where the drive runs steadily "
                 "(docs/modes.md, A running drive)\n",
                 number_text(a.t).c_str(), 100 * a.position_defect, 100 * a.velocity_defect, 100 * kSteadyPosition,
                 100 * kSteadyVelocity);
  if (a.forced >= 0)
    std::fprintf(
        stderr,
        "beltsim modes: warning: the drive is forced at t = %s s: pulley %s's law changes at up to %.2g times its value "
        "a second, so its motion changes from one passing to the next and the modes are those of one "
        "passing's; for the modes at a steady speed take --campbell, which holds the speed steady, or the "
        "scene without its forcing (docs/modes.md, A running drive)\n",
        number_text(a.t).c_str(), sc.model.pulleys[a.forced].name.c_str(), a.forcing_rate);
}

// --check K1,K2: the mode numbers (from 1, as listed), read before the run
std::vector<size_t> check_list(const Raw& raw) {
  std::vector<size_t> ks;
  if (!raw.check) return ks;
  std::stringstream in(*raw.check);
  for (std::string p; std::getline(in, p, ',');) ks.push_back(static_cast<size_t>(whole_number("--check", p, 1)));
  if (ks.empty() || raw.check->back() == ',')
    throw UsageError("--check takes mode numbers separated by commas (e.g. 12,23), got '" + *raw.check + "'");
  return ks;
}

// "A", "A and B", "A, B and C"
std::string and_list(const std::vector<std::string>& names) {
  std::string out;
  for (size_t k = 0; k < names.size(); ++k) out += (k == 0 ? "" : k + 1 == names.size() ? " and " : ", ") + names[k];
  return out;
}

// the options of the form asked for, read and checked before the script runs: the modes of one
// operating point (--at, --shapes, --video, --check) or a Campbell diagram (--campbell with
// --rpm, --orders, --settle)
struct Form {
  std::optional<double> at;  // unset: the run's t_end
  int shapes = 6;
  std::vector<size_t> checks;
  std::vector<double> rpm, orders;
  double settle = CampbellSettings{}.settle;
};

// The options read; an option the form asked for would leave unused is refused, each one given
// named: --rpm, --orders and --settle without --campbell, --at, --shapes, --video and --check
// with it, --video with --shapes 0.
Form read_form(const Raw& raw) {
  Form f;
  if (!raw.campbell) {
    std::vector<std::string> given;
    if (raw.rpm) given.emplace_back("--rpm");
    if (raw.orders) given.emplace_back("--orders");
    if (raw.settle) given.emplace_back("--settle");
    if (!given.empty())
      throw UsageError(and_list(given) + (given.size() == 1 ? " goes" : " go") +
                       " with --campbell PULLEY (a Campbell diagram): the modes of one operating point (--at) do "
                       "not use " +
                       (given.size() == 1 ? "it" : "them"));
    if (raw.at) {
      f.at = number("--at", *raw.at);
      if (!(*f.at >= 0)) throw UsageError("--at must be a time >= 0 [s], got '" + *raw.at + "'");
    }
    if (raw.shapes) f.shapes = whole_number("--shapes", *raw.shapes, 0);
    if (raw.video && f.shapes == 0)
      throw UsageError("--video makes a video of each mode drawn, and --shapes 0 draws none");
    f.checks = check_list(raw);
    return f;
  }
  std::vector<std::string> given, why;
  if (raw.at) given.emplace_back("--at"), why.emplace_back("takes each speed's modes after --settle");
  if (raw.shapes) given.emplace_back("--shapes");
  if (raw.video) given.emplace_back("--video");
  if (raw.shapes || raw.video) why.emplace_back("draws no mode shapes");
  if (raw.check) given.emplace_back("--check"), why.emplace_back("checks no mode in time");
  if (!given.empty())
    throw UsageError(and_list(given) + (given.size() == 1 ? " goes" : " go") +
                     " with the modes of one operating point (--at), not with --campbell: a Campbell diagram " +
                     and_list(why));
  if (!raw.rpm) throw UsageError("--campbell needs --rpm FROM:TO:COUNT");
  f.rpm = speeds(*raw.rpm);
  f.orders = orders(raw.orders.value_or("2,4"));
  if (raw.settle) {
    f.settle = number("--settle", *raw.settle);
    if (!(f.settle > 0)) throw UsageError("--settle must be a time > 0 [s], got '" + *raw.settle + "'");
  }
  return f;
}

// a mode number of --check past the modes listed: refused after the table, before modes.csv and the
// shapes are written
void require_listed(const ModeAnalysis& a, const std::vector<size_t>& ks) {
  for (size_t k : ks)
    if (k > a.modes.size()) {
      std::fflush(stdout);  // the table before the message, in a log of both
      throw UsageError("--check: there is no mode " + std::to_string(k) + " (" + std::to_string(a.modes.size()) +
                       " listed)");
    }
}

// each listed mode pushed and run on (sim/mode_check.hpp)
void check_modes(const Scene& sc, const Drive& d, const Eigen::VectorXd& y, const ModeAnalysis& a,
                 const std::vector<size_t>& ks) {
  std::vector<size_t> index;
  for (size_t k : ks) index.push_back(k - 1);
  const std::vector<ModeCheck> checks = check_modes(sc, d, a.t, y, a, index);
  for (size_t i = 0; i < ks.size(); ++i) {
    const size_t k = ks[i];
    const Mode& m = a.modes[k - 1];
    const ModeCheck& c = checks[i];
    std::printf("check of mode %zu (%.2f Hz, zeta %.4f): pushed and run on, watched at %s: ", k, m.frequency, m.damping,
                c.where.c_str());
    if (std::isnan(c.frequency))
      std::printf("no oscillation between %.3g and %.3g Hz", 0.25 * m.frequency, 4 * m.frequency);
    else
      std::printf("%.2f Hz, zeta %.4f", c.frequency, c.damping);
    std::printf("; off the mode's motion by %.0f %% (RMS) over its first period: %s\n", 100 * c.misfit,
                c.agrees ? "agrees" : "does NOT agree");
  }
}

ModeSettings mode_settings(const Raw& raw) {
  ModeSettings s;
  if (raw.fmin) s.f_min = number("--fmin", *raw.fmin);
  if (raw.fmax) s.f_max = number("--fmax", *raw.fmax);
  if (!(s.f_min >= 0) || !(s.f_max > s.f_min))
    throw UsageError("--fmin must be >= 0 and below --fmax (got " + number_text(s.f_min) + " and " +
                     number_text(s.f_max) + " Hz)");
  return s;
}

int point_modes(const std::string& script, const Scene& sc, RunSettings rs, const Raw& raw, const Form& form,
                const ModeSettings& ms) {
  const double at = form.at.value_or(rs.t_end);
  rs.t_end = at;
  rs.frames.reset();
  Simulation sim(sc, rs);
  sim.run_to(at, &stop_flag());
  if (stop_signal() != 0) return stopped_status();
  const Eigen::VectorXd y = sim.state();
  const Drive d = sim.drive();
  const ModeAnalysis a = analyze_modes(sc, d, sim.now(), y, ms);
  sim.close();
  std::printf("modes of %s\n", script.c_str());
  print_table(sc, a);
  require_listed(a, form.checks);
  const std::string csv = (fs::path(rs.out_dir) / "modes.csv").string();
  {
    CsvWriter w(csv, mode_columns(a));
    for (size_t k = 0; k < a.modes.size(); ++k) w.row(mode_row(a, k));
  }
  std::printf("%s\n", csv.c_str());
  render::ModePictures p;
  p.dir = (fs::path(rs.out_dir) / "shapes").string();
  p.count = form.shapes;
  p.video = raw.video;
  for (const std::string& f : render::draw_modes(sc, d, y, a, p)) std::printf("%s\n", f.c_str());
  check_modes(sc, d, y, a, form.checks);
  return 0;
}

int campbell_modes(const std::string& script, const Scene& sc, const RunSettings& rs, const Raw& raw, const Form& form,
                   const ModeSettings& ms) {
  CampbellSettings cs;
  cs.pulley = sc.find_pulley(*raw.campbell);
  if (cs.pulley < 0) {
    std::vector<std::string> names;
    std::string list;
    for (const Pulley& p : sc.model.pulleys) names.push_back(p.name), list += (list.empty() ? "" : ", ") + p.name;
    throw UsageError("--campbell: the scene has no pulley '" + *raw.campbell + "'" + did_you_mean(*raw.campbell, names) +
                     "; its pulleys: " + list);
  }
  cs.rpm = form.rpm;
  cs.settle = form.settle;
  cs.modes = ms;
  const std::vector<double>& ord = form.orders;
  const std::vector<CampbellPoint> pts = campbell(sc, rs, cs, &stop_flag(), [](const CampbellPoint& p) {
    std::fprintf(stderr, "beltsim modes: %s rpm: %zu modes\n", number_text(p.rpm).c_str(), p.analysis.modes.size());
  });
  if (stop_signal() != 0) return stopped_status();
  const std::string csv = (fs::path(rs.out_dir) / "campbell.csv").string();
  const std::string png = (fs::path(rs.out_dir) / "campbell.png").string();
  write_campbell_csv(pts, csv);
  std::printf("%s\n", csv.c_str());
  try {
    plot::plot_campbell_png(
        pts, ord, "Campbell diagram of " + fs::path(script).filename().string() + " over '" + *raw.campbell + "' speed",
        *raw.campbell, png);
    std::printf("%s\n", png.c_str());
  } catch (const std::exception& e) {  // the CSV is the result; the picture is a convenience
    std::fprintf(stderr, "beltsim modes: no plot: %s\n", e.what());
    mark_output_failure_shown(e.what());
  }
  return 0;
}

}  // namespace

int cmd_modes(const std::string& script, const script::Overrides& o, const script::Safety& s, const Raw& raw) {
  try {
    const ModeSettings ms = mode_settings(raw);
    const Form form = read_form(raw);
    script::Interpreter lua(s);
    const script::Interruptible on_signal(lua);
    const script::Captured cap = capture_first_run(lua, script, o, "modes", false);
    RunSettings rs = cap.settings;
    rs.out_dir = o.has("out") ? o.run.out_dir : (fs::path(script::default_out_dir(script)) / "modes").string();
    if (raw.campbell) return campbell_modes(script, *cap.scene, rs, raw, form, ms);
    return point_modes(script, *cap.scene, rs, raw, form, ms);
  } catch (const UsageError&) {
    throw;
  } catch (const script::ScriptError& e) {
    std::fprintf(stderr, "beltsim: %s\n%s", e.what(), script::shown_traceback(e.traceback).c_str());
    return stop_signal() != 0 ? stopped_status() : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "beltsim: %s\n", e.what());
    mark_output_failure_shown(e.what());
    return stop_signal() != 0 ? stopped_status() : 1;
  }
}

}  // namespace beltsim::app
