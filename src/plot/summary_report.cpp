// A summary's figures as a table, a CSV and a plot (summary.hpp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "integrate/stepper.hpp"
#include "io/csv_writer.hpp"
#include "io/suggest.hpp"
#include "plot/plot.hpp"
#include "plot/summary.hpp"

namespace beltsim::plot {

namespace {

namespace fs = std::filesystem;

std::string four_digits(double v) {
  char b[32];
  std::snprintf(b, sizeof b, "%.4g", v);
  return b;
}

std::string with_unit(const Figure& f) {
  return f.quantity + (f.unit.empty() ? "" : " [" + f.unit + "]");
}

double window_value(const Summary& s, const std::string& quantity) {
  for (const Figure& f : s.figures)
    if (f.section == "window" && f.quantity == quantity) return f.value;
  return NAN;
}

// one section: its items as rows, its quantities (in their first order) as columns
void section_table(const Summary& s, const std::string& section, std::string& out) {
  std::vector<std::string> items, quantities;
  for (const Figure& f : s.figures) {
    if (f.section != section) continue;
    if (std::find(items.begin(), items.end(), f.item) == items.end()) items.push_back(f.item);
    if (std::find(quantities.begin(), quantities.end(), with_unit(f)) == quantities.end())
      quantities.push_back(with_unit(f));
  }
  if (items.empty()) return;
  size_t first = section.size();
  for (const std::string& i : items) first = std::max(first, i.size());
  std::vector<size_t> width;
  for (const std::string& q : quantities) width.push_back(std::max<size_t>(q.size(), 10));
  char b[256];
  out += "\n" + section + std::string(first - section.size(), ' ');
  for (size_t k = 0; k < quantities.size(); ++k)
    std::snprintf(b, sizeof b, "  %*s", static_cast<int>(width[k]), quantities[k].c_str()), out += b;
  out += "\n";
  for (const std::string& i : items) {
    out += i + std::string(first - i.size(), ' ');
    for (size_t k = 0; k < quantities.size(); ++k) {
      std::string cell = "";
      for (const Figure& f : s.figures)
        if (f.section == section && f.item == i && with_unit(f) == quantities[k]) cell = four_digits(f.value);
      std::snprintf(b, sizeof b, "  %*s", static_cast<int>(width[k]), cell.c_str()), out += b;
    }
    out += "\n";
  }
}

}  // namespace

std::string summary_table(const Summary& s) {
  std::string out = "summary of " + s.dir + " over t = " + four_digits(window_value(s, "from")) + " to " +
                    four_digits(window_value(s, "to")) + " s (" + four_digits(window_value(s, "rows")) +
                    (window_value(s, "rows") == 1 ? " sample" : " samples") + "), belt speed " + four_digits(window_value(s, "belt_speed")) + " m/s\n";
  if (!s.end_status.empty() && s.end_status != "ok")
    out += "the run did not end ok: end.status = " + s.end_status +
           (s.end_note.empty() ? "" : " (" + s.end_note + ")") + "; these figures are of its samples up to its stop\n";
  for (const char* section : {"spans", "pulleys", "wraps", "hubs", "arms", "rotors", "loss"})
    section_table(s, section, out);
  // an interval that reaches an end of the window began before it or goes on after it
  const double from = window_value(s, "from"), to = window_value(s, "to");
  for (const Overrun& o : s.overruns) {
    out += "\n" + o.pulley + " overruns (s):";
    if (o.intervals.empty()) out += " none";
    for (size_t k = 0; k < o.intervals.size() && k < 20; ++k) {
      const auto [a, b] = o.intervals[k];
      out += (k ? ", " : " ") + four_digits(a) + (a <= from ? " (open at the window's start)" : "") + " to " +
             four_digits(b) + (b >= to ? " (open at the window's end)" : "");
    }
    if (o.intervals.size() > 20) out += ", and " + std::to_string(o.intervals.size() - 20) + " more";
    out += "\n";
  }
  // measured (docs/outputs.md, interval means): scripts/fixed_centres.lua at 30 m/s, its driver
  // kinematic, 9.8 W (2.8 % of the input) at rtol 1e-4, 0.09 W at 1e-5, -0.01 W at 1e-6
  double input = NAN;
  for (const Figure& f : s.figures)
    if (f.section == "loss" && f.quantity == "input") input = f.value;
  // the integrator's own miss first (rkf45's, ros34pw2's): a tighter tolerance would not mend it
  const std::string integrator_miss = energy_miss(s.integrator);
  if (s.losses && !s.jumps.empty())
    out += "\nloss: the window holds a state set from a script (" + join(s.jumps) +
           "): the energy it put in or took out is in stored, with no torque's work for it in input, so input - "
           "output - (total + stored) = " +
           four_digits(s.imbalance) +
           " W is that, not a tolerance's bias (docs/outputs.md, the energy columns); a window after it balances\n";
  else if (s.losses && std::abs(s.imbalance) > Summary::kImbalanceShare * std::abs(input) && input > 0)
    out += "\nloss: input - output - (total + stored) = " + four_digits(s.imbalance) + " W, " +
           four_digits(100 * s.imbalance / input) + " % of the input: " +
           (integrator_miss.empty()
                ? "the belt torques' interval means (and a kinematic pulley's torque_mean, so input and output) carry "
                  "a bias of the run's tolerance that the losses and the motion do not (docs/outputs.md, interval "
                  "means); run at rtol 1e-5 or 1e-6 for input, output and share\n"
                : "the run's integrator is " + s.integrator + ", and " + integrator_miss +
                      " (docs/integration.md); run it with trbdf2 (the default) for the losses\n");
  if (s.losses && window_value(s, "rows") == 1)
    out += "\nloss: nan: the window holds one sample, and the losses, input and output are powers over its "
           "duration: give --from and --to two samples or more apart\n";
  if (!s.losses) out += "\nloss: not recorded (the run has no energy.* columns: give energy = true to beltsim.scene)\n";
  if (!s.mu_per_sample)
    out += "\nmu: the belt's least mu at the start (parameters.csv belt.mu_min) on every wrap and sample: the run "
           "has no <pulley>.mu columns (it was written by an older beltsim), so a stretch wetted during it is not "
           "seen in the capstan margins; run it again for the mu each wrap had\n";
  return out;
}

std::vector<std::string> summary_columns(const Summary& s) {
  std::vector<std::string> names;
  for (const Figure& f : s.figures) {
    std::string unit = f.unit;
    std::replace(unit.begin(), unit.end(), '/', '_');
    names.push_back((f.item.empty() ? f.section : f.item) + "." + f.quantity + (unit.empty() ? "" : "_" + unit));
  }
  return names;
}

void write_summary_csv(const Summary& s, const std::string& path) {
  std::vector<double> row;
  for (const Figure& f : s.figures) row.push_back(f.value);
  CsvWriter w(path, summary_columns(s));
  w.row(row);
}

void plot_summary(const Summary& s, const std::string& png) {
  const double from = window_value(s, "from"), to = window_value(s, "to");
  const Table t = read_timeseries_csv((fs::path(s.dir) / "timeseries.csv").string());
  const std::vector<double>& time = t.column("t");
  PlotSpec spec;
  spec.title = "summary of " + s.dir;
  spec.file = png;
  auto series = [&](const std::string& column, const std::string& unit) {
    Series out{column, unit, {}, {}};
    const std::vector<double>& y = t.column(column);
    for (size_t r = 0; r < time.size(); ++r)
      if (time[r] >= from && time[r] <= to) out.t.push_back(time[r]), out.y.push_back(y[r]);
    spec.series.push_back(std::move(out));
  };
  for (const Figure& f : s.figures)
    if (f.section == "spans" && f.quantity == "tension_mean") series(f.item + ".tension", "N");
  for (const Figure& f : s.figures)
    if (f.section == "arms" && f.quantity == "arm_angle_mean") series(f.item + ".arm_angle", "rad");
  for (const Overrun& o : s.overruns) {
    series(o.pulley + ".omega", "rad/s");
    series(o.pulley + ".rotor_speed", "rad/s");
    for (size_t k = 0; k < o.intervals.size() && k < 20; ++k)
      spec.marks.push_back({o.intervals[k].first, o.pulley + " overruns"});
  }
  for (const Mark& m : read_event_marks((fs::path(s.dir) / "events.csv").string()))
    if (m.x >= from && m.x <= to) spec.marks.push_back(m);
  plot_png(spec);
}

}  // namespace beltsim::plot
