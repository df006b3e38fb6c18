#include "plot/csv_compare.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "io/number_text.hpp"
#include "io/suggest.hpp"
#include "io/units.hpp"

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

ColumnTolerance CsvTolerance::of(const std::string& column) const {
  const std::string unit = header_unit(column);
  ColumnTolerance t;
  const auto r = column_rtol.find(column);
  t.rtol = r != column_rtol.end() && r->second ? *r->second : rtol;
  const auto a = column_atol.find(column);
  const auto u = unit_atol.find(unit);
  if (a != column_atol.end() && a->second)
    t.atol = *a->second;
  else if (u != unit_atol.end())
    t.atol = u->second;
  else if (atol)
    t.atol = *atol;
  else
    t.atol = t.rtol * unit_scale(unit);
  return t;
}

namespace {

// one column compared: ya against yb (B's values at A's rows)
ColumnResult compare_column(const std::string& name, const ColumnTolerance& ct, const std::vector<double>& ya,
                            const std::vector<double>& yb, const std::vector<double>* t) {
  ColumnResult r{name, header_unit(name), ct, -1, {}, 0, {}};
  for (std::size_t i = 0; i < ya.size(); ++i) {
    const double x = ya[i], y = yb[i];
    const ValueAt at{i + 1, t ? (*t)[i] : 0, x, y};
    if (std::isnan(x) != std::isnan(y)) {
      if (r.nan_rows++ == 0) r.first_nan = at;
      continue;
    }
    double ratio = 0;  // both NaN, or equal (also equal infinities)
    if (!std::isnan(x) && x != y) {
      const double allowed = ct.atol + ct.rtol * std::max(std::abs(x), std::abs(y));
      ratio = allowed > 0 ? std::abs(x - y) / allowed : std::numeric_limits<double>::infinity();
      if (std::isnan(ratio)) ratio = std::numeric_limits<double>::infinity();  // inf against a finite value
    }
    if (ratio > r.ratio) r.ratio = ratio, r.worst = at;
  }
  return r;
}

std::string where(const ValueAt& v, bool timed) {
  return (timed ? "at t = " + num(v.t) + " s (row " + std::to_string(v.row) + ")" : "at row " + std::to_string(v.row)) +
         ": " + num(v.a) + " vs " + num(v.b);
}

std::string tols_text(const ColumnResult& r) {
  return "rtol " + num(r.tol.rtol) + ", atol " + num(r.tol.atol) + (r.unit.empty() ? "" : " " + r.unit);
}

std::string times_text(double ratio) {
  return std::isinf(ratio) ? std::string("beyond any tolerance") : num(ratio) + " times its tolerance";
}

// "NaN against a number at 3 times, the first at t = 0 s (row 1): 0 vs nan"
std::string nan_text(const ColumnResult& r, bool timed) {
  return "NaN against a number at " + std::to_string(r.nan_rows) + (timed ? " time" : " row") +
         (r.nan_rows == 1 ? "" : "s") + ", the first " + where(r.first_nan, timed);
}

// the one line of a comparison that ran to its end
std::string reason_text(const CsvComparison& c, std::size_t rows, const std::set<std::string>& skip) {
  std::vector<std::string> numeric, nans;
  const ColumnResult* first_nan = nullptr;
  for (const ColumnResult& r : c.failing) {
    if (r.ratio > 1) numeric.push_back(r.name);
    if (r.nan_rows == 0) continue;
    nans.push_back(r.name);
    if (!first_nan || r.first_nan.row < first_nan->first_nan.row) first_nan = &r;
  }
  const std::string left_out =
      skip.empty() ? "" : " (left out: " + some(std::vector<std::string>(skip.begin(), skip.end())) + ")";
  const std::string of = " of " + std::to_string(c.compared) + " columns";
  if (c.worst.name.empty() && nans.empty())
    return "no values to compare (" + std::to_string(c.compared) + " columns, " + std::to_string(rows) + " rows)";
  const std::string at = c.worst.name + " " + where(c.worst.worst, c.timed);
  if (c.match) {
    const std::string agree = std::to_string(c.compared) + (c.compared == 1 ? " column" : " columns") + left_out +
                              (c.compared == 1 ? " agrees at " : " agree at ") + std::to_string(rows) +
                              (c.timed ? (rows == 1 ? " time" : " times") : (rows == 1 ? " row" : " rows"));
    if (c.worst.ratio == 0) return agree + ": every value equal";
    return agree + "; closest to its tolerance: " + at + ", " + num(c.worst.ratio) + " of its tolerance (" +
           tols_text(c.worst) + ")";
  }
  std::string line;
  if (!numeric.empty())
    line = std::to_string(numeric.size()) + of + " differ (" + some(numeric) + "); worst: " + at +
           ", |a - b| = " + num(std::abs(c.worst.worst.a - c.worst.worst.b)) + ", " + times_text(c.worst.ratio) + " (" +
           tols_text(c.worst) + ")";
  if (!nans.empty()) {
    if (!line.empty()) line += "; and ";
    const std::size_t n = numeric.empty() ? c.compared : nans.size();  // the number before "columns"
    const std::string columns = n == 1 ? " column" : " columns";
    line += "NaN against a number in " + std::to_string(nans.size()) +
            (numeric.empty() ? " of " + std::to_string(c.compared) + columns : columns) + " (" + some(nans) +
            "), the first in " + first_nan->name + " " + where(first_nan->first_nan, c.timed);
    if (numeric.empty()) line += "; every number within its tolerance";
  }
  return line;
}

}  // namespace

std::vector<std::string> failing_lines(const CsvComparison& c) {
  std::vector<std::string> lines;
  for (const ColumnResult& r : c.failing) {
    // the unit after the name, unless the header names it already ("load [N]": it read "load [N] [N]")
    const std::string head =
        "  " + r.name + (bracketed_unit(r.name) ? "" : " [" + (r.unit.empty() ? "1" : r.unit) + "]") + ": ";
    if (r.ratio > 1)
      lines.push_back(head + "worst " + where(r.worst, c.timed) + ", |a - b| = " +
                      num(std::abs(r.worst.a - r.worst.b)) + ", " + times_text(r.ratio) + " (" + tols_text(r) + ")");
    if (r.nan_rows > 0) lines.push_back(head + nan_text(r, c.timed));
  }
  return lines;
}

CsvComparison compare_csv(const Table& a, const Table& b, const CsvTolerance& tol) {
  auto require = [&](const std::string& option, const std::string& name) {
    if (!a.has(name))
      throw std::invalid_argument(option + " " + name + ": " + a.path + " has no column '" + name + "'" +
                                  did_you_mean(name, a.names) + "; its columns: " + join(a.names));
  };
  for (const auto& [name, t] : tol.column_rtol) require("--col-tol", name);
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
  c.timed = a.has(kTime);
  bool interpolated = false;
  std::vector<std::size_t> rows_of_b;  // when A's times are some of B's: B's row (from 0) of each
  if (c.timed) {
    check_increasing(a);
    check_increasing(b);
    const std::vector<double>&ta = a.column(kTime), &tb = b.column(kTime);
    // A's times all among B's (a short run against the first part of a long one at the same sample
    // times, or a coarser sample of the same run): compared with those rows, nothing interpolated
    if (ta != tb && rows > 0 && rows < rows_b) {
      for (std::size_t i = 0, j = 0; i < rows; ++i) {
        while (j < rows_b && tb[j] < ta[i]) ++j;
        if (j == rows_b || tb[j] != ta[i]) break;
        rows_of_b.push_back(j);
      }
      if (rows_of_b.size() != rows) rows_of_b.clear();
    }
    const bool some_of_b = !rows_of_b.empty();
    interpolated = ta != tb && !some_of_b;
    if (ta != tb) {
      if (rows_b < 2 || rows == 0 || ta.front() < tb.front() || ta.back() > tb.back()) {
        c.reason = "the times differ and " + b.path + " (t in [" + (rows_b ? num(tb.front()) : "") + ", " +
                   (rows_b ? num(tb.back()) : "") + "] s, " + std::to_string(rows_b) + " rows) does not cover " +
                   a.path + "'s" + (rows ? " [" + num(ta.front()) + ", " + num(ta.back()) + "] s" : " (no rows)");
        return c;
      }
      // a run that ends early (a golden test's scenario shortened by mistake) is not a match unless
      // asked for (a short run against the first part of a long one): the ends agree to rounding
      const double slack = 1e-9 * std::max({1.0, std::abs(tb.front()), std::abs(tb.back())});
      const bool spans = std::abs(ta.front() - tb.front()) <= slack && std::abs(ta.back() - tb.back()) <= slack;
      if (!spans && !tol.partial) {
        c.reason = "the times differ: " + a.path + " spans t in [" + num(ta.front()) + ", " + num(ta.back()) + "] s, " +
                   b.path + " [" + num(tb.front()) + ", " + num(tb.back()) + "] s (--partial compares " + a.path +
                   " with the part of " + b.path + " it spans)";
        return c;
      }
      if (some_of_b) {
        const std::string n = std::to_string(rows), n_b = std::to_string(rows_b);
        const bool run = rows_of_b.back() - rows_of_b.front() + 1 == rows;  // consecutive rows
        c.note = run ? a.path + " spans a part of " + b.path + "'s times: its " + n + " times are " + b.path +
                           "'s rows " + std::to_string(rows_of_b.front() + 1) + " to " +
                           std::to_string(rows_of_b.back() + 1) + " of " + n_b + ", compared row by row"
                     : a.path + "'s " + n + " times are among " + b.path + "'s " + n_b +
                           (spans ? "" : " (" + a.path + " spans a part of them)") + ", compared at those rows";
        c.note += " (nothing interpolated)";
      } else {
        c.note = "the times differ (" + std::to_string(rows) + " rows in " + a.path + ", " + std::to_string(rows_b) +
                 " in " + b.path + (spans ? "" : "; " + a.path + " spans a part of " + b.path + "'s times") +
                 "): " + b.path + " interpolated linearly onto " + a.path + "'s times";
      }
    }
  } else if (rows != rows_b) {
    c.reason = "the row counts differ: " + std::to_string(rows) + " in " + a.path + ", " + std::to_string(rows_b) +
               " in " + b.path + " (no 't' column to align them on)";
    return c;
  }
  const std::vector<double>* t = c.timed ? &a.column(kTime) : nullptr;
  c.worst.ratio = -1;
  for (std::size_t k = 0; k < a.names.size(); ++k) {
    const std::string& name = a.names[k];
    if ((c.timed && name == kTime) || tol.skip.count(name)) continue;
    ++c.compared;
    // B's value at each of A's rows (B may have more rows than A, or fewer when interpolated)
    const std::vector<double>& column_b = b.column(name);
    std::vector<double> yb(rows);
    for (std::size_t i = 0; i < rows; ++i)
      yb[i] = interpolated        ? interpolate(b.column(kTime), column_b, (*t)[i])
              : rows_of_b.empty() ? column_b[i]
                                  : column_b[rows_of_b[i]];
    const ColumnResult r = compare_column(name, tol.of(name), a.columns[k], yb, t);
    if (r.ratio > c.worst.ratio) c.worst = r;
    if (r.failed()) c.failing.push_back(r);
  }
  if (c.worst.ratio < 0) c.worst = ColumnResult{};  // no number compared
  c.match = c.failing.empty();
  c.reason = reason_text(c, rows, tol.skip);
  return c;
}

}  // namespace beltsim::plot
