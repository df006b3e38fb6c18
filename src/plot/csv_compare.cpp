#include "plot/csv_compare.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "io/number_text.hpp"
#include "io/suggest.hpp"

namespace beltsim::plot {

namespace {

const std::string kTime = "t";

std::string num(double v) {
  // six significant digits: enough to see a difference a reader can act on
  char b[32];
  std::snprintf(b, sizeof b, "%.6g", v);
  return b;
}

std::vector<std::string> only_in(const Table& x, const Table& y) {
  std::vector<std::string> out;
  for (const std::string& n : x.names)
    if (!y.has(n)) out.push_back(n);
  return out;
}

void check_increasing(const Table& t) {
  const std::vector<double>& ts = t.column(kTime);
  for (std::size_t i = 1; i < ts.size(); ++i)
    if (!(ts[i] > ts[i - 1]))
      throw std::runtime_error(t.path + ": column 't' does not increase at data row " + std::to_string(i + 1) + " (" +
                               number_text(ts[i - 1]) + " then " + number_text(ts[i]) + ")");
}

// B's column y at A's time t by linear interpolation (t within B's times)
double interpolate(const std::vector<double>& tb, const std::vector<double>& y, double t) {
  const auto it = std::lower_bound(tb.begin(), tb.end(), t);
  const std::size_t k = it - tb.begin();
  if (k < tb.size() && tb[k] == t) return y[k];
  const double w = (t - tb[k - 1]) / (tb[k] - tb[k - 1]);
  return (1 - w) * y[k - 1] + w * y[k];
}

// "a, b, c" or "a, b, c, d, e and 7 more": a reason stays one readable line
std::string some(const std::vector<std::string>& names) {
  constexpr std::size_t kShown = 5;
  if (names.size() <= kShown + 1) return join(names);
  return join(std::vector<std::string>(names.begin(), names.begin() + kShown)) + " and " +
         std::to_string(names.size() - kShown) + " more";
}

}  // namespace

const ColumnTolerance& CsvTolerance::of(const std::string& column) const {
  const auto it = columns.find(column);
  return it == columns.end() ? all : it->second;
}

CsvComparison compare_csv(const Table& a, const Table& b, const CsvTolerance& tol) {
  auto require = [&](const std::string& option, const std::string& name) {
    if (!a.has(name))
      throw std::invalid_argument(option + " " + name + ": " + a.path + " has no column '" + name + "'" +
                                  did_you_mean(name, a.names) + "; its columns: " + join(a.names));
  };
  for (const auto& [name, t] : tol.columns) require("--col-tol", name);
  for (const std::string& name : tol.skip) require("--skip", name);
  CsvComparison c;
  const std::vector<std::string> a_only = only_in(a, b), b_only = only_in(b, a);
  if (!a_only.empty() || !b_only.empty()) {
    c.reason = "the columns differ:";
    if (!a_only.empty()) c.reason += " only in " + a.path + ": " + some(a_only) + (b_only.empty() ? "" : ";");
    if (!b_only.empty()) c.reason += " only in " + b.path + ": " + some(b_only);
    return c;
  }
  const std::size_t rows = a.columns.empty() ? 0 : a.columns[0].size();
  const std::size_t rows_b = b.columns.empty() ? 0 : b.columns[0].size();
  const bool timed = a.has(kTime);
  bool interpolated = false;
  if (timed) {
    check_increasing(a);
    check_increasing(b);
    const std::vector<double>&ta = a.column(kTime), &tb = b.column(kTime);
    interpolated = ta != tb;
    if (interpolated) {
      if (rows_b < 2 || rows == 0 || ta.front() < tb.front() || ta.back() > tb.back()) {
        c.reason = "the times differ and " + b.path + " (t in [" + (rows_b ? num(tb.front()) : "") + ", " +
                   (rows_b ? num(tb.back()) : "") + "] s, " + std::to_string(rows_b) + " rows) does not cover " +
                   a.path + "'s" + (rows ? " [" + num(ta.front()) + ", " + num(ta.back()) + "] s" : " (no rows)");
        return c;
      }
      c.note = "the times differ (" + std::to_string(rows) + " rows in " + a.path + ", " + std::to_string(rows_b) +
               " in " + b.path + "): " + b.path + " interpolated linearly onto " + a.path + "'s times";
    }
  } else if (rows != rows_b) {
    c.reason = "the row counts differ: " + std::to_string(rows) + " in " + a.path + ", " + std::to_string(rows_b) +
               " in " + b.path + " (no 't' column to align them on)";
    return c;
  }
  c.worst_ratio = -1;
  for (std::size_t k = 0; k < a.names.size(); ++k) {
    const std::string& name = a.names[k];
    if ((timed && name == kTime) || tol.skip.count(name)) continue;
    const std::vector<double>&ya = a.columns[k], &yb = b.column(name);
    const ColumnTolerance& ct = tol.of(name);
    bool failed = false;
    for (std::size_t i = 0; i < rows; ++i) {
      const double x = ya[i], y = interpolated ? interpolate(b.column(kTime), yb, a.column(kTime)[i]) : yb[i];
      double ratio;
      if (std::isnan(x) && std::isnan(y))
        ratio = 0;
      else if (std::isnan(x) || std::isnan(y))
        ratio = std::numeric_limits<double>::infinity();
      else if (x == y)
        ratio = 0;  // also equal infinities
      else {
        const double allowed = ct.atol + ct.rtol * std::max(std::abs(x), std::abs(y));
        ratio = allowed > 0 ? std::abs(x - y) / allowed : std::numeric_limits<double>::infinity();
        if (std::isnan(ratio)) ratio = std::numeric_limits<double>::infinity();  // inf against a finite value
      }
      failed = failed || ratio > 1;
      if (ratio > c.worst_ratio) {
        c.worst_ratio = ratio, c.worst_column = name, c.worst_row = i + 1;
        c.worst_t = timed ? a.column(kTime)[i] : 0, c.worst_a = x, c.worst_b = y;
      }
    }
    if (failed) c.failing_columns.push_back(name);
  }
  c.match = c.failing_columns.empty();
  std::size_t compared = a.names.size() - (timed ? 1 : 0);
  for (const std::string& name : tol.skip) compared -= name != kTime;
  if (c.worst_column.empty()) {
    c.reason = "no values to compare (" + std::to_string(compared) + " columns, " + std::to_string(rows) + " rows)";
    c.worst_ratio = 0;
    return c;
  }
  const ColumnTolerance& wt = tol.of(c.worst_column);
  const std::string left_out =
      tol.skip.empty() ? "" : " (left out: " + some(std::vector<std::string>(tol.skip.begin(), tol.skip.end())) + ")";
  const std::string agree =
      std::to_string(compared) + " columns" + left_out + " agree at " + std::to_string(rows) + (timed ? " times" : " rows");
  const std::string at = c.worst_column + (timed ? " at t = " + num(c.worst_t) + " s (row " : " at row ") +
                         std::to_string(c.worst_row) + (timed ? ")" : "") + ": " + num(c.worst_a) + " vs " +
                         num(c.worst_b);
  const std::string tols = "rtol " + num(wt.rtol) + ", atol " + num(wt.atol);
  if (c.match && c.worst_ratio == 0) {
    c.reason = agree + ": every value equal";
  } else if (c.match) {
    c.reason =
        agree + "; closest to its tolerance: " + at + ", " + num(c.worst_ratio) + " of its tolerance (" + tols + ")";
  } else {
    c.reason = std::to_string(c.failing_columns.size()) + " of " + std::to_string(compared) + " columns differ (" +
               some(c.failing_columns) + "); worst: " + at + ", |a - b| = " + num(std::abs(c.worst_a - c.worst_b)) +
               ", " +
               (std::isinf(c.worst_ratio) ? std::string("beyond any tolerance")
                                          : num(c.worst_ratio) + " times its tolerance") +
               " (" + tols + ")";
  }
  return c;
}

}  // namespace beltsim::plot
