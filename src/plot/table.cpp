#include "plot/table.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "io/csv_writer.hpp"
#include "io/input_file.hpp"
#include "io/suggest.hpp"

namespace beltsim::plot {

std::string trim_blanks(const std::string& s) {
  const size_t a = s.find_first_not_of(" \t");
  if (a == std::string::npos) return "";
  return s.substr(a, s.find_last_not_of(" \t") - a + 1);
}

bool parse_number_field(const std::string& text, double& out) {
  std::string s = trim_blanks(text);
  if (s.empty()) {
    out = std::nan("");
    return true;
  }
  size_t from = s[0] == '+' ? 1 : 0;
  const auto r = std::from_chars(s.data() + from, s.data() + s.size(), out, std::chars_format::general);
  return r.ec == std::errc() && r.ptr == s.data() + s.size();
}

RowReader::~RowReader() {
  std::free(buf_);
}

bool RowReader::next(std::string& row) {
  if (!line(row)) return false;
  bool quoted = false;
  for (size_t from = 0;;) {
    for (size_t i = from; i < row.size(); ++i) quoted = quoted != (row[i] == '"');
    if (!quoted) break;
    from = row.size() + 1;
    std::string more;
    if (!line(more)) break;  // a quote left open at the end: the cells say what is wrong
    row += '\n';
    row += more;
  }
  if (!row.empty() && row.back() == '\r') row.pop_back();
  return true;
}

bool RowReader::line(std::string& s) {
  const ssize_t n = ::getline(&buf_, &cap_, f_);
  if (n <= 0) return false;
  s.assign(buf_, static_cast<size_t>(n) - (buf_[n - 1] == '\n' ? 1 : 0));
  ++lines_;
  return true;
}

bool Table::has(std::string_view name) const {
  return index.count(std::string(name)) > 0;
}

const std::vector<double>& Table::column(std::string_view name) const {
  const auto it = index.find(std::string(name));
  if (it == index.end())
    throw std::runtime_error(path + " has no column '" + std::string(name) + "'" +
                             did_you_mean(std::string(name), names) + "; its columns: " + join(names));
  return columns[it->second];
}

Table read_timeseries_csv(const std::string& path, const std::vector<std::string>* only) {
  InputFile f(path);
  Table t;
  t.path = path;
  std::string line;
  std::vector<bool> wanted;  // per column: read its fields (with `only`: named there)
  RowReader rows(f.stream());
  for (int number_of_line = 1; rows.next(line); number_of_line = rows.lines() + 1) {
    if (trim_blanks(line).empty()) continue;
    std::vector<std::string> fields = csv_fields(line);
    const std::string where = path + ":" + std::to_string(number_of_line) + ": ";
    if (t.names.empty()) {
      for (auto& s : fields) {
        s = trim_blanks(s);
        if (s.empty()) throw std::runtime_error(where + "the header has an empty column name");
        if (!t.index.emplace(s, t.names.size()).second)
          throw std::runtime_error(where + "the header names '" + s + "' twice");
        t.names.push_back(s);
        wanted.push_back(!only || std::find(only->begin(), only->end(), s) != only->end());
      }
      t.columns.resize(t.names.size());
      continue;
    }
    if (fields.size() != t.names.size())
      throw std::runtime_error(where + "expected " + std::to_string(t.names.size()) + " fields as in the header, got " +
                               std::to_string(fields.size()));
    for (size_t k = 0; k < fields.size(); ++k) {
      double v = std::nan("");
      if (!wanted[k]) {
        t.columns[k].push_back(v);
        continue;
      }
      if (!parse_number_field(fields[k], v))
        throw std::runtime_error(where + "column '" + t.names[k] + "': '" + trim_blanks(fields[k]) +
                                 "' is not a number");
      t.columns[k].push_back(v);
    }
  }
  if (std::ferror(f.stream())) throw std::runtime_error("cannot read " + path + ": " + std::strerror(errno));
  if (t.names.empty()) throw std::runtime_error(path + " is empty (no header line)");
  return t;
}

bool is_sweep_summary(const std::string& csv_path) {
  InputFile f(csv_path);
  std::string line;
  if (!RowReader(f.stream()).next(line)) return false;
  const std::vector<std::string> names = csv_fields(line);
  return names.size() > 2 && names[0] == "point" && std::find(names.begin(), names.end(), "status") != names.end();
}

}  // namespace beltsim::plot
