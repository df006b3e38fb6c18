// The fuzz target over a sweep's values (issue 45): the fuzzer's bytes are the --set lists of
// `beltsim sweep` and what the points' runs return, and every value must come back exactly from
// every file it is written to: point.csv (read_point_result: a point whose file does not read back
// for its own parameters runs again on every resume) and summary.csv (read as CSV, and by `beltsim
// plot`'s reader, row for row). The input is lines; "\n" in a line stands for a line feed, "\r"
// for a carriage return, "\0" for a zero byte, "\\" for a backslash:
//   set KEY=V1,V2,..   a --set list (script::set_grid reads them all, as the command line does)
//   fig NAME=TEXT      a figure every point's run returns (TEXT as a string)
//   err MESSAGE        the points failed with this message (error_status)
// A refusal (std::invalid_argument from the lists, a grid of more than kMaxPoints points here) is
// no finding; values that do not read back are, and abort with both texts on stderr.
//
// Built as beltsim_fuzz_sweep with BELTSIM_FUZZ (scripts/setup.sh test fuzzes with it), and as
// beltsim_fuzz_sweep_replay (the normal build) which runs the seeds (tests/fuzz/sweeps/) through
// it as a ctest test with --each-accepted: every seed must be taken.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

#include "io/csv_writer.hpp"
#include "plot/plot.hpp"
#include "script/script_args.hpp"
#include "sweep/results.hpp"

namespace {

namespace fs = std::filesystem;
namespace sw = beltsim::sweep;

// points written per input: every value of a short grid, and few enough files per execution
constexpr size_t kMaxPoints = 12;

struct Folder {
  fs::path dir;
  Folder() { dir = fs::temp_directory_path() / ("beltsim_fuzz_sweep_" + std::to_string(getpid())); }
  ~Folder() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
};

std::string g_refusal;  // why the last input was refused, "" when it was taken

// the line with its escapes undone
std::string unescaped(const std::string& s) {
  std::string out;
  for (size_t i = 0; i < s.size(); ++i) {
    if (s[i] != '\\' || i + 1 == s.size()) {
      out += s[i];
      continue;
    }
    const char c = s[++i];
    out += c == 'n' ? '\n' : c == 'r' ? '\r' : c == '0' ? '\0' : c;
  }
  return out;
}

[[noreturn]] void finding(const std::string& what, const std::string& wrote, const std::string& read) {
  std::fprintf(stderr, "fuzz_sweep: %s\n  written: [%s]\n  read:    [%s]\n", what.c_str(), wrote.c_str(), read.c_str());
  std::abort();
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

std::string joined(const std::vector<std::string>& cells) {
  std::string s;
  for (const std::string& c : cells) s += (s.empty() ? "" : "|") + c;
  return s;
}

// what defined the points: a program and options of this harness's, no files
const sw::Inputs kInputs{"fuzz_sweep", "--set 'k=1,2'", {}};

// point.csv of each point reads back as written, for the point's own parameters
void check_points(const std::string& dir, const std::vector<sw::Point>& points, const sw::PointResult& given) {
  for (const sw::Point& p : points) {
    sw::PointResult r = sw::unique_columns(p, given);  // as the sweep does before it writes
    r.inputs = sw::inputs_text(kInputs);
    sw::write_point_result(dir, p, r);
    const std::optional<sw::PointResult> back = sw::read_point_result(dir, p);
    if (!back)
      finding("point " + p.id + "'s point.csv does not read back for its parameters (" + sw::params_text(p) + ")",
              slurp(fs::path(dir) / p.id / sw::kPointFile), "nothing");
    if (back->status != r.status) finding("point " + p.id + "'s status", r.status, back->status);
    if (back->inputs != r.inputs) finding("point " + p.id + "'s inputs", r.inputs, back->inputs);
    if (back->figures != r.figures)
      finding("point " + p.id + "'s figures", std::to_string(r.figures.size()), std::to_string(back->figures.size()));
  }
}

// summary.csv: a header and a row per point with each parameter's text, the status and the figures,
// as CSV and as `beltsim plot` reads it
void check_summary(const std::string& dir, const std::vector<sw::Point>& points) {
  sw::write_summary(dir, points, sw::Definition{kInputs.program, kInputs.options, {}, {}}, sw::Figures::kOwn);
  const std::string path = (fs::path(dir) / sw::kSummaryFile).string();
  const std::vector<std::vector<std::string>> rows = beltsim::csv_rows(slurp(path));
  if (rows.size() != points.size() + 1)
    finding("summary.csv's rows", std::to_string(points.size() + 1), std::to_string(rows.size()));
  const std::vector<std::string>& header = rows[0];
  for (size_t i = 0; i < points.size(); ++i) {
    const sw::Point& p = points[i];
    const std::vector<std::string>& row = rows[i + 1];
    if (row.size() != header.size())
      finding("summary.csv row " + std::to_string(i + 1) + "'s cells", joined(header), joined(row));
    const std::optional<sw::PointResult> r = sw::read_point_result(dir, p);
    std::vector<std::string> expected{p.id};
    for (const auto& [name, v] : p.params) expected.push_back(sw::value_text(v));
    expected.push_back(r->status);
    for (const auto& [name, text] : r->figures) expected.push_back(text);
    if (std::vector<std::string>(
            row.begin(), row.begin() + static_cast<std::ptrdiff_t>(std::min(row.size(), expected.size()))) != expected)
      finding("summary.csv row " + std::to_string(i + 1), joined(expected), joined(row));
  }
  // `beltsim plot summary.csv x y` reads it with the columns it draws; no column asked for here,
  // so only the rows' shape counts: one row per point, each with the header's cells. Plot trims the
  // header's names (a CSV written by hand: "t, a"), so it is asked only when each name is one it
  // can address as it stands: not empty, no blank at either end.
  for (const std::string& name : header)
    if (name.empty() || name.front() == ' ' || name.front() == '\t' || name.back() == ' ' || name.back() == '\t')
      return;
  const std::vector<std::string> none;
  const beltsim::plot::Table t = beltsim::plot::read_timeseries_csv(path, &none);
  if (t.names != header) finding("summary.csv's header as plot reads it", joined(header), joined(t.names));
  if (!t.columns.empty() && t.columns[0].size() != points.size())
    finding("summary.csv's rows as plot reads them", std::to_string(points.size()),
            std::to_string(t.columns[0].size()));
}

}  // namespace

extern "C" const char* BeltsimFuzzRefusal() {
  return g_refusal.c_str();
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const Folder f;
  g_refusal.clear();
  std::vector<std::string> sets;
  sw::PointResult given;
  const std::string text(reinterpret_cast<const char*>(data), size);
  for (size_t b = 0; b <= text.size();) {
    size_t e = text.find('\n', b);
    if (e == std::string::npos) e = text.size();
    const std::string line = text.substr(b, e - b);
    b = e + 1;
    const std::string what = line.substr(0, 4), rest = unescaped(line.size() > 4 ? line.substr(4) : "");
    if (what == "set ") sets.push_back(rest);
    if (what == "err ") given.status = sw::error_status(rest);
    if (what == "fig ") {
      const size_t eq = rest.find('=');
      given.figures.emplace_back(rest.substr(0, eq), eq == std::string::npos ? "" : rest.substr(eq + 1));
    }
  }
  std::vector<sw::Point> points;
  try {
    points = sw::grid_points(beltsim::script::set_grid(sets));
  } catch (const std::invalid_argument& e) {
    g_refusal = e.what();
    return 0;
  }
  if (points.size() > kMaxPoints) {
    g_refusal = std::to_string(points.size()) + " points, more than this harness writes";
    return 0;
  }
  std::error_code ec;
  fs::remove_all(f.dir, ec);
  check_points(f.dir.string(), points, given);
  check_summary(f.dir.string(), points);
  return 0;
}
