#include "sweep/results.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "io/csv_writer.hpp"
#include "io/output_dir.hpp"

namespace beltsim::sweep {

namespace {

std::string header(const Point& p) {
  std::string h = "point";
  for (const auto& [name, v] : p.params) {
    h += ',';
    h += csv_text(name);
  }
  return h + ",status";
}

std::string row(const Point& p, const std::string& status) {
  std::string r = csv_text(p.id);
  for (const auto& [name, v] : p.params) {
    r += ',';
    r += csv_text(value_text(v));
  }
  return r + "," + csv_text(status);
}

}  // namespace

std::string error_status(const std::string& message) {
  std::string m = message;
  std::replace(m.begin(), m.end(), '\n', ' ');
  std::replace(m.begin(), m.end(), '\r', ' ');
  return "error: " + m;
}

void write_point_result(const std::string& dir, const Point& p, const PointResult& r) {
  const OutputDir top(dir);
  const OutputDir folder(top, p.id);
  std::string h = header(p), v = row(p, r.status);
  for (const auto& [name, text] : r.figures) {
    h += ',';
    h += csv_text(name);
    v += ',';
    v += csv_text(text);
  }
  write_file_whole(folder, kPointFile, h + "\n" + v + "\n");
}

std::optional<PointResult> read_point_result(const std::string& dir, const Point& p) {
  std::ifstream f(std::filesystem::path(dir) / p.id / kPointFile, std::ios::binary);
  if (!f) return std::nullopt;
  std::ostringstream text;
  text << f.rdbuf();
  const std::vector<std::vector<std::string>> rows = csv_rows(text.str());
  if (rows.size() != 2) return std::nullopt;
  const std::vector<std::string>&names = rows[0], &values = rows[1];
  const std::size_t n = p.params.size();
  if (names.size() != values.size() || names.size() < n + 2 || names[0] != "point" || values[0] != p.id ||
      names[n + 1] != "status")
    return std::nullopt;
  for (std::size_t k = 0; k < n; ++k)
    if (names[k + 1] != p.params[k].first || values[k + 1] != value_text(p.params[k].second)) return std::nullopt;
  PointResult r;
  r.status = values[n + 1];
  for (std::size_t k = n + 2; k < names.size(); ++k) r.figures.emplace_back(names[k], values[k]);
  return r;
}

PointResult unique_columns(const Point& p, PointResult r) {
  std::vector<std::string> taken{"point", "status"};
  for (const auto& [name, v] : p.params) taken.push_back(name);
  for (const auto& [name, text] : r.figures) {
    if (std::find(taken.begin(), taken.end(), name) != taken.end())
      return {error_status("run(p) returned the figure '" + name +
                           "', a name point.csv and summary.csv already have for a column (point, status, a "
                           "parameter or an earlier figure); give it another"),
              {}};
    taken.push_back(name);
  }
  return r;
}

OutputDir claim_sweep_folder(const std::string& dir) {
  OutputDir top(dir);
  const std::string who = top.try_lock();
  if (!who.empty())
    throw std::runtime_error("the sweep folder " + dir + " is in use by " + who +
                             ": another sweep is running there; wait for it to end, or give this one a folder "
                             "of its own (--out)");
  return top;
}

SummaryCounts write_summary(const std::string& dir, const std::vector<Point>& points) {
  SummaryCounts counts;
  std::vector<std::optional<PointResult>> results;
  std::vector<std::string> figures;
  for (const Point& p : points) {
    results.push_back(read_point_result(dir, p));
    if (!results.back()) {
      ++counts.not_run;
      continue;
    }
    ++(results.back()->ok() ? counts.ok : counts.failed);
    for (const auto& [name, text] : results.back()->figures)
      if (std::find(figures.begin(), figures.end(), name) == figures.end()) figures.push_back(name);
  }
  std::string text;
  if (!points.empty()) {
    text = header(points[0]);
    for (const std::string& f : figures) {
      text += ',';
      text += csv_text(f);
    }
    text += "\n";
  }
  for (std::size_t i = 0; i < points.size(); ++i) {
    const auto& r = results[i];
    text += row(points[i], r ? r->status : "not run");
    for (const std::string& f : figures) {
      text += ",";
      if (!r) continue;
      const auto it = std::find_if(r->figures.begin(), r->figures.end(), [&](const auto& x) { return x.first == f; });
      if (it != r->figures.end()) text += csv_text(it->second);
    }
    text += "\n";
  }
  const OutputDir top(dir);
  write_file_whole(top, kSummaryFile, text);
  return counts;
}

}  // namespace beltsim::sweep
