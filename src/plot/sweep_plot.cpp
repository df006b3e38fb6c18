// `beltsim plot` of a sweep's summary.csv (plot.hpp): its figures against a parameter, a mark per
// point.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <optional>
#include <set>
#include <stdexcept>
#include <string_view>

#include "io/number_text.hpp"
#include "io/shell_word.hpp"
#include "io/suggest.hpp"
#include "io/units.hpp"
#include "plot/plot.hpp"

namespace beltsim::plot {

namespace {

// the columns of a sweep's summary between `point` and `status`: its parameters
std::vector<std::string> parameter_names(const std::vector<std::string>& names) {
  const auto status = std::find(names.begin(), names.end(), "status");
  if (names.empty() || names[0] != "point" || status == names.end()) return {};
  return std::vector<std::string>(names.begin() + 1, status);
}

}  // namespace

std::string plot_example(const std::string& csv_path, const std::vector<std::string>& columns) {
  const std::vector<std::string> names = read_csv_header(csv_path);
  const std::vector<std::string> no_numbers;
  const Table table = read_timeseries_csv(csv_path, &no_numbers, &names);
  // the distinct numbers in a column (0: none, text)
  const auto values = [&](const std::string& name) {
    std::set<double> seen;
    for (const std::string& field : table.text(name)) {
      double v = 0;
      if (!field.empty() && parse_number_field(field, v) && std::isfinite(v)) seen.insert(v);
    }
    return seen.size();
  };
  const std::vector<std::string> parameters = parameter_names(names);
  std::string x = columns.empty() || std::find(names.begin(), names.end(), columns[0]) == names.end() ? "" : columns[0];
  if (x.empty()) {
    size_t most = 0;
    for (const std::string& p : parameters)
      if (const size_t n = values(p); n > most) x = p, most = n;
  }
  const auto status = std::find(names.begin(), names.end(), "status");
  std::string y, repeat;  // a figure of its own; one that repeats a parameter (["pretension [N]"])
  for (auto it = status == names.end() ? names.begin() : status + 1; it != names.end() && y.empty(); ++it) {
    if (*it == x || *it == "inputs" || values(*it) == 0) continue;
    const bool repeats = std::find(parameters.begin(), parameters.end(), name_without_unit(*it)) != parameters.end();
    if (!repeats)
      y = *it;
    else if (repeat.empty())
      repeat = *it;
  }
  if (y.empty()) y = repeat;
  if (x.empty() || y.empty()) return "";
  return "beltsim plot " + shell_word(csv_path) + " " + shell_word(x) + " " + shell_word(y);
}

namespace {

// the summary's columns to draw as numbers, and point, status, the parameters and `by` as text too
Table read_summary(const std::string& csv_path, const std::vector<std::string>& columns, const std::string& by) {
  std::vector<std::string> text = parameter_names(read_csv_header(csv_path));
  text.insert(text.end(), {"point", "status", by});
  return read_timeseries_csv(csv_path, &columns, &text);
}

// a column's unit as summary_units.csv beside the summary has it (sweep/results.hpp: the quick
// form's figures from the program's table, a sweep file's from the brackets its names end with);
// a summary written before that file came: the unit a header gives in brackets ("hub load [N]"),
// else not known (unit_of's table would read "slip" as an element's, m/s, for a user's difference
// of speeds)
std::optional<std::string> column_unit(const std::optional<ColumnUnits>& units, const std::string& h) {
  if (units)
    for (const auto& [column, unit] : *units)
      if (column == h) return unit;
  return bracketed_unit(h);
}

PlotSpec spec_of(const Table& table, const std::vector<std::string>& columns, const std::string& out_png) {
  const std::string& csv_path = table.path;
  const std::vector<double>& x = table.column(columns[0]);
  for (const auto& name : columns) table.column(name);
  PlotSpec spec;
  spec.file = out_png;
  spec.points = true;
  const std::optional<ColumnUnits> units = read_units_file(csv_path);
  spec.x_label = columns[0];
  const std::filesystem::path cp(csv_path);
  spec.title = cp.has_parent_path() && cp.parent_path().has_filename()
                   ? (cp.parent_path().filename() / cp.filename()).string()
                   : cp.filename().string();
  for (size_t k = 1; k < columns.size(); ++k) {
    const std::string& h = columns[k];
    const std::optional<std::string> unit = column_unit(units, h);
    const std::string name = unit && bracketed_unit(h) ? name_without_unit(h) : h;  // the unit drawn once
    spec.series.push_back(Series{name, unit.value_or(""), x, table.column(h), !unit});
  }
  return spec;
}

// Into report: the points (rows) of the summary that get no mark in spec (its series one per
// column, a value per row): no x, no value in any series, or (by) none of the column the series
// are told apart by. Each named with its parameters and why: its status, or what it lacks when it
// ran ok.
void note_left_out_points(const Table& table, const PlotSpec& spec, const std::string& by, PlotReport& report) {
  const std::vector<std::string>& ids = table.text("point");
  const std::vector<std::string>& status = table.text("status");
  const std::vector<std::string> parameters = parameter_names(table.names);
  const std::vector<double>& x = spec.series.at(0).t;
  report.of_points = ids.size();
  size_t failed = 0, not_run = 0, outdated = 0, lacking = 0;
  for (size_t i = 0; i < ids.size(); ++i) {
    bool drawn = false;
    for (const Series& s : spec.series) drawn = drawn || (std::isfinite(s.t[i]) && std::isfinite(s.y[i]));
    const bool without_by = !by.empty() && table.text(by)[i].empty();
    if (drawn && !without_by) continue;
    std::string why = status[i];
    if (why == "ok") {
      std::vector<std::string> lacks;
      if (!std::isfinite(x[i]))
        lacks.push_back(spec.x_label);
      else if (drawn)
        lacks.push_back(by);
      else
        for (const Series& s : spec.series) lacks.push_back(s.name);
      why = "ok, but without a value of " + or_list(lacks);
      ++lacking;
    } else if (why == "not run") {
      ++not_run;
    } else if (why.rfind("outdated: ", 0) == 0) {
      ++outdated;
    } else {
      ++failed;
    }
    std::string where;
    for (const std::string& p : parameters) where += (where.empty() ? "" : ", ") + p + "=" + table.text(p)[i];
    report.points.push_back("point " + ids[i] + (where.empty() ? "" : " (" + where + ")") + ": " + shortened(why, 160));
  }
  std::vector<std::string> counts;
  for (const auto& [n, what] :
       {std::pair{failed, "failed"}, {not_run, "not run"}, {outdated, "outdated"}, {lacking, "ok without a value"}})
    if (n > 0) counts.push_back(std::to_string(n) + " " + what);
  report.points_why = join(counts);
}

// A value of the column the series are told apart by: its text as written, the number it is (when
// every value is one) and the rows that have it
struct ByValue {
  std::string text;
  double number = 0;
  std::vector<size_t> rows;
};

// the values of the column `by` in its rows (none for an empty field): in increasing order when
// every one is a number (one value however written: 40 and 40.0), else in the order they come
std::vector<ByValue> by_values(const std::vector<std::string>& texts) {
  bool numbers = true;
  for (const std::string& t : texts) {
    double v = 0;
    numbers = numbers && (t.empty() || (parse_number_field(t, v) && std::isfinite(v)));
  }
  std::vector<ByValue> values;
  for (size_t i = 0; i < texts.size(); ++i) {
    if (texts[i].empty()) continue;
    double v = 0;
    if (numbers) parse_number_field(texts[i], v);
    auto it = std::find_if(values.begin(), values.end(),
                           [&](const ByValue& b) { return numbers ? b.number == v : b.text == texts[i]; });
    if (it == values.end()) it = values.insert(values.end(), ByValue{texts[i], v, {}});
    it->rows.push_back(i);
  }
  if (numbers)
    std::stable_sort(values.begin(), values.end(),
                     [](const ByValue& a, const ByValue& b) { return a.number < b.number; });
  return values;
}

// Splits spec's series (one per column, a value per row) into one per value of the column `by`,
// its marks joined by a line in x order: a colour per value, a shape per column; titled "load =
// 40 N·m" (with the column's unit). A series with no value to draw is left out (its points are
// named as such). When a series holds several points at one x (another parameter varies within
// it), a line through them would zigzag: the marks are left unjoined, and report notes why.
void split_by(const Table& table, const std::string& by, const std::optional<std::string>& unit, PlotSpec& spec,
              PlotReport& report) {
  const std::vector<ByValue> values = by_values(table.text(by));
  const std::string label = unit && bracketed_unit(by) ? name_without_unit(by) : by;
  const std::string suffix = unit && !unit->empty() ? " " + *unit : "";
  std::vector<Series> split;
  for (size_t c = 0; c < spec.series.size(); ++c) {
    const Series& whole = spec.series[c];
    for (size_t v = 0; v < values.size(); ++v) {
      std::vector<size_t> rows;
      for (const size_t i : values[v].rows)
        if (std::isfinite(whole.t[i])) rows.push_back(i);
      std::stable_sort(rows.begin(), rows.end(), [&](size_t a, size_t b) { return whole.t[a] < whole.t[b]; });
      Series s{whole.name, whole.unit, {}, {}, whole.unknown_unit};
      bool any = false;
      for (const size_t i : rows) {
        s.t.push_back(whole.t[i]);
        s.y.push_back(whole.y[i]);
        any = any || std::isfinite(whole.y[i]);
      }
      if (!any) continue;
      s.variant = label + " = " + values[v].text + suffix;
      s.colour = static_cast<int>(v) + 1;
      s.shape = static_cast<int>(c);
      split.push_back(std::move(s));
    }
  }
  // the first x a series has two points at, and the parameters that differ between them
  const std::vector<std::string> parameters = parameter_names(table.names);
  const std::vector<double>& x = spec.series.at(0).t;
  for (const ByValue& v : values)
    for (size_t a = 0; a < v.rows.size() && report.notes.empty(); ++a)
      for (size_t b = a + 1; b < v.rows.size() && report.notes.empty(); ++b) {
        const size_t i = v.rows[a], j = v.rows[b];
        if (!std::isfinite(x[i]) || x[i] != x[j]) continue;
        std::vector<std::string> differ;
        for (const std::string& p : parameters)
          if (p != by && table.text(p)[i] != table.text(p)[j]) differ.push_back(p);
        report.notes.push_back("--by " + by + ": the series " + label + " = " + v.text + suffix +
                               " has several points at " + spec.x_label + " = " + number_text(x[i]) +
                               (differ.empty() ? "" : " (they differ in " + and_list(differ) + ")") +
                               ": the points are drawn unjoined, as a line through them would zigzag");
      }
  spec.series = std::move(split);
  spec.joined = report.notes.empty();
}

// fewer than two columns: the error, with an example made of the file's own
void require_x_and_y(const std::string& csv_path, const std::vector<std::string>& columns) {
  if (columns.size() >= 2) return;
  const std::string example = plot_example(csv_path, columns);
  throw std::runtime_error(csv_path + " is a sweep's summary: name the x column and at least one y column" +
                           (example.empty() ? "" : ", e.g. " + example) +
                           "; its columns: " + join(read_csv_header(csv_path)));
}

// summary_spec's, its left-out columns and points and its notes in report
PlotSpec build_spec(const std::string& csv_path, const std::vector<std::string>& columns, const std::string& out_png,
                    const std::string& by, PlotReport& report) {
  require_x_and_y(csv_path, columns);
  if (!by.empty()) {
    const std::vector<std::string> names = read_csv_header(csv_path);
    if (std::find(names.begin(), names.end(), by) == names.end())
      throw std::runtime_error("--by " + by + ": " + csv_path + " has no column '" + by + "'" +
                               column_suggestion(by, names) + "; its columns: " + join(names));
    if (std::find(columns.begin(), columns.end(), by) != columns.end())
      throw std::runtime_error(csv_path + ": " + by + " is drawn (" + (by == columns[0] ? "x" : "y") +
                               "), so it cannot tell series apart too: draw a series per value of another column");
  }
  const Table table = read_summary(csv_path, columns, by);
  PlotSpec spec = spec_of(table, columns, out_png);
  report.columns = drop_empty(spec, csv_path);
  note_left_out_points(table, spec, by, report);
  if (!by.empty()) split_by(table, by, column_unit(read_units_file(csv_path), by), spec, report);
  return spec;
}

}  // namespace

PlotSpec summary_spec(const std::string& csv_path, const std::vector<std::string>& columns, const std::string& out_png,
                      const std::string& by) {
  PlotReport report;
  return build_spec(csv_path, columns, out_png, by, report);
}

PlotReport plot_summary_csv(const std::string& csv_path, const std::vector<std::string>& columns,
                            const std::string& out_png, const std::string& by) {
  PlotReport report;
  plot_png(build_spec(csv_path, columns, out_png, by, report));
  return report;
}

}  // namespace beltsim::plot
