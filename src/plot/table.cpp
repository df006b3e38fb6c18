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

std::string name_without_unit(const std::string& name) {
  const size_t open = name.rfind('[');
  if (name.empty() || name.back() != ']' || open == std::string::npos) return name;
  const std::string rest = trim_blanks(name.substr(0, open));
  return rest.empty() ? name : rest;
}

std::string column_suggestion(const std::string& name, const std::vector<std::string>& names) {
  // a sweep file's figures end with their unit, which is easily left out
  const std::string bare = name_without_unit(name);
  std::vector<std::string> same, bare_names;
  for (const std::string& n : names) {
    if (n != name && name_without_unit(n) == bare) same.push_back("'" + n + "'");
    bare_names.push_back(name_without_unit(n));
  }
  if (!same.empty()) return " (did you mean " + or_list(same) + "?)";
  if (std::string s = did_you_mean(name, names); !s.empty()) return s;
  // a slip of the finger in a name that lacks its unit too ("slip_mx" for "slip_max [1]")
  for (const std::string& close : close_names(bare, bare_names))
    for (size_t k = 0; k < names.size(); ++k)
      if (bare_names[k] == close && std::find(same.begin(), same.end(), "'" + names[k] + "'") == same.end())
        same.push_back("'" + names[k] + "'");
  return same.empty() ? "" : " (did you mean " + or_list(same) + "?)";
}

const std::vector<double>& Table::column(std::string_view name) const {
  return columns[at(name)];
}

const std::vector<std::string>& Table::text(std::string_view name) const {
  return texts[at(name)];
}

size_t Table::at(std::string_view name) const {
  const auto it = index.find(std::string(name));
  if (it == index.end())
    throw std::runtime_error(path + " has no column '" + std::string(name) + "'" +
                             column_suggestion(std::string(name), names) + "; its columns: " + join(names));
  return it->second;
}

Table read_timeseries_csv(const std::string& path, const std::vector<std::string>* only,
                          const std::vector<std::string>* as_text) {
  InputFile f(path);
  Table t;
  t.path = path;
  std::string line;
  std::vector<bool> wanted;  // per column: read its fields (with `only`: named there)
  std::vector<bool> text;    // per column: keep its fields as text (named in as_text)
  const auto named = [](const std::vector<std::string>* list, const std::string& s) {
    return list && std::find(list->begin(), list->end(), s) != list->end();
  };
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
        text.push_back(named(as_text, s));
        wanted.push_back(text.back() ? named(only, s) : !only || named(only, s));
      }
      t.columns.resize(t.names.size());
      t.texts.resize(t.names.size());
      continue;
    }
    if (fields.size() != t.names.size())
      throw std::runtime_error(where + "expected " + std::to_string(t.names.size()) + " fields as in the header, got " +
                               std::to_string(fields.size()));
    for (size_t k = 0; k < fields.size(); ++k) {
      double v = std::nan("");
      if (text[k]) t.texts[k].push_back(trim_blanks(fields[k]));
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

std::vector<std::string> read_csv_header(const std::string& path) {
  InputFile f(path);
  std::string line;
  if (!RowReader(f.stream()).next(line)) return {};
  std::vector<std::string> names = csv_fields(line);
  for (std::string& n : names) n = trim_blanks(n);
  return names;
}

bool is_sweep_summary(const std::string& csv_path) {
  const std::vector<std::string> names = read_csv_header(csv_path);
  return names.size() > 2 && names[0] == "point" && std::find(names.begin(), names.end(), "status") != names.end();
}

}  // namespace beltsim::plot
