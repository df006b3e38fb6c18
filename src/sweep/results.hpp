// The results of a sweep's points and their summary (docs/sweeps.md).
//
// A point's folder DIR/<id>/ holds what its runs wrote and, written last and whole (created
// unnamed, then renamed: io/output_dir.hpp), point.csv: a header and one row,
//   point,<parameter>...,status,<figure>...
// Cells are quoted as CSV (csv_text), so a value with commas, quotes or line breaks reads back
// exactly. The status is "ok", "diverged at t = T s" or "error: message" (one line). A point is done when
// its point.csv says ok for the same parameters; any other point runs again when the sweep does.
// A sweep that runs its points, merges the summary or writes its Slurm jobs holds DIR first
// (claim_sweep_folder): a second one on the same folder is refused rather than run the points the
// first is running.
// summary.csv merges every point's row in the points' order (a point with no point.csv: "not run";
// the figures are the union of every point's, in the order they first come).
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "io/output_dir.hpp"
#include "sweep/points.hpp"

namespace beltsim::sweep {

struct PointResult {
  std::string status = "ok";
  std::vector<std::pair<std::string, std::string>> figures;  // name, text (numbers in full precision)
  bool ok() const { return status == "ok"; }
};

inline constexpr const char* kPointFile = "point.csv";
inline constexpr const char* kSummaryFile = "summary.csv";

// "error: " + message, the message on one line
std::string error_status(const std::string& message);

// DIR/<id>/point.csv written whole (the folder made when missing); output_error on failure
void write_point_result(const std::string& dir, const Point& p, const PointResult& r);
// what DIR/<id>/point.csv says of p; nullopt when it is missing, unreadable, or written for other
// parameters (the sweep changed)
std::optional<PointResult> read_point_result(const std::string& dir, const Point& p);

// r, or when a figure's name is one point.csv and summary.csv already have for a column (point,
// status, a parameter, an earlier figure) a failed result that names it: a file would hold two
// columns of one name
PointResult unique_columns(const Point& p, PointResult r);

// DIR, made when missing and claimed for this process until the object is destroyed (the lock
// of io/output_dir.hpp); throws std::runtime_error naming DIR when another sweep holds it
OutputDir claim_sweep_folder(const std::string& dir);

struct SummaryCounts {
  int ok = 0, failed = 0, not_run = 0;
};
// DIR/summary.csv written whole from every point's point.csv
SummaryCounts write_summary(const std::string& dir, const std::vector<Point>& points);

}  // namespace beltsim::sweep
