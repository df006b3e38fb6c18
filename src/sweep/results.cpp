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

// point.csv's columns and summary.csv's, without the figures
std::string header(const Point& p, bool inputs) {
  std::string h = "point";
  for (const auto& [name, v] : p.params) {
    h += ',';
    h += csv_text(name);
  }
  return h + (inputs ? ",status,inputs" : ",status");
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
  std::string h = header(p, true), v = row(p, r.status) + "," + csv_text(r.inputs);
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
  std::size_t k = n + 2;
  if (k < names.size() && names[k] == "inputs") r.inputs = values[k++];  // (none: an older beltsim's)
  for (; k < names.size(); ++k) r.figures.emplace_back(names[k], values[k]);
  return r;
}

PointCheck check_point(const std::string& dir, const Point& p, Definition& now) {
  PointCheck c;
  c.result = read_point_result(dir, p);
  if (c.result) c.changed = changed_inputs(c.result->inputs, now);
  return c;
}

PointResult unique_columns(const Point& p, PointResult r) {
  std::vector<std::string> taken{"point", "status", "inputs"};
  for (const auto& [name, v] : p.params) taken.push_back(name);
  for (const auto& [name, text] : r.figures) {
    if (std::find(taken.begin(), taken.end(), name) != taken.end())
      return {error_status("run(p) returned the figure '" + name +
                           "', a name point.csv and summary.csv already have for a column (point, status, "
                           "inputs, a parameter or an earlier figure); give it another"),
              {},
              r.inputs};
    taken.push_back(name);
  }
  return r;
}

namespace {

// the parameters' names in the header of a point.csv or summary.csv (empty when it is not one)
std::vector<std::string> header_parameters(const std::filesystem::path& file) {
  std::ifstream f(file, std::ios::binary);
  if (!f) return {};
  std::ostringstream text;
  text << f.rdbuf();
  const std::vector<std::vector<std::string>> rows = csv_rows(text.str());
  if (rows.empty() || rows[0].empty() || rows[0][0] != "point") return {};
  const auto status = std::find(rows[0].begin(), rows[0].end(), "status");
  if (status == rows[0].end()) return {};
  return std::vector<std::string>(rows[0].begin() + 1, status);
}

}  // namespace

std::vector<std::string> study_parameters(const std::string& dir) {
  namespace fs = std::filesystem;
  if (std::vector<std::string> names = header_parameters(fs::path(dir) / kSummaryFile); !names.empty()) return names;
  std::error_code ec;
  std::vector<fs::path> folders;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec))
    if (it->is_directory(ec)) folders.push_back(it->path());
  std::sort(folders.begin(), folders.end());
  for (const fs::path& f : folders)
    if (std::vector<std::string> names = header_parameters(f / kPointFile); !names.empty()) return names;
  return {};
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

Results current_results(const std::string& dir, const std::vector<Point>& points, Definition& now) {
  Results results;
  for (const Point& p : points) {
    PointCheck c = check_point(dir, p, now);
    // (a failure whose inputs are not known, written for a point whose process died, keeps its
    // status: it runs again in any case)
    if (c.result && !c.changed.empty() && (c.result->ok() || !c.result->inputs.empty()))
      c.result = PointResult{kOutdated + c.changed, {}, ""};
    results.push_back(std::move(c.result));
  }
  return results;
}

Reasons rerun_reasons(const Results& results) {
  Reasons reasons;
  for (const auto& r : results) {
    if (!r || !r->outdated()) continue;
    const std::string why = r->status.substr(std::string(kOutdated).size());
    auto it = std::find_if(reasons.begin(), reasons.end(), [&](const auto& x) { return x.first == why; });
    if (it == reasons.end())
      reasons.emplace_back(why, 1);
    else
      ++it->second;
  }
  return reasons;
}

std::vector<std::string> reason_lines(const std::string& name, const Reasons& reasons) {
  std::vector<std::string> lines;
  for (const auto& [why, n] : reasons)
    lines.push_back("sweep " + name + ": " + std::to_string(n) + (n == 1 ? " point runs" : " points run") +
                    " again: " + why);
  return lines;
}

SummaryCounts write_summary(const OutputDir& top, const std::vector<Point>& points, const Results& results) {
  SummaryCounts counts;
  std::vector<std::string> figures;
  for (const auto& r : results) {
    if (!r || r->outdated()) {
      ++counts.not_run;
      continue;
    }
    ++(r->ok() ? counts.ok : counts.failed);
    for (const auto& [name, text] : r->figures)
      if (std::find(figures.begin(), figures.end(), name) == figures.end()) figures.push_back(name);
  }
  std::string text;
  if (!points.empty()) {
    text = header(points[0], false);
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
  write_file_whole(top, kSummaryFile, text);
  return counts;
}

SummaryCounts write_summary(const std::string& dir, const std::vector<Point>& points, Definition now) {
  return write_summary(OutputDir(dir), points, current_results(dir, points, now));
}

}  // namespace beltsim::sweep
