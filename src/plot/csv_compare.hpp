// Two CSV files of numbers (timeseries.csv of two runs, a run against a stored result) compared
// column by column, for `beltsim compare`.
//
// Columns are matched by name (their order may differ); both files must have the same names. A
// value a of A and b of B agree when |a − b| <= atol + rtol·max(|a|, |b|) (both NaN agree; one
// NaN does not), with the column's own rtol and atol where given. Rows are aligned on the time
// column 't' when both files have one: the same times row by row, otherwise B interpolated
// linearly onto A's times (B must cover them); without a 't' column, row by row.
#pragma once

#include <cstddef>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "plot/plot.hpp"

namespace beltsim::plot {

struct ColumnTolerance {
  double rtol = 1e-6, atol = 1e-12;
};

struct CsvTolerance {
  ColumnTolerance all;
  std::map<std::string, ColumnTolerance> columns;  // per-column overrides
  std::set<std::string> skip;                      // columns left out (both files must still have them)
  const ColumnTolerance& of(const std::string& column) const;
};

struct CsvComparison {
  bool match = false;
  std::string reason;  // one line: why they differ, or what matched
  std::string note;    // "" or how the rows were aligned when the times differ
  // the value closest to (or furthest past) its tolerance
  std::string worst_column;   // "" when nothing was compared
  std::size_t worst_row = 0;  // 1-based data row of A
  double worst_t = 0, worst_a = 0, worst_b = 0;
  double worst_ratio = 0;  // |a − b| / (atol + rtol·max(|a|, |b|)): > 1 fails
  std::vector<std::string> failing_columns;
};

// Throws std::invalid_argument for a per-column tolerance or a skipped column naming a column A
// lacks (with a suggestion), std::runtime_error for a 't' column that does not increase.
CsvComparison compare_csv(const Table& a, const Table& b, const CsvTolerance& tol);

}  // namespace beltsim::plot
