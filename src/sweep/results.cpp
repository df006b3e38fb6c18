#include "sweep/results.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "io/csv_writer.hpp"
#include "io/output_dir.hpp"
#include "io/suggest.hpp"
#include "io/units.hpp"

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

namespace {

// point.csv's text
std::string point_csv(const Point& p, const PointResult& r) {
  std::string h = header(p, true), v = row(p, r.status) + "," + csv_text(r.inputs);
  for (const auto& [name, text] : r.figures) {
    h += ',';
    h += csv_text(name);
    v += ',';
    v += csv_text(text);
  }
  return h + "\n" + v + "\n";
}

}  // namespace

void write_point_result(const std::string& dir, const Point& p, const PointResult& r) {
  const OutputDir top(dir);
  const OutputDir folder(top, p.id);
  write_file_whole(folder, kPointFile, point_csv(p, r));
}

namespace {

// a point.csv as written: its id, its parameters (name, value as text) in its order, its result
struct PointFile {
  std::string id;
  std::vector<std::pair<std::string, std::string>> params;
  PointResult result;
};

std::optional<PointFile> read_point_file(const std::filesystem::path& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return std::nullopt;
  std::ostringstream text;
  text << f.rdbuf();
  const std::vector<std::vector<std::string>> rows = csv_rows(text.str());
  if (rows.size() != 2) return std::nullopt;
  const std::vector<std::string>&names = rows[0], &values = rows[1];
  const auto status = std::find(names.begin(), names.end(), "status");  // (no parameter takes the name)
  if (names.size() != values.size() || names.empty() || names[0] != "point" || status == names.end())
    return std::nullopt;
  PointFile pf;
  pf.id = values[0];
  const auto n = static_cast<std::size_t>(status - names.begin()) - 1;
  for (std::size_t k = 0; k < n; ++k) pf.params.emplace_back(names[k + 1], values[k + 1]);
  pf.result.status = values[n + 1];
  std::size_t k = n + 2;
  if (k < names.size() && names[k] == "inputs") pf.result.inputs = values[k++];  // (none: an older beltsim's)
  for (; k < names.size(); ++k) pf.result.figures.emplace_back(names[k], values[k]);
  return pf;
}

// a point's parameters as text, in the order of their names: the same for the same point under
// another number or another order of the --set lists
using Signature = std::vector<std::pair<std::string, std::string>>;
Signature signature(Signature params) {
  std::sort(params.begin(), params.end());
  return params;
}
Signature signature(const Point& p) {
  Signature s;
  for (const auto& [name, v] : p.params) s.emplace_back(name, value_text(v));
  return signature(std::move(s));
}

// the folders of DIR named as a point's id is (digits), sorted
std::vector<std::string> numbered_folders(const std::string& dir) {
  namespace fs = std::filesystem;
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (!name.empty() && name.find_first_not_of("0123456789") == std::string::npos &&
        it->symlink_status(ec).type() == fs::file_type::directory)
      names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace

std::optional<PointResult> read_point_result(const std::string& dir, const Point& p) {
  std::optional<PointFile> pf = read_point_file(std::filesystem::path(dir) / p.id / kPointFile);
  if (!pf || pf->id != p.id || pf->params.size() != p.params.size()) return std::nullopt;
  for (std::size_t k = 0; k < p.params.size(); ++k)
    if (pf->params[k].first != p.params[k].first || pf->params[k].second != value_text(p.params[k].second))
      return std::nullopt;
  return std::move(pf->result);
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

// the parameters' names in the header of a point.csv or summary.csv (empty when it is not one),
// read no further than the header (a summary of many points is read by each point's process)
std::vector<std::string> header_parameters(const std::filesystem::path& file) {
  std::ifstream f(file, std::ios::binary);
  if (!f) return {};
  std::string header;
  bool quoted = false;  // (a quoted name may hold a line break)
  for (char c; f.get(c) && (quoted || c != '\n');) {
    if (c == '"') quoted = !quoted;
    header += c;
  }
  const std::vector<std::vector<std::string>> rows = csv_rows(header);
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

std::string other_study_refusal(const std::string& dir, const std::vector<std::string>& names) {
  const std::vector<std::string> earlier = study_parameters(dir);
  std::vector<std::string> a = earlier, b = names;
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  if (earlier.empty() || a == b) return "";
  return dir + " holds another study (its points vary " + join(earlier) + ", these vary " + join(names) +
         "), whose summary.csv and points this one would replace: give it a folder of its own (--out DIR), or " +
         "remove " + dir + " first";
}

std::string study_folder_refusal(const std::string& what, const std::string& dir) {
  const std::vector<std::string> names = study_parameters(dir);
  if (names.empty()) return "";
  return what + ": the output folder " + dir + " holds a study of `beltsim sweep` (its summary.csv and a folder " +
         "per point; its points vary " + join(names) + "), among whose files this run's outputs would lie: give " +
         "the run a folder of its own (--out DIR, or out = ... in the script), or remove " + dir + " first";
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
  // the ok results in DIR's numbered folders by their parameters, read once a point has none of
  // its own: those of points that ran under another number
  std::optional<std::map<Signature, PointFile>> elsewhere;
  for (const Point& p : points) {
    PointCheck c = check_point(dir, p, now);
    // (a failure whose inputs are not known, written for a point whose process died, keeps its
    // status: it runs again in any case)
    if (c.result && !c.changed.empty() && (c.result->ok() || !c.result->inputs.empty()))
      c.result = PointResult{kOutdated + c.changed, {}, ""};
    if (!c.result) {
      if (!elsewhere) {
        elsewhere.emplace();
        for (const std::string& folder : numbered_folders(dir))
          if (std::optional<PointFile> pf = read_point_file(std::filesystem::path(dir) / folder / kPointFile);
              pf && pf->id == folder && pf->result.ok())
            elsewhere->emplace(signature(pf->params), std::move(*pf));
      }
      const auto it = elsewhere->find(signature(p));
      if (it != elsewhere->end() && it->second.id != p.id) {
        const std::string why = changed_inputs(it->second.result.inputs, now);
        c.result = PointResult{kOutdated + (why.empty() ? std::string(kRenumbered) : why), {}, ""};
      }
    }
    results.push_back(std::move(c.result));
  }
  return results;
}

namespace {

bool name_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-';
}

// A point's folder moved from DIR/NAME to DIR/earlier/TO: the paths that named it, as the sweep
// names the folder (DIR as given, and that path normalised and absolute), each with its new form
struct FolderMove {
  std::vector<std::pair<std::string, std::string>> forms;  // old, new

  FolderMove(const std::string& top, const std::string& name, const std::string& to) {
    namespace fs = std::filesystem;
    const fs::path from = fs::path(top) / name, now = fs::path(top) / kEarlierFolder / to;
    std::error_code ec;
    // (a pair, not a structured binding: clang 14 does not capture bindings in a lambda)
    for (const auto& move :
         {std::pair{from, now}, std::pair{from.lexically_normal(), now.lexically_normal()},
          std::pair{fs::absolute(from, ec).lexically_normal(), fs::absolute(now, ec).lexically_normal()}}) {
      const std::string old_form = move.first.string();
      if (!old_form.empty() &&
          std::find_if(forms.begin(), forms.end(), [&](const auto& f) { return f.first == old_form; }) == forms.end())
        forms.emplace_back(old_form, move.second.string());
    }
  }

  // text with each of the old paths, where it is a path of its own or the start of one (not
  // inside a longer name: DIR/1 is not the start of DIR/10 nor the end of /x/DIR/1), in its new form
  std::string apply(std::string text) const {
    for (const auto& [from, to] : forms) {
      std::string out;
      std::size_t at = 0;
      for (std::size_t k; (k = text.find(from, at)) != std::string::npos;) {
        const std::size_t end = k + from.size();
        const bool whole = (k == 0 || (!name_char(text[k - 1]) && text[k - 1] != '/')) &&
                           (end == text.size() || !name_char(text[end]));
        out.append(text, at, k - at).append(whole ? to : from);
        at = end;
      }
      text = out.append(text, at, std::string::npos);
    }
    return text;
  }

  // a CSV text's records that name the folder rewritten (their cells quoted as csv_text does),
  // every other record kept byte for byte
  std::string apply_csv(const std::string& text) const {
    std::string out;
    std::size_t start = 0;
    bool quoted = false;
    for (std::size_t k = 0; k <= text.size(); ++k) {
      if (k < text.size() && text[k] == '"') quoted = !quoted;
      if (k < text.size() && (quoted || text[k] != '\n')) continue;
      const std::string record = text.substr(start, k - start);
      std::vector<std::string> cells = csv_fields(record);
      bool changed = false;
      for (std::string& c : cells) {
        std::string renamed = apply(c);
        changed = changed || renamed != c;
        c = std::move(renamed);
      }
      if (changed) {
        for (std::size_t c = 0; c < cells.size(); ++c) out.append(c ? "," : "").append(csv_text(cells[c]));
      } else {
        out += record;
      }
      if (k < text.size()) out += '\n';
      start = k + 1;
    }
    return out;
  }
};

std::optional<std::string> read_text(const std::filesystem::path& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return std::nullopt;
  std::ostringstream text;
  text << f.rdbuf();
  return text.str();
}

// the files of a point's folder (about to move, FolderMove) that beltsim wrote naming it,
// rewritten to name its new place: point.csv's status and figures (the quick form's csv and
// parameters, a path run(p) returned, a status naming the point's files), and every
// parameters.csv in it or its subfolders (run.out). Anything else stays as written (log.txt,
// checkpoints, the files run(p) wrote itself). output_error when one cannot be written
void rename_in_folder(const OutputDir& folder, const FolderMove& move, bool top) {
  namespace fs = std::filesystem;
  std::vector<std::string> folders;
  std::error_code ec;
  for (fs::directory_iterator it(folder.path(), ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const fs::file_type type = it->symlink_status(ec).type();
    if (type == fs::file_type::directory) folders.push_back(name);
    if (type != fs::file_type::regular) continue;
    if (top && name == kPointFile) {
      std::optional<PointFile> pf = read_point_file(it->path());
      if (!pf) continue;
      PointResult r = pf->result;
      r.status = move.apply(r.status);
      for (auto& [figure, text] : r.figures) text = move.apply(text);
      if (r.status == pf->result.status && r.figures == pf->result.figures) continue;
      Point p;
      p.id = pf->id;
      for (const auto& [param, text] : pf->params) p.params.emplace_back(param, Value(text));
      write_file_whole(folder, kPointFile, point_csv(p, r));
    } else if (name == "parameters.csv") {
      const std::optional<std::string> text = read_text(it->path());
      if (!text) output_error(folder.file(name), "cannot read it to name the folder's new place");
      if (const std::string renamed = move.apply_csv(*text); renamed != *text) write_file_whole(folder, name, renamed);
    }
  }
  for (const std::string& name : folders) rename_in_folder(OutputDir(folder, name), move, false);
}

}  // namespace

std::vector<std::string> move_stale_folders(const OutputDir& top, const std::vector<Point>& points) {
  namespace fs = std::filesystem;
  std::vector<std::string> ids;
  for (const Point& p : points) ids.push_back(p.id);
  std::sort(ids.begin(), ids.end());
  std::vector<std::string> moved;
  std::optional<OutputDir> earlier;
  std::error_code ec;
  for (const std::string& name : numbered_folders(top.path())) {
    const fs::path from = fs::path(top.path()) / name;
    if (std::binary_search(ids.begin(), ids.end(), name) ||
        !(fs::exists(from / kPointFile, ec) || fs::exists(from / "log.txt", ec)))
      continue;
    if (!earlier) earlier.emplace(top, kEarlierFolder);
    std::string to = name;
    for (int k = 2; fs::symlink_status(fs::path(earlier->path()) / to, ec).type() != fs::file_type::not_found; ++k)
      to = name + "-" + std::to_string(k);
    // its files named as they will lie, before it moves: a rewriting that fails leaves it where
    // it was, for the next run to move
    rename_in_folder(OutputDir(top, name), FolderMove(top.path(), name, to), true);
    fs::rename(from, fs::path(earlier->path()) / to, ec);
    if (ec) output_error(earlier->file(to), "cannot move " + from.string() + " there: " + ec.message());
    moved.push_back(name);
  }
  return moved;
}

namespace {

// NAME in top's folder is a folder (not a link to one)
bool is_folder(const OutputDir& top, const std::string& name) {
  struct stat st {};
  return ::fstatat(top.fd(), name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 && S_ISDIR(st.st_mode);
}

// the folder NAME of top holds a point.csv
bool holds_result(const OutputDir& top, const std::string& name) {
  struct stat st {};
  return ::fstatat(top.fd(), (name + "/" + kPointFile).c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0;
}

// NAME of top removed with all it holds (links removed, never followed); none is no error
void remove_folder(const OutputDir& top, const std::string& name) {
  std::error_code ec;
  std::filesystem::remove_all(std::filesystem::path(top.path()) / name, ec);
  if (ec) output_error(top.file(name), "cannot remove it: " + ec.message());
}

// the folder FROM of top renamed TO, which must not exist
void rename_folder(const OutputDir& top, const std::string& from, const std::string& to) {
  if (top.has(to)) output_error(top.file(to), "cannot rename " + top.file(from) + " to it: it exists");
  if (::renameat(top.fd(), from.c_str(), top.fd(), to.c_str()) != 0)
    output_error(top.file(to), "cannot rename " + top.file(from) + " to it: " + std::strerror(errno));
}

}  // namespace

bool keep_earlier_folder(const OutputDir& top, const std::string& id) {
  if (!is_folder(top, id) || !holds_result(top, id)) return false;
  rename_folder(top, id, kKeptPrefix + id);
  return true;
}

void drop_earlier_folder(const OutputDir& top, const std::string& id) {
  remove_folder(top, kKeptPrefix + id);
}

void restore_earlier_folder(const OutputDir& top, const std::string& id) {
  remove_folder(top, id);
  rename_folder(top, kKeptPrefix + id, id);
}

std::vector<std::string> settle_earlier_folders(const OutputDir& top, const std::string& name) {
  namespace fs = std::filesystem;
  const std::string prefix = kKeptPrefix;
  std::vector<std::string> ids;
  std::error_code ec;
  for (fs::directory_iterator it(top.path(), ec), end; !ec && it != end; it.increment(ec)) {
    const std::string n = it->path().filename().string();
    if (n.size() > prefix.size() && n.compare(0, prefix.size(), prefix) == 0 &&
        n.find_first_not_of("0123456789", prefix.size()) == std::string::npos && is_folder(top, n))
      ids.push_back(n.substr(prefix.size()));
  }
  std::sort(ids.begin(), ids.end());
  std::vector<std::string> lines;
  for (const std::string& id : ids) {
    const std::string kept = top.file(prefix + id);
    if (const int fd = ::openat(top.fd(), id.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC); fd >= 0) {
      const std::string who = folder_holder(fd);
      ::close(fd);
      if (!who.empty())
        output_error(kept, "cannot settle it: " + top.file(id) + " is in use by " + who +
                               " (a point of an earlier sweep still ending?); run the sweep again once it has ended");
    }
    if (holds_result(top, id)) {
      drop_earlier_folder(top, id);
      lines.push_back("sweep " + name + ": point " + id + " had run again to a result when a sweep ended (killed " +
                      "outright?) before removing its earlier folder: " + kept + " removed");
    } else {
      restore_earlier_folder(top, id);
      lines.push_back("sweep " + name + ": point " + id + " was running again when a sweep ended (killed outright?): " +
                      "its earlier folder put back from " + kept + " to " + top.file(id) +
                      " (the partial one removed), with its earlier result");
    }
  }
  return lines;
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

std::string moved_line(const std::string& name, const OutputDir& top, const std::vector<std::string>& moved) {
  if (moved.empty()) return "";
  std::string names;
  for (std::size_t k = 0; k < moved.size() && k < 10; ++k) names += (k ? ", " : "") + moved[k];
  if (moved.size() > 10) names += ", ...";
  return "sweep " + name + ": " + std::to_string(moved.size()) +
         (moved.size() == 1 ? " folder of no point now moved to " : " folders of no point now moved to ") +
         top.file(kEarlierFolder) + "/: " + names;
}

std::string SummaryCounts::over_text(bool brief) const {
  if (over == 0) return "";
  if (brief) return " (" + std::to_string(over) + " past " + (over == 1 ? "its" : "their") + " check)";
  return ", " + std::to_string(over) +
         (over == 1 ? " of them past its accuracy check" : " of them past their accuracy check") + " (check.over in " +
         kSummaryFile + ": do not trust " + (over == 1 ? "its" : "their") + " answer at this tolerance)";
}

SummaryCounts write_summary(const OutputDir& top, const std::vector<Point>& points, const Results& results,
                            Figures named) {
  SummaryCounts counts;
  std::vector<std::string> figures;
  for (const auto& r : results) {
    counts.add(r);
    if (!r || r->outdated()) continue;
    for (const auto& [name, text] : r->figures)
      if (std::find(figures.begin(), figures.end(), name) == figures.end()) figures.push_back(name);
  }
  std::string text;
  // summary_units.csv: a parameter has none (its name is a Lua name, which holds no brackets); a
  // figure's as its kind of names gives it (Figures); point and status are text
  ColumnUnits units;
  if (!points.empty()) {
    text = header(points[0], false);
    units.emplace_back("point", std::nullopt);
    for (const auto& [name, v] : points[0].params) units.emplace_back(name, std::nullopt);
    units.emplace_back("status", std::nullopt);
    for (const std::string& f : figures) {
      text += ',';
      text += csv_text(f);
      units.emplace_back(f, named == Figures::kRunResult ? run_result_unit(f) : bracketed_unit(f));
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
  write_units_file(top, kSummaryFile, units);  // first: a column summary.csv names has its row there
  write_file_whole(top, kSummaryFile, text);
  return counts;
}

SummaryCounts write_summary(const std::string& dir, const std::vector<Point>& points, Definition now, Figures figures) {
  return write_summary(OutputDir(dir), points, current_results(dir, points, now), figures);
}

}  // namespace beltsim::sweep
