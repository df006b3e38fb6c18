// `beltsim plot` of a sweep's summary.csv (plot.hpp): its figures against a parameter, a mark per
// point.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <set>
#include <stdexcept>

#include "io/suggest.hpp"
#include "io/units.hpp"
#include "plot/plot.hpp"

namespace beltsim::plot {

namespace {

// a word as a shell reads it back: quoted when it holds anything but letters, digits and ._-/+=:,@%
std::string shell_word(const std::string& s) {
  const bool plain = !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || std::string_view("._-/+=:,@%").find(c) != std::string::npos;
  });
  if (plain) return s;
  std::string q = "'";
  for (const char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

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
  std::string x = columns.empty() ? "" : columns[0];
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

PlotSpec summary_spec(const std::string& csv_path, const std::vector<std::string>& columns,
                      const std::string& out_png) {
  if (columns.size() < 2) {
    const std::string example = plot_example(csv_path, columns);
    throw std::runtime_error(csv_path + " is a sweep's summary: name the x column and at least one y column" +
                             (example.empty() ? "" : ", e.g. " + example) +
                             "; its columns: " + join(read_csv_header(csv_path)));
  }
  const Table table = read_timeseries_csv(csv_path, &columns);
  const std::vector<double>& x = table.column(columns[0]);
  for (const auto& name : columns) table.column(name);
  PlotSpec spec;
  spec.file = out_png;
  spec.points = true;
  // each column's unit as summary_units.csv beside it has it (sweep/results.hpp: the quick form's
  // figures from the program's table, a sweep file's from the brackets its names end with); a
  // summary written before that file came: the unit a header gives in brackets ("hub load [N]"),
  // else not known (unit_of's table would read "slip" as an element's, m/s, for a user's
  // difference of speeds)
  const std::optional<ColumnUnits> units = read_units_file(csv_path);
  const auto unit_of_column = [&](const std::string& h) {
    if (units)
      for (const auto& [column, unit] : *units)
        if (column == h) return unit;
    return bracketed_unit(h);
  };
  spec.x_label = columns[0];
  const std::filesystem::path cp(csv_path);
  spec.title = cp.has_parent_path() && cp.parent_path().has_filename()
                   ? (cp.parent_path().filename() / cp.filename()).string()
                   : cp.filename().string();
  for (size_t k = 1; k < columns.size(); ++k) {
    const std::string& h = columns[k];
    const std::optional<std::string> unit = unit_of_column(h);
    const std::string name = unit && bracketed_unit(h) ? name_without_unit(h) : h;  // the unit drawn once
    spec.series.push_back(Series{name, unit.value_or(""), x, table.column(h), !unit});
  }
  return spec;
}

std::vector<std::string> plot_summary_csv(const std::string& csv_path, const std::vector<std::string>& columns,
                                          const std::string& out_png) {
  PlotSpec spec = summary_spec(csv_path, columns, out_png);
  std::vector<std::string> dropped = drop_empty(spec, csv_path);
  plot_png(spec);
  return dropped;
}

}  // namespace beltsim::plot
