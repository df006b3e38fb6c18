// The review figures of a run's outputs over a window (summary.hpp); the table, the CSV and the
// plot are in summary_report.cpp.
#include "plot/summary.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "io/csv_writer.hpp"
#include "io/input_file.hpp"
#include "io/number_text.hpp"
#include "plot/plot.hpp"

namespace beltsim::plot {

namespace {

namespace fs = std::filesystem;

// parameters.csv's values by name (`name,value,unit,source,note`)
struct Parameters {
  std::string path;
  std::map<std::string, std::string> values, notes;
  double number(const std::string& name) const {
    const auto it = values.find(name);
    if (it == values.end()) throw std::runtime_error(path + " has no row '" + name + "'");
    const std::optional<double> v = parse_number(it->second);
    if (!v) throw std::runtime_error(path + ": " + name + " is not a number: '" + it->second + "'");
    return *v;
  }
};

Parameters read_parameters(const std::string& path) {
  Parameters p{path, {}, {}};
  std::string text;
  try {
    InputFile f(path);
    text = f.read_rest();
  } catch (const InputFileError& e) {
    throw std::runtime_error(e.what());
  }
  const std::vector<std::vector<std::string>> rows = csv_rows(text);
  if (rows.empty() || rows[0].size() < 2 || rows[0][0] != "name" || rows[0][1] != "value")
    throw std::runtime_error(path + ":1: not a parameters.csv (its header must start name,value)");
  for (size_t k = 1; k < rows.size(); ++k)
    if (rows[k].size() >= 2) {
      p.values[rows[k][0]] = rows[k][1];
      if (rows[k].size() >= 5) p.notes[rows[k][0]] = rows[k][4];
    }
  return p;
}

struct Stats {
  double mean = NAN, min = NAN, max = NAN;
};

// over the finite values of c in rows [r0, r1); the mean clamped into [min, max], where rounding of
// the sum can leave it (three 0.8s: 0.8000000000000002)
Stats stats(const std::vector<double>& c, size_t r0, size_t r1) {
  Stats s;
  double sum = 0;
  size_t n = 0;
  for (size_t r = r0; r < r1; ++r) {
    if (!std::isfinite(c[r])) continue;
    sum += c[r], ++n;
    s.min = n == 1 ? c[r] : std::min(s.min, c[r]);
    s.max = n == 1 ? c[r] : std::max(s.max, c[r]);
  }
  if (n) s.mean = std::clamp(sum / static_cast<double>(n), s.min, s.max);
  return s;
}

struct Window {
  const Table& t;
  size_t r0, r1;  // the rows [r0, r1) with from <= t <= to
  Stats of(const std::string& column) const { return stats(t.column(column), r0, r1); }
  const std::vector<double>& time() const { return t.column("t"); }
};

// the pulleys in the CSV's order (their `<name>.omega` columns) and the spans as (from, to) pairs
// of them: span_<a>_<b> split where both halves are pulleys' names
struct Layout {
  std::vector<std::string> pulleys;
  std::vector<std::pair<std::string, std::string>> spans;
};

Layout layout(const Table& t) {
  Layout l;
  const std::string omega = ".omega", tension = ".tension";
  auto ends = [](const std::string& s, const std::string& e) {
    return s.size() > e.size() && s.compare(s.size() - e.size(), e.size(), e) == 0;
  };
  for (const std::string& n : t.names)
    if (ends(n, omega)) l.pulleys.push_back(n.substr(0, n.size() - omega.size()));
  for (const std::string& n : t.names) {
    if (n.rfind("span_", 0) != 0 || !ends(n, tension)) continue;
    const std::string ab = n.substr(5, n.size() - 5 - tension.size());
    for (const std::string& a : l.pulleys) {
      if (ab.rfind(a + "_", 0) != 0) continue;
      const std::string b = ab.substr(a.size() + 1);
      if (std::find(l.pulleys.begin(), l.pulleys.end(), b) != l.pulleys.end()) l.spans.push_back({a, b});
    }
  }
  return l;
}

std::string span_name(const std::pair<std::string, std::string>& s) {
  return "span_" + s.first + "_" + s.second;
}

// the intervals of the window where x < 0, their ends interpolated linearly between samples
std::vector<std::pair<double, double>> negative_intervals(const std::vector<double>& t, const std::vector<double>& x,
                                                          size_t r0, size_t r1) {
  std::vector<std::pair<double, double>> out;
  bool in = false;
  double start = 0;
  for (size_t r = r0; r < r1; ++r) {
    const bool neg = x[r] < 0;
    if (neg == in) continue;
    // the crossing between the samples r - 1 and r (at the window's first sample: there)
    double at = t[r];
    if (r > r0 && std::isfinite(x[r - 1]) && std::isfinite(x[r]) && x[r - 1] != x[r])
      at = t[r - 1] + (t[r] - t[r - 1]) * x[r - 1] / (x[r - 1] - x[r]);
    if (neg) {
      start = at;
    } else {
      out.push_back({start, at});
    }
    in = neg;
  }
  if (in) out.push_back({start, t[r1 - 1]});
  return out;
}

void add(Summary& s, const std::string& section, const std::string& item, const std::string& quantity, double v,
         const std::string& unit) {
  s.figures.push_back({section, item, quantity, v, unit});
}

void add_count(Summary& s, const std::string& section, const std::string& item, const std::string& quantity, size_t n) {
  s.figures.push_back({section, item, quantity, static_cast<double>(n), "", true});
}

// the loss channels' power over the window, when the run tracked them
void add_losses(Summary& s, const Window& w, const Layout& l) {
  const char* channels[] = {"axial", "bending", "contact", "friction"};
  for (const char* c : channels)
    if (!w.t.has(std::string("energy.dissipated_") + c)) return;
  if (!w.t.has("energy.mechanical")) return;
  s.losses = true;
  const std::vector<double>& t = w.time();
  const double span = t[w.r1 - 1] - t[w.r0];
  double total = 0;
  auto channel = [&](const char* c) {
    const std::vector<double>& e = w.t.column(std::string("energy.dissipated_") + c);
    const double p = span > 0 ? (e[w.r1 - 1] - e[w.r0]) / span : NAN;
    total += p;
    add(s, "loss", "", c, p, "W");
  };
  for (const char* c : channels) channel(c);
  // the tensioner arms' and the couplings' own losses, where the drive has them
  for (const char* c : {"arms", "couplings"})
    if (w.t.has(std::string("energy.dissipated_") + c)) channel(c);
  add(s, "loss", "", "total", total, "W");
  // each pulley's mean power M·ω over the window (ω the rotor's where coupled): per interval
  // between samples its `torque_mean` (the exact mean over the interval, which a kinematic
  // driver's sampled torque aliases) or, in a run without that column, the mean of the interval's
  // two sampled torques, times the mean of its two speeds. The pulleys that put power in on the
  // mean are the drivers (input), those that take it out the loads (output): input − output =
  // total + stored, stored the change of the mechanical energy over the window / its duration
  double input = 0, output = 0;
  for (const std::string& p : l.pulleys) {
    const std::vector<double>& omega = w.t.column(w.t.has(p + ".rotor_speed") ? p + ".rotor_speed" : p + ".omega");
    const std::vector<double>& torque = w.t.column(p + ".torque");
    const std::vector<double>* mean = w.t.has(p + ".torque_mean") ? &w.t.column(p + ".torque_mean") : nullptr;
    double work = 0;
    for (size_t r = w.r0 + 1; r < w.r1; ++r) {
      const double m = mean ? (*mean)[r] : (torque[r - 1] + torque[r]) / 2;
      work += m * (omega[r - 1] + omega[r]) / 2 * (t[r] - t[r - 1]);
    }
    const double power = span > 0 ? work / span : NAN;
    if (power > 0) input += power;
    if (power < 0) output -= power;
  }
  if (!(span > 0)) input = output = NAN;  // a window of one sample
  add(s, "loss", "", "input", input, "W");
  add(s, "loss", "", "output", output, "W");
  const std::vector<double>& mechanical = w.t.column("energy.mechanical");
  const double stored = span > 0 ? (mechanical[w.r1 - 1] - mechanical[w.r0]) / span : NAN;
  add(s, "loss", "", "stored", stored, "W");
  s.imbalance = input - output - (total + stored);
  add(s, "loss", "", "share", input > 0 ? total / input : NAN, "");
}

// the states a script set in (t0, t1], from DIR/events.csv (none without it): a speed law's jump
// (`<pulley>.speed`), an arm's or a rotor's state (`.arm`, `.rotor`); a user's trial read the
// energy a set_speed put in as the tolerance's imbalance, as the table then said
std::vector<std::string> state_jumps(const std::string& dir, double t0, double t1) {
  std::vector<std::string> out;
  std::ifstream f(std::filesystem::path(dir) / "events.csv");
  std::string line;
  std::getline(f, line);  // the header
  while (std::getline(f, line)) {
    const size_t a = line.find(','), b = a == std::string::npos ? a : line.find(',', a + 1);
    if (b == std::string::npos) continue;
    const std::string what = line.substr(a + 1, b - a - 1);
    char* end = nullptr;
    const double t = std::strtod(line.c_str(), &end);
    if (end != line.c_str() + a || !(t > t0 && t <= t1)) continue;
    for (const char* kind : {".speed", ".arm", ".rotor"})
      if (what.size() > std::string(kind).size() &&
          what.compare(what.size() - std::string(kind).size(), std::string::npos, kind) == 0)
        out.push_back(what + " at t = " + rounded_text(t, 6) + " s");
  }
  return out;
}

// the wrap's capstan margin at each sample of the window: e^{μθ} against (T1 − m'v²)/(T2 − m'v²),
// μ the mean μ of the elements on the wrap then (`<p>.mu`: a wetted stretch moves through the
// wrap), T1 ≥ T2 the tensions of the spans either side and v the belt's speed then; NaN where no
// element touches the pulley. Its minimum and mean over the window are the review's figures.
std::vector<double> capstan_margins(const Window& w, const std::vector<double>& mu, const std::vector<double>& a,
                                    const std::vector<double>& b, const std::vector<double>& speed, double mass,
                                    double theta) {
  std::vector<double> margin(w.r1 - w.r0, NAN);
  for (size_t r = w.r0; r < w.r1; ++r) {
    const double t1 = std::max(a[r], b[r]), t2 = std::min(a[r], b[r]), c = mass * speed[r] * speed[r];
    const double ratio = t2 - c > 0 ? (t1 - c) / (t2 - c) : INFINITY;
    if (std::isfinite(mu[r])) margin[r - w.r0] = std::exp(mu[r] * theta) / ratio;
  }
  return margin;
}

// each pulley's wrap: the measured slip arc, the capstan ratio of the spans either side against
// e^{μθ}, and the hub load against the span tensions' resultant
void add_wraps(Summary& s, const Window& w, const Layout& l, const Parameters& prm, const std::vector<double>& speed,
               double belt_speed) {
  const double mass = prm.number("belt.mass_per_length");
  const double centrifugal = mass * belt_speed * belt_speed;
  for (const std::string& p : l.pulleys) {
    const double theta = prm.number("pulley." + p + ".wrap_angle") * M_PI / 180;
    std::string in, out;  // the spans that run onto and off the pulley
    for (const auto& sp : l.spans) {
      if (sp.second == p) in = span_name(sp);
      if (sp.first == p) out = span_name(sp);
    }
    const std::vector<double> none(w.time().size(), NAN);  // a pulley whose span names are not found
    const std::vector<double>& a = in.empty() ? none : w.t.column(in + ".tension");
    const std::vector<double>& b = out.empty() ? none : w.t.column(out + ".tension");
    const double t_in = stats(a, w.r0, w.r1).mean, t_out = stats(b, w.r0, w.r1).mean;
    const double t1 = std::max(t_in, t_out), t2 = std::min(t_in, t_out);
    const double ratio = t2 - centrifugal > 0 ? (t1 - centrifugal) / (t2 - centrifugal) : INFINITY;
    // a run written before the wraps' μ was a column: the belt's least μ at its start, throughout
    std::vector<double> start_mu;
    if (!s.mu_per_sample) start_mu.assign(w.time().size(), prm.number("belt.mu_min"));
    const std::vector<double>& mu_t = s.mu_per_sample ? w.t.column(p + ".mu") : start_mu;
    const Stats mu = stats(mu_t, w.r0, w.r1);
    const std::vector<double> margins = capstan_margins(w, mu_t, a, b, speed, mass, theta);
    const Stats margin = stats(margins, 0, margins.size());
    const std::vector<double>& slip = w.t.column(p + ".slip_arc");
    const std::vector<double>& contact = w.t.column(p + ".contact_arc");
    double worst = 0;
    for (size_t r = w.r0; r < w.r1; ++r)
      if (contact[r] > 0) worst = std::max(worst, slip[r] / contact[r]);
    const double contact_mean = w.of(p + ".contact_arc").mean;
    add(s, "wraps", p, "wrap", theta, "rad");
    add(s, "wraps", p, "mu", mu.mean, "");
    add(s, "wraps", p, "mu_min", mu.min, "");
    add(s, "wraps", p, "slip_arc_share", contact_mean > 0 ? w.of(p + ".slip_arc").mean / contact_mean : NAN, "");
    add(s, "wraps", p, "slip_arc_share_max", worst, "");
    add(s, "wraps", p, "slip_arc_share_capstan", std::log(ratio) / (mu.mean * theta), "");
    add(s, "wraps", p, "capstan_ratio", ratio, "");
    add(s, "wraps", p, "capstan_limit", std::exp(mu.mean * theta), "");
    add(s, "wraps", p, "capstan_margin", margin.min, "");
    add(s, "wraps", p, "capstan_margin_mean", margin.mean, "");
    const Stats hub = w.of(p + ".hub_load");
    add(s, "hubs", p, "hub_load_mean", hub.mean, "N");
    add(s, "hubs", p, "hub_load_max", hub.max, "N");
    // the wrap presses on the hub with its spans' tensions less the centrifugal m'v² each: the
    // belt running round the wrap takes m'v² of its tension to turn its own mass (a tension that
    // does not press it onto the pulley), so the contact forces sum to the resultant of T − m'v²
    const double f1 = t1 - centrifugal, f2 = t2 - centrifugal;
    add(s, "hubs", p, "hub_load_spans", std::sqrt(f1 * f1 + f2 * f2 - 2 * f1 * f2 * std::cos(theta)), "N");
  }
}

void add_arms_and_rotors(Summary& s, const Window& w, const Layout& l) {
  for (const std::string& p : l.pulleys) {
    if (!w.t.has(p + ".arm_angle")) continue;
    const Stats a = w.of(p + ".arm_angle"), rate = w.of(p + ".arm_rate");
    add(s, "arms", p, "arm_angle_mean", a.mean, "rad");
    add(s, "arms", p, "arm_angle_min", a.min, "rad");
    add(s, "arms", p, "arm_angle_max", a.max, "rad");
    add(s, "arms", p, "arm_angle_swing", a.max - a.min, "rad");
    add(s, "arms", p, "arm_rate_peak", std::max(std::abs(rate.min), std::abs(rate.max)), "rad/s");
  }
  for (const std::string& p : l.pulleys) {
    if (!w.t.has(p + ".rotor_speed")) continue;
    const double sense = w.of(p + ".omega").mean < 0 ? -1 : 1;
    const std::vector<double>& torque = w.t.column(p + ".coupling_torque");
    std::vector<double> x(torque.size());
    for (size_t r = 0; r < x.size(); ++r) x[r] = sense * torque[r];
    Overrun o{p, negative_intervals(w.time(), x, w.r0, w.r1)};
    double total = 0, longest = 0;
    for (const auto& [a, b] : o.intervals) total += b - a, longest = std::max(longest, b - a);
    add(s, "rotors", p, "rotor_speed_mean", w.of(p + ".rotor_speed").mean, "rad/s");
    add_count(s, "rotors", p, "overrun_count", o.intervals.size());
    add(s, "rotors", p, "overrun_time", total, "s");
    add(s, "rotors", p, "overrun_longest", longest, "s");
    s.overruns.push_back(std::move(o));
  }
}

}  // namespace

Summary summarize(const std::string& dir, double from, double to) {
  if (!(from <= to)) {
    std::ostringstream m;
    m << "summary: the window's start " << from << " s lies after its end " << to << " s";
    throw std::runtime_error(m.str());
  }
  Summary s;
  s.dir = dir;
  const Table table = read_timeseries_csv((fs::path(dir) / "timeseries.csv").string());
  const Parameters prm = read_parameters((fs::path(dir) / "parameters.csv").string());
  if (const auto it = prm.values.find("run.integrator"); it != prm.values.end()) s.integrator = it->second;
  if (const auto it = prm.values.find("end.status"); it != prm.values.end()) {
    s.end_status = it->second;
    if (const auto n = prm.notes.find("end.status"); n != prm.notes.end()) s.end_note = n->second;
  }
  const std::vector<double>& t = table.column("t");
  size_t r0 = 0;
  while (r0 < t.size() && t[r0] < from) ++r0;
  size_t r1 = r0;
  while (r1 < t.size() && t[r1] <= to) ++r1;
  if (r1 == r0) {
    std::ostringstream m;
    m << table.path << " has no samples with ";
    if (std::isinf(to))
      m << "t >= " << from << " s";
    else if (std::isinf(from))
      m << "t <= " << to << " s";
    else
      m << "t in [" << from << ", " << to << "] s";
    if (t.empty())
      m << " (it has no rows)";
    else
      m << " (its samples run from t = " << t.front() << " to " << t.back() << " s)";
    throw std::runtime_error(m.str());
  }
  const Window w{table, r0, r1};
  const Layout l = layout(table);
  if (l.pulleys.empty()) throw std::runtime_error(table.path + " has no <pulley>.omega column");
  s.mu_per_sample = table.has(l.pulleys[0] + ".mu");
  // the belt's speed along the travel on the first pulley's wrap: its rim's speed plus the slip
  const std::string& p0 = l.pulleys[0];
  const double radius = prm.number("pulley." + p0 + ".radius");
  const std::vector<double>& omega = table.column(p0 + ".omega");
  const std::vector<double>& slip = table.column(p0 + ".slip_speed");
  std::vector<double> speed(t.size(), NAN);
  for (size_t r = r0; r < r1; ++r) speed[r] = std::abs(omega[r]) * radius + slip[r];
  const double belt_speed = stats(speed, r0, r1).mean;

  add(s, "window", "", "from", t[r0], "s");
  add(s, "window", "", "to", t[r1 - 1], "s");
  add_count(s, "window", "", "rows", r1 - r0);
  add(s, "window", "", "belt_speed", belt_speed, "m/s");
  for (const auto& sp : l.spans) {
    const Stats st = w.of(span_name(sp) + ".tension");
    add(s, "spans", span_name(sp), "tension_mean", st.mean, "N");
    add(s, "spans", span_name(sp), "tension_min", st.min, "N");
    add(s, "spans", span_name(sp), "tension_max", st.max, "N");
  }
  for (const std::string& p : l.pulleys) {
    const double loss = w.of(p + ".slip_speed").mean;
    add(s, "pulleys", p, "omega_mean", w.of(p + ".omega").mean, "rad/s");
    add(s, "pulleys", p, "slip_speed_mean", loss, "m/s");
    add(s, "pulleys", p, "speed_loss", loss / belt_speed, "");
    add(s, "pulleys", p, "creep_mean", w.of(p + ".creep").mean, "");
    add(s, "pulleys", p, "creep_pitch_mean", w.of(p + ".creep_pitch").mean, "");
  }
  add_wraps(s, w, l, prm, speed, belt_speed);
  add_arms_and_rotors(s, w, l);
  add_losses(s, w, l);
  if (s.losses) s.jumps = state_jumps(dir, t[r0], t[r1 - 1]);
  return s;
}

}  // namespace beltsim::plot
