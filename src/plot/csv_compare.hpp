// Two CSV files of numbers (timeseries.csv of two runs, a run against a stored result) compared
// column by column, for `beltsim compare`.
//
// Columns are matched by name (their order may differ); both files must have the same names. A
// value a of A and b of B agree when |a − b| <= atol + rtol·max(|a|, |b|), with the column's own
// rtol and atol where given, else atol from the column's unit (io/units.hpp: the unit given for
// all columns of that unit, else the one given for all, else rtol times the unit's scale). Both
// NaN agree; NaN against a number is counted apart from the numbers that differ. Rows are aligned
// on the time column 't' when both files have one: the same times row by row, A's times all among
// B's (a short run against the first part of a long one) with those rows of B, otherwise B
// interpolated linearly onto A's times (B must cover them); without a 't' column, row by row.
#pragma once

#include <cstddef>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "plot/plot.hpp"

namespace beltsim::plot {

struct ColumnTolerance {
  double rtol = 1e-6, atol = 1e-12;
};

struct CsvTolerance {
  double rtol = 1e-6;                                                     // every column's
  std::optional<double> atol;                                             // every column's (else its unit's)
  std::map<std::string, double> unit_atol;                                // by unit (io/units.hpp's form): before atol
  std::map<std::string, std::optional<double>> column_rtol, column_atol;  // by column: before both
  std::set<std::string> skip;  // columns left out (both files must still have them)
  bool partial = false;        // A's times may span a part of B's (else both span the same times)
  // column's tolerances; its unit from its header (header_unit)
  ColumnTolerance of(const std::string& column) const;
};

// where a column's values lie furthest from agreeing
struct ValueAt {
  std::size_t row = 0;  // 1-based data row of A
  double t = 0, a = 0, b = 0;
};

struct ColumnResult {
  std::string name, unit;
  ColumnTolerance tol;
  double ratio = 0;          // the largest |a − b| / (atol + rtol·max(|a|, |b|)) of numbers: > 1 fails
  ValueAt worst;             // where
  std::size_t nan_rows = 0;  // rows with NaN against a number
  ValueAt first_nan;         // the first of them
  bool failed() const { return ratio > 1 || nan_rows > 0; }
};

struct CsvComparison {
  bool match = false;
  std::string reason;  // one line: why they differ, or what matched
  std::string note;    // "" or how the rows were aligned when the times differ
  bool timed = false;  // aligned on 't'
  std::size_t compared = 0;  // columns compared
  // the column whose numbers come closest to (or go furthest past) their tolerance; no name when
  // no number was compared
  ColumnResult worst;
  std::vector<ColumnResult> failing;  // columns with numbers past their tolerance or NaN mismatches
};

// a line for each failing column: its unit, its worst numbers and its NaN mismatches
std::vector<std::string> failing_lines(const CsvComparison& c);

// Throws std::invalid_argument for a per-column tolerance or a skipped column naming a column A
// lacks (with a suggestion), std::runtime_error for a 't' column that does not increase.
CsvComparison compare_csv(const Table& a, const Table& b, const CsvTolerance& tol);

}  // namespace beltsim::plot
