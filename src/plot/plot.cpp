#include "plot/plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "io/csv_writer.hpp"
#include "io/input_file.hpp"
#include "io/number_text.hpp"
#include "io/suggest.hpp"
#include "io/units.hpp"
#include "plot/gnuplot.hpp"

namespace beltsim::plot {

namespace {

// series that share a unit, in the order of their first appearance
struct Group {
  std::string unit;
  std::vector<int> series;
  bool unknown = false;  // a series of unknown unit, alone (Series::unknown_unit)
};

std::string last_component(const std::string& name) {
  const size_t dot = name.rfind('.');
  return dot == std::string::npos ? name : name.substr(dot + 1);
}

std::string with_unit(const std::string& what, const std::string& unit) {
  if (unit.empty()) return what;
  return what.empty() ? "[" + unit + "]" : what + " [" + unit + "]";
}

// the quantity every series of the group is ("omega" for driver.omega and driven.omega), "" when
// they differ
std::string shared_quantity(const PlotSpec& spec, const Group& g) {
  const std::string q = last_component(spec.series[g.series[0]].name);
  for (int k : g.series)
    if (last_component(spec.series[k].name) != q) return "";
  return q;
}

// whether every series of the group is of one name (one column, a series per value of another)
bool one_name(const PlotSpec& spec, const std::vector<int>& series) {
  for (int k : series)
    if (spec.series[k].name != spec.series[series[0]].name) return false;
  return true;
}

// "name [unit]" for series of one name, "omega [rad/s]" for several of one quantity, else the names
std::string axis_label(const PlotSpec& spec, const Group& g) {
  if (one_name(spec, g.series)) return with_unit(spec.series[g.series[0]].name, g.unit);
  if (const std::string q = shared_quantity(spec, g); !q.empty()) return with_unit(q, g.unit);
  std::vector<std::string> names;
  for (int k : g.series)
    if (std::find(names.begin(), names.end(), spec.series[k].name) == names.end()) names.push_back(spec.series[k].name);
  return with_unit(join(names), g.unit);
}

// a series' title in the legend: its name, with its unit when the axes differ in theirs, and the
// value of the column it is drawn for ("slip_max, load = 40 N·m"; that alone when every series
// drawn is of one name)
std::string legend_title(const PlotSpec& spec, int k, bool units_in_key, bool right) {
  const Series& s = spec.series[k];
  std::string title = units_in_key ? with_unit(s.name, s.unit) : s.name;
  if (!s.variant.empty()) {
    std::vector<int> all(spec.series.size());
    for (size_t i = 0; i < all.size(); ++i) all[i] = static_cast<int>(i);
    title = one_name(spec, all) ? s.variant : title + ", " + s.variant;
  }
  return title + (right ? " (right axis)" : "");
}

// the series as a gnuplot datablock $s<k>: "t y" rows, an empty line (a gap) at undefined values
void datablock(std::ostringstream& g, int k, const Series& s) {
  g << "$s" << k << " << EOD\n";
  bool gap = true;
  for (size_t i = 0; i < s.t.size(); ++i) {
    if (!std::isfinite(s.t[i]) || !std::isfinite(s.y[i])) {
      if (!gap) g << '\n';
      gap = true;
      continue;
    }
    g << number_text(s.t[i]) << ' ' << number_text(s.y[i]) << '\n';
    gap = false;
  }
  g << "EOD\n";
}

// the characters (UTF-8 code points) of s
size_t code_points(const std::string& s) {
  size_t n = 0;
  for (const char c : s) n += (static_cast<unsigned char>(c) & 0xC0) != 0x80;
  return n;
}

// the marks inside [x0, x1], those at one time in one (an event and an overrun that begin at the
// window's start share a line and a label: two labels there were drawn over each other)
std::vector<Mark> shown_marks(const PlotSpec& spec, double x0, double x1) {
  std::vector<Mark> shown;
  for (const Mark& m : spec.marks) {
    if (!(m.x >= x0 && m.x <= x1)) continue;
    const auto same = std::find_if(shown.begin(), shown.end(), [&](const Mark& o) { return o.x == m.x; });
    if (same == shown.end())
      shown.push_back(m);
    else
      same->label += "; " + m.label;
  }
  return shown;
}

// [px] the width a mark's label takes beside its line (9 pt, boxed, and the gap to the line)
constexpr double kMarkLabelPx = 22;

// the legend inside a panel's top left (or right), as a mark's label must keep clear of it: its
// width and the panel's width in pixels, and the share of the panel's height it takes from the top
struct LegendBox {
  double width_px = 0, panel_width_px = 1, height_share = 0;
  bool right = false;
  // whether the label of a mark at the share `at` of the panel's width, reading up from the top
  // right of its line (kMarkLabelPx wide), would cross it
  bool covers(double at) const {
    const double x = at * panel_width_px;
    return width_px > 0 && (right ? x + 30 > panel_width_px - width_px : x < width_px);
  }
};

// the marks inside [x0, x1]: dashed grey lines on every panel, their labels right of the line,
// reading upwards to the top, shortened to `label_px` (none for 0); left of it where the panel
// (`width_px` wide) has no room for it on the right: a mark at the window's end had its label
// outside the frame. A label that would cross the legend (a mark under it) reads upwards to just
// below it instead, shortened to the height left there
void mark_lines(std::ostringstream& g, const PlotSpec& spec, double x0, double x1, double label_px, double width_px,
                const LegendBox& legend = {}) {
  // 9 pt: under 7 pixels a character
  const auto fitting = [](double px) { return static_cast<size_t>(std::max(0.0, px / 7.0)); };
  const double top = 1 - legend.height_share - 0.03;  // below the legend, in the panel's share
  const size_t below = fitting(label_px / 0.9 * (top - 0.05));
  // each label on a box of its own, two thirds white: readable where it crosses a curve, which
  // still shows through
  g << "unset arrow\nunset label\nset style textbox opaque noborder fillcolor rgb '#50ffffff'\n";
  int k = 0;
  for (const Mark& m : shown_marks(spec, x0, x1)) {
    ++k;
    g << "set arrow " << k << " from " << number_text(m.x) << ", graph 0 to " << number_text(m.x)
      << ", graph 1 nohead dt 2 lw 1 lc rgb '#777777' back\n";
    const double at = x1 > x0 ? (m.x - x0) / (x1 - x0) : 0;
    const bool under = legend.covers(at);
    const size_t chars = under ? below : fitting(label_px);
    // a label right of its line, boxed, takes about kMarkLabelPx pixels
    const bool left = (1 - at) * width_px < kMarkLabelPx;
    if (chars >= 4)
      g << "set label " << k << " " << gnuplot_string(shortened(m.label, chars)) << " at " << number_text(m.x)
        << ", graph " << (under ? number_text(top) : std::string("0.98")) << " right rotate by 90 offset "
        << (left ? "-0.8" : "1") << ",0 font ',9' tc rgb '#555555' front boxed\n";
  }
}

// the finite values' range of a group's series
std::pair<double, double> group_range(const PlotSpec& spec, const Group& grp) {
  double lo = INFINITY, hi = -INFINITY;
  for (int k : grp.series)
    for (double y : spec.series[k].y)
      if (std::isfinite(y)) lo = std::min(lo, y), hi = std::max(hi, y);
  return {lo, hi};
}

// An axis ("y" or "y2") whose values differ only in their last digits: a column constant up to
// rounding (within 1e-9 of its size: a span tension at rest, 500.106 ± 1e-10 N) is drawn flat in
// the middle of ±1 % about its value, not stretched over the panel's height as if it moved; a
// range too narrow for gnuplot's six digits to tell the tics apart gets as many digits as do.
void narrow_axis(std::ostringstream& g, const char* axis, double lo, double hi) {
  g << "set " << axis << "range [*:*]\nset format " << axis << " '% h'\n";
  if (!(hi >= lo)) return;  // no finite value
  const double size = std::max(std::abs(lo), std::abs(hi)), mid = 0.5 * (lo + hi);
  if (size == 0) return;  // all zero: gnuplot's own range about 0
  if (hi - lo <= 1e-9 * size) {
    g << "set " << axis << "range [" << number_text(mid - 0.01 * size) << ":" << number_text(mid + 0.01 * size)
      << "]\n";
    return;
  }
  // about four tic intervals: the digits that tell size from size + step apart
  const int digits = static_cast<int>(std::ceil(std::log10(size / ((hi - lo) / 4)))) + 1;
  if (digits > 6) g << "set format " << axis << " '%." << std::min(digits, 15) << "g'\n";
}

// 1, 2 or 5 times a power of ten: the tic step at or above raw
double nice_step(double raw) {
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  return raw <= mag ? mag : raw <= 2 * mag ? 2 * mag : raw <= 5 * mag ? 5 * mag : 10 * mag;
}

// [share of the panel] the room between a sweep's marks and the frame, on every side: a mark at
// the range's end was cut in half by it (trial 27)
constexpr double kPointsMargin = 0.05;

// The y2 axis of a points plot, its values from lo to hi: gnuplot's offsets widen y1 and x only,
// so its range is set here, kPointsMargin of it beyond the values, out to the next tic (at about
// four tic intervals, as gnuplot's own). A flat axis keeps narrow_axis's range.
void pad_y2(std::ostringstream& g, double lo, double hi) {
  if (!(hi - lo > 1e-9 * std::max(std::abs(lo), std::abs(hi)))) return;
  const double pad = kPointsMargin * (hi - lo), step = nice_step((hi - lo + 2 * pad) / 4);
  g << "set y2range [" << number_text(std::floor((lo - pad) / step) * step) << ":"
    << number_text(std::ceil((hi + pad) / step) * step) << "]\nset y2tics " << number_text(step) << "\n";
}

void plot_command(std::ostringstream& g, const PlotSpec& spec, const std::vector<int>& series, bool second_axis,
                  const std::vector<int>& y2, bool units_in_key) {
  g << "plot ";
  for (size_t n = 0; n < series.size(); ++n) {
    const int k = series[n];
    const Series& s = spec.series[k];
    const bool right = second_axis && std::find(y2.begin(), y2.end(), k) != y2.end();
    // the shapes of a series' marks: a filled circle, square, triangle, diamond, triangle down
    static constexpr int kShapes[] = {7, 5, 9, 13, 11};
    g << (n ? ", \\\n     " : "") << "$s" << k << " using 1:2 with ";
    if (spec.points)
      g << (spec.joined ? "linespoints lw 1.5 " : "points ") << "pt " << kShapes[s.shape % 5] << " ps 1.5 ";
    else
      g << "lines lw 2 ";
    g << "lt " << (s.colour > 0 ? s.colour : k + 1) << (right ? " axes x1y2" : "") << " title "
      << gnuplot_string(legend_title(spec, k, units_in_key, right));
  }
  g << "\n";
}

}  // namespace

std::string shortened(const std::string& s, size_t n) {
  size_t chars = 0, cut = 0;
  for (size_t i = 0; i < s.size(); ++i) {
    if ((static_cast<unsigned char>(s[i]) & 0xC0) == 0x80) continue;  // a continuation byte
    if (++chars == n) cut = i;
  }
  return chars <= n ? s : s.substr(0, cut) + "…";
}

void plot_png(const PlotSpec& spec) {
  if (spec.file.empty()) throw std::runtime_error("plot: no output file given");
  const PrivateOutput out;  // gnuplot writes there; the picture is then written to spec.file
  run_gnuplot(plot_script(spec, out.path()));
  out.deliver(spec.file, "plot");
}

std::string plot_script(const PlotSpec& spec, const std::string& png) {
  if (spec.series.empty()) throw std::runtime_error("plot " + spec.file + ": no series to draw");
  if (spec.width < 16 || spec.height < 16 || spec.width > 20000 || spec.height > 20000)
    throw std::runtime_error("plot " + spec.file + ": size " + std::to_string(spec.width) + "x" +
                             std::to_string(spec.height) + " is outside 16..20000 pixels");
  std::vector<Group> groups;
  for (size_t k = 0; k < spec.series.size(); ++k) {
    const Series& s = spec.series[k];
    if (s.t.size() != s.y.size())
      throw std::runtime_error("plot " + spec.file + ": series '" + s.name + "' has " + std::to_string(s.t.size()) +
                               " times but " + std::to_string(s.y.size()) + " values");
    bool any = false;
    for (size_t i = 0; i < s.t.size() && !any; ++i) any = std::isfinite(s.t[i]) && std::isfinite(s.y[i]);
    if (!any) throw std::runtime_error("plot " + spec.file + ": series '" + s.name + "' has no finite values");
    // (a series of unknown unit shares its axis only with those of its name: its column's, one a value)
    auto g = std::find_if(groups.begin(), groups.end(), [&](const Group& x) {
      return x.unit == s.unit && x.unknown == s.unknown_unit && (!x.unknown || spec.series[x.series[0]].name == s.name);
    });
    if (g == groups.end()) g = groups.insert(groups.end(), Group{s.unit, {}, s.unknown_unit});
    g->series.push_back(static_cast<int>(k));
  }

  std::ostringstream g;
  g << "set encoding utf8\n"
    << "set terminal pngcairo size " << spec.width << "," << spec.height
    << " font 'DejaVu Sans,12' linewidth 1 noenhanced\n"
    << "set output " << gnuplot_string(png) << "\n"
    << line_colours_script();
  for (size_t k = 0; k < spec.series.size(); ++k) datablock(g, static_cast<int>(k), spec.series[k]);
  // one time axis for every series (and every panel)
  double t0 = INFINITY, t1 = -INFINITY;
  for (const Series& s : spec.series)
    for (size_t i = 0; i < s.t.size(); ++i)
      if (std::isfinite(s.t[i]) && std::isfinite(s.y[i])) t0 = std::min(t0, s.t[i]), t1 = std::max(t1, s.t[i]);
  if (spec.points)  // no mark on the frame
    g << "set offsets graph " << kPointsMargin << ", graph " << kPointsMargin << ", graph " << kPointsMargin
      << ", graph " << kPointsMargin << "\n";
  else if (t1 > t0)
    g << "set xrange [" << number_text(t0) << ":" << number_text(t1) << "]\n";
  g << "set grid xtics ytics lc rgb '#dddddd'\n"
    << "set xlabel " << gnuplot_string(spec.x_label) << "\n";
  if (groups.size() <= 2) {
    // the legend below the plot: the plot keeps the full width, and both y axes stay in view
    // (a sweep's: a line's room above it, where its entries touched the x axis' label)
    g << "set key below center horizontal Left reverse" << (spec.points ? " height 1" : "") << "\n";
    if (!spec.title.empty()) g << "set title " << gnuplot_string(spec.title) << "\n";
    g << "set ylabel " << gnuplot_string(axis_label(spec, groups[0])) << "\n";
    std::vector<int> all;
    for (size_t k = 0; k < spec.series.size(); ++k) all.push_back(static_cast<int>(k));
    if (groups.size() == 2) {
      g << "set ytics nomirror\nset y2tics\nset y2label " << gnuplot_string(axis_label(spec, groups[1])) << "\n";
    }
    for (size_t a = 0; a < groups.size(); ++a) {
      const auto [lo, hi] = group_range(spec, groups[a]);
      narrow_axis(g, a == 0 ? "y" : "y2", lo, hi);
      if (a == 1 && spec.points) pad_y2(g, lo, hi);
    }
    // (the panel: the picture's width but for the axes' numbers and labels, about 100 pixels a side
    // that has them)
    if (!spec.points) mark_lines(g, spec, t0, t1, 0.6 * spec.height, spec.width - (groups.size() == 2 ? 200.0 : 100.0));
    plot_command(g, spec, all, groups.size() == 2, groups.size() == 2 ? groups[1].series : std::vector<int>{},
                 groups.size() == 2);
  } else {
    // one panel per unit, stacked, aligned, the time axis numbered and labelled on the lowest only;
    // each panel's legend inside at its top left (or right, below)
    const double top = spec.title.empty() ? 0.97 : 0.93;
    g << "set multiplot layout " << groups.size() << ",1 margins 0.1,0.97,0.09," << top << " spacing 0,0.03";
    if (!spec.title.empty()) g << " title " << gnuplot_string(spec.title);
    // the legends on the left, unless the top panel's (the one with the marks' labels) would cover
    // labels there (an event at the window's start) and fewer on the right: then on the right
    size_t longest = 0;
    for (int k : groups[0].series) longest = std::max(longest, code_points(legend_title(spec, k, false, false)));
    // a sample line and the margins, about 9 pixels a character at 12 pt
    LegendBox legend{9.0 * static_cast<double>(longest) + 120, spec.width * (0.97 - 0.1)};
    int left = 0, right = 0;
    for (const Mark& m : spec.points ? std::vector<Mark>{} : shown_marks(spec, t0, t1)) {
      const double at = t1 > t0 ? (m.x - t0) / (t1 - t0) : 0;
      left += legend.covers(at);
      legend.right = true;
      right += legend.covers(at);
      legend.right = false;
    }
    legend.right = right < left;
    g << "\nset key inside " << (legend.right ? "right" : "left")
      << " top Left reverse opaque box\nset format x ''\nunset xlabel\n";
    const double n = static_cast<double>(groups.size());
    const double panel_px = spec.height * (top - 0.09 - 0.03 * (n - 1)) / n;
    for (size_t p = 0; p < groups.size(); ++p) {
      if (p + 1 == groups.size()) g << "set format x '% h'\nset xlabel " << gnuplot_string(spec.x_label) << "\n";
      // the label along the axis when it fits the panel's height (under 8 pixels a character at 12 pt),
      // else the quantity and its unit ("tension [N]" for span_alt_pump.tension) when the panel's
      // series share it, else the unit alone (the legend names the series)
      auto fits = [&](const std::string& l) { return 8.0 * static_cast<double>(l.size()) <= panel_px; };
      std::string label = axis_label(spec, groups[p]);
      if (!fits(label)) label = with_unit(shared_quantity(spec, groups[p]), groups[p].unit);
      if (!fits(label)) label = with_unit("", groups[p].unit);
      g << "set ylabel " << gnuplot_string(label) << "\n";
      // about four tic intervals however short the panel
      const auto [lo, hi] = group_range(spec, groups[p]);
      narrow_axis(g, "y", lo, hi);
      if (hi - lo > 1e-9 * std::max(std::abs(lo), std::abs(hi))) {
        g << "set ytics " << number_text(nice_step((hi - lo) / 4)) << "\n";
      } else {
        g << "set ytics autofreq\n";
      }
      // room above the curves for the legend (a line of about 17 pixels a series, and its box),
      // so that it covers none of them: the range grows upwards by the legend's share of the panel
      const double key = std::min(0.6, (17.0 * static_cast<double>(groups[p].series.size()) + 22) / panel_px);
      // (a sweep's marks: kPointsMargin more on every side)
      const double margin = spec.points ? kPointsMargin : 0;
      g << "set offsets graph " << margin << ", graph " << margin << ", graph " << number_text(key / (1 - key) + margin)
        << ", graph " << margin << "\n";
      legend.height_share = key;
      if (!spec.points) mark_lines(g, spec, t0, t1, p == 0 ? 0.9 * panel_px : 0, legend.panel_width_px, legend);
      plot_command(g, spec, groups[p].series, false, {}, false);
    }
    g << "unset multiplot\n";
  }
  g << "set output\n";
  return g.str();
}

std::vector<Mark> read_event_marks(const std::string& events_csv) {
  std::vector<Mark> marks;
  std::optional<InputFile> f;
  try {
    f.emplace(events_csv);
  } catch (const InputFileError&) {
    return marks;  // none, or not a regular file: no marks
  }
  std::string line;
  bool header = true;
  RowReader rows(f->stream());
  while (rows.next(line)) {
    if (std::exchange(header, false)) continue;
    const std::vector<std::string> fields = csv_fields(line);
    double t = 0;
    if (fields.size() != 3 || !parse_number_field(fields[0], t) || !std::isfinite(t)) continue;
    const std::string label = shortened(trim_blanks(fields[1] + " " + fields[2]), 40);
    if (!marks.empty() && marks.back().x == t)
      marks.back().label += "; " + label;
    else
      marks.push_back({t, label});
  }
  return marks;
}

std::vector<std::string> drop_empty(PlotSpec& spec, const std::string& csv_path) {
  std::vector<std::string> dropped;
  std::vector<Series> kept;
  for (Series& s : spec.series) {
    bool any = false;
    for (size_t i = 0; i < s.t.size() && i < s.y.size() && !any; ++i)
      any = std::isfinite(s.t[i]) && std::isfinite(s.y[i]);
    if (any)
      kept.push_back(std::move(s));
    else
      dropped.push_back(s.name);
  }
  if (kept.empty())
    throw std::runtime_error(csv_path + ": no finite value to draw in " + join(dropped) +
                             (dropped.size() == 1 ? "" : " (any of them)"));
  spec.series = std::move(kept);
  return dropped;
}

std::string left_out_warning(const std::vector<std::string>& names) {
  if (names.empty()) return "";
  return "left out of the plot, with no finite value to draw: " + join(names);
}

std::vector<std::string> left_out_warnings(const PlotReport& report) {
  std::vector<std::string> w;
  if (!report.columns.empty()) w.push_back(left_out_warning(report.columns));
  if (!report.points.empty()) {
    std::string s = "left out of the plot, with nothing to draw: " + std::to_string(report.points.size()) + " of the " +
                    std::to_string(report.of_points) + " points (" + report.points_why + "):";
    // (a sweep of many failed points: the first ten, the others counted)
    constexpr size_t kListed = 10;
    for (size_t k = 0; k < report.points.size() && k < kListed; ++k) s += "\n  " + report.points[k];
    if (report.points.size() > kListed)
      s += "\n  and " + std::to_string(report.points.size() - kListed) + " more (their status is in the summary)";
    w.push_back(s);
  }
  w.insert(w.end(), report.notes.begin(), report.notes.end());
  return w;
}

PlotReport plot_csv(const std::string& csv_path, const std::vector<std::string>& columns, double from_t,
                    const std::string& out_png, double to_t, const std::string& by) {
  if (is_sweep_summary(csv_path)) {
    if (from_t > -INFINITY || to_t < INFINITY)
      throw std::runtime_error(csv_path +
                               " is a sweep's summary, drawn against a column of its own, not time: "
                               "a start or end time does not apply to it");
    return plot_summary_csv(csv_path, columns, out_png, by);
  }
  if (!by.empty())
    throw std::runtime_error(csv_path + " is a time series, drawn against t: a series per value of a column (" + by +
                             ") is for a sweep's summary");
  const Table table = read_timeseries_csv(csv_path);
  const std::vector<double>& t = table.column("t");
  std::vector<std::string> wanted = columns;
  if (wanted.empty()) {
    for (const auto& n : table.names)
      if (n.size() > 6 && n.compare(n.size() - 6, 6, ".omega") == 0) wanted.push_back(n);
    if (wanted.empty())
      throw std::runtime_error(
          csv_path + " has no '<pulley>.omega' column to plot; name the columns, its columns: " + join(table.names));
  }
  for (const auto& name : wanted) table.column(name);  // every unknown name fails before plotting
  // (a sweep's summary takes its x column first; a time series is drawn against t, which drawn as
  // a column of its own was a line of t against t)
  if (std::find(wanted.begin(), wanted.end(), "t") != wanted.end())
    throw std::runtime_error(csv_path +
                             " is a time series: its columns are drawn against t, so name only the "
                             "columns to draw (t is not one)");
  PlotSpec spec;
  spec.file = out_png;
  // the run's folder and the file: which run it is, without the machine's own path
  const std::filesystem::path cp(csv_path);
  spec.title = cp.has_parent_path() && cp.parent_path().has_filename()
                   ? (cp.parent_path().filename() / cp.filename()).string()
                   : cp.filename().string();
  if (!t.empty() && from_t > t.front() && to_t < t.back())
    spec.title += "  (" + number_text(from_t) + " s ≤ t ≤ " + number_text(to_t) + " s)";
  else if (!t.empty() && from_t > t.front())
    spec.title += "  (t ≥ " + number_text(from_t) + " s)";
  else if (!t.empty() && to_t < t.back())
    spec.title += "  (t ≤ " + number_text(to_t) + " s)";
  for (const auto& name : wanted) {
    const std::vector<double>& y = table.column(name);
    Series s{name, unit_of(name), {}, {}};
    for (size_t i = 0; i < t.size(); ++i) {
      if (!(t[i] >= from_t && t[i] <= to_t)) continue;
      s.t.push_back(t[i]);
      s.y.push_back(y[i]);
    }
    if (s.t.empty())
      throw std::runtime_error(
          csv_path + " has no samples at " +
          (to_t < INFINITY ? number_text(from_t) + " s <= t <= " + number_text(to_t) : "t >= " + number_text(from_t)) +
          " s" + (t.empty() ? " (it has no rows)" : " (its last is at " + number_text(t.back()) + " s)"));
    spec.series.push_back(std::move(s));
  }
  spec.marks = read_event_marks((cp.parent_path() / "events.csv").string());
  PlotReport report;
  report.columns = drop_empty(spec, csv_path);
  plot_png(spec);
  return report;
}

}  // namespace beltsim::plot
