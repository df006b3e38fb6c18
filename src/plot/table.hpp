// CSV files read as columns of numbers: a run's timeseries.csv, a sweep's summary.csv (the
// files beltsim plot, summary and compare read).
#pragma once

#include <cstdio>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

namespace beltsim::plot {

// s without the blanks (spaces, tabs) at its ends
std::string trim_blanks(const std::string& s);

// a decimal number, "nan"/"inf" in any case, or empty (NaN), blanks about it ignored; hex and
// trailing text are not numbers (false)
bool parse_number_field(const std::string& text, double& out);

// The rows of a CSV stream one at a time (POSIX getline, one buffer for all): a row is a line
// without its '\n' (and a '\r' before it), and runs on over the line breaks inside a quoted cell
// (csv_text writes a value with one so: a sweep's values and figures, summary.csv).
class RowReader {
 public:
  explicit RowReader(std::FILE* f) : f_(f) {}
  ~RowReader();
  RowReader(const RowReader&) = delete;
  RowReader& operator=(const RowReader&) = delete;
  // false at the end of the file
  bool next(std::string& row);
  int lines() const { return lines_; }  // read so far: the number of the row's last line

 private:
  bool line(std::string& s);
  std::FILE* f_;
  char* buf_ = nullptr;
  size_t cap_ = 0;
  int lines_ = 0;
};

// A CSV file as columns: the first line is the header of names, every later line holds one
// number per name ("nan" or an empty field: NaN).
struct Table {
  std::string path;
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;       // columns[k] belongs to names[k]
  std::unordered_map<std::string, size_t> index;  // names[k] -> k (a lookup in constant time)
  // texts[k]: the fields of names[k] as written (blanks about them dropped) for a column read as
  // text (read_timeseries_csv's as_text), else empty
  std::vector<std::vector<std::string>> texts;

  bool has(std::string_view name) const;
  // throws std::runtime_error "<path> has no column 'x' (did you mean 'y'?); its columns: a, b, ..."
  // (column_suggestion)
  const std::vector<double>& column(std::string_view name) const;
  const std::vector<std::string>& text(std::string_view name) const;  // (empty unless read as text)

 private:
  size_t at(std::string_view name) const;
};

// a column's name less the unit in brackets at its end ("slip_max" of "slip_max [1]"; a name that
// is a bracket alone, "[N]", as it is)
std::string name_without_unit(const std::string& name);

// " (did you mean 'slip_max [1]'?)": the columns of `names` that are `name` but for a unit in
// brackets at the end of either (a sweep file's figures are named so, and the unit is the part
// easily left out), else those close to it (io/suggest.hpp), else those whose names less the
// brackets are close to it less its own; "" for none
std::string column_suggestion(const std::string& name, const std::vector<std::string>& names);

// Throws std::runtime_error "<path>:<line>: <reason>" for a bad row (wrong field count, a field
// that is not a decimal number) and for a missing, empty or unreadable file (a regular file only:
// io/input_file.hpp). With `only`, the fields of the other columns are not read (NaN): text such
// as a sweep's status may stand there. With `as_text`, the fields of the columns it names are kept
// as text (Table::texts), and read as numbers only when `only` names them too (else NaN). Time
// linear in the file's size, however many columns.
Table read_timeseries_csv(const std::string& path, const std::vector<std::string>* only = nullptr,
                          const std::vector<std::string>* as_text = nullptr);

// the names in a CSV file's header line (blanks about them dropped); none for an empty file.
// Throws as read_timeseries_csv for a file it cannot read.
std::vector<std::string> read_csv_header(const std::string& path);

// Whether a CSV file is a sweep's summary.csv (or a point's point.csv): its header starts "point,"
// and names a status column (sweep/results.hpp). Throws as read_timeseries_csv for a file it
// cannot read.
bool is_sweep_summary(const std::string& csv_path);

}  // namespace beltsim::plot
