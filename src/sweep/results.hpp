// The results of a sweep's points and their summary (docs/sweeps.md).
//
// A point's folder DIR/<id>/ holds what its runs wrote and, written last and whole (created
// unnamed, then renamed: io/output_dir.hpp), point.csv: a header and one row,
//   point,<parameter>...,status,inputs,<figure>...
// Cells are quoted as CSV (csv_text), so a value with commas, quotes or line breaks reads back
// exactly. The status is "ok", "diverged at t = T s: message" or "error: message" (one line); inputs is what defined
// the point (sweep/inputs.hpp). A point is done when its point.csv says ok for the same parameters
// and the same inputs as now; any other point runs again when the sweep does.
// A sweep that runs its points, merges the summary or writes its Slurm jobs holds DIR first
// (claim_sweep_folder): a second one on the same folder is refused rather than run the points the
// first is running.
// summary.csv merges every point's row in the points' order, without the inputs (a point with no
// point.csv: "not run"; one run with other inputs than now: "outdated: why", without figures; the
// figures are the union of every point's, in the order they first come).
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "io/output_dir.hpp"
#include "sweep/inputs.hpp"
#include "sweep/points.hpp"

namespace beltsim::sweep {

// the status summary.csv gives a point run with other inputs than now's, before why
inline constexpr const char* kOutdated = "outdated: ";
// why a point whose result is in another folder runs again (after kOutdated): its folder is its
// number in the sweep's order, and its files name that folder (parameters.csv, the quick form's
// figures csv and parameters, any path run(p) returned), so a result is not moved to a new number
inline constexpr const char* kRenumbered =
    "the points were numbered otherwise when they ran (a value added or removed before them in a list, or "
    "wider ids); a point's files name its folder, so its results are not moved to its new number";
// DIR's folder of the folders of points no point of the sweep has now (move_stale_folders)
inline constexpr const char* kEarlierFolder = "earlier";
struct PointResult {
  std::string status = "ok";
  std::vector<std::pair<std::string, std::string>> figures;  // name, text (numbers in full precision)
  std::string inputs = "";  // inputs_text (sweep/inputs.hpp); "" when unknown (a point whose process died)
  bool ok() const { return status == "ok"; }
  bool outdated() const { return status.rfind(kOutdated, 0) == 0; }
  // its figure check.over is true: the run's own error estimate passed the contract's bounds
  bool check_over() const {
    for (const auto& [name, text] : figures)
      if (name == "check.over") return text == "true";
    return false;
  }
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

// a point's result in DIR as it stands now
struct PointCheck {
  std::optional<PointResult> result;  // nullopt: no point.csv for these parameters
  std::string changed;                // why its inputs are not now's (changed_inputs); "" when they are
};
PointCheck check_point(const std::string& dir, const Point& p, Definition& now);

// r, or when a figure's name is one point.csv and summary.csv already have for a column (point,
// status, a parameter, an earlier figure) a failed result that names it: a file would hold two
// columns of one name
PointResult unique_columns(const Point& p, PointResult r);

// the names of the parameters of the study DIR holds: the columns of its summary.csv between
// `point` and `status`, else of the first point.csv in a folder of it; empty when it holds neither
std::vector<std::string> study_parameters(const std::string& dir);
// whether a study's folder may be written, both from study_parameters: "" when it may, else why not.
// A quick study of the parameters `names` (the default folder out/<script> is every study's of
// the script): DIR holds no study, or one of the same names (in any order)
std::string other_study_refusal(const std::string& dir, const std::vector<std::string>& names);
// a run's outputs, WHAT its key for the message ("run.out"): DIR holds no study. A run's files
// among a study's would be taken for part of it (and a run into out/<script> is every quick
// study's default folder)
std::string study_folder_refusal(const std::string& what, const std::string& dir);

// DIR, made when missing and claimed for this process until the object is destroyed (the lock
// of io/output_dir.hpp); throws std::runtime_error naming DIR when another sweep holds it
OutputDir claim_sweep_folder(const std::string& dir);

struct SummaryCounts {
  int ok = 0, failed = 0, not_run = 0;
  // of the ok: those whose run estimated its own error past the contract (check = true: the figure
  // check.over true, its log saying "do not trust this run's answer at this tolerance")
  int over = 0;
  // a point's result as summary.csv counts it: ok, failed, or not run (none, or outdated)
  void add(const std::optional<PointResult>& r) {
    ++(!r || r->outdated() ? not_run : r->ok() ? ok : failed);
    if (r && r->ok() && r->check_over()) ++over;
  }
  // after the ok count, "" when none: ", 1 of them past its accuracy check (check.over in
  // summary.csv: ...)"; brief (the progress line, redrawn in place), " (1 past its check)"
  std::string over_text(bool brief = false) const;
};
// what DIR holds of each point: its result, nullopt when it has none; a result with other
// inputs than now's as the status "outdated: why" without figures (but a failure recorded
// without its inputs, that of a point whose process died, as it is); a point with none in its
// folder whose parameters have an ok result in another numbered folder (it ran under another
// number) as "outdated: " + kRenumbered, or why its inputs are not now's
using Results = std::vector<std::optional<PointResult>>;
Results current_results(const std::string& dir, const std::vector<Point>& points, Definition& now);
// the numbered folders of DIR (top) that are no point's of now and hold a point's point.csv or
// log.txt (a point removed from the sweep, or numbered otherwise before), moved into
// DIR/earlier/ (as NAME, or NAME-2, ... when taken), so that they are not taken for results; their
// names, sorted. Before each moves, its point.csv (status, figures) and every parameters.csv in it
// are rewritten where they name it (DIR/NAME as top names it, or its absolute path) to name it at
// DIR/earlier/TO; the other files stay as written. output_error when one cannot be rewritten or
// moved (it is then left where it was, for the next run)
std::vector<std::string> move_stale_folders(const OutputDir& top, const std::vector<Point>& points);
// what a sweep says of them: "sweep NAME: 9 folders of no point now moved to DIR/earlier/: 0, 1, ..."
// ("" when none)
std::string moved_line(const std::string& name, const OutputDir& top, const std::vector<std::string>& moved);
// A point that runs again while its folder holds a point.csv (a result of an earlier run: ok,
// failed or outdated) runs in a folder of its own: the earlier folder is renamed aside to
// DIR/.kept-<id> (hidden, and no point's number, so neither the sweep's listing of the folders nor
// the summary takes it), the point runs in a new DIR/<id> (its files name that folder), and when
// the run ends with a result (its own, or the error of a process that died) the earlier folder is
// removed; when it is stopped first, its folder is removed and the earlier one renamed back, whole.
inline constexpr const char* kKeptPrefix = ".kept-";
// DIR/<id> renamed to DIR/.kept-<id> when it is a folder that holds a point.csv; whether it was.
// output_error when it cannot be (a .kept-<id> already there, a rename that fails)
bool keep_earlier_folder(const OutputDir& top, const std::string& id);
// the run again ended with a result: DIR/.kept-<id> removed (output_error when it cannot be)
void drop_earlier_folder(const OutputDir& top, const std::string& id);
// the run again stopped without one: DIR/<id> removed and DIR/.kept-<id> renamed to it
// (output_error when either cannot be)
void restore_earlier_folder(const OutputDir& top, const std::string& id);
// the folders DIR/.kept-<id> that a sweep ended without settling (killed outright while points
// ran again), settled as it would have: restored where DIR/<id> holds no point.csv (the run did not
// end), else removed (it ended with a result); what a sweep NAME says of each, a line each, sorted.
// output_error when one cannot be, or when a process still holds DIR/<id> (a point of that sweep
// still ending): nothing is changed of that point
std::vector<std::string> settle_earlier_folders(const OutputDir& top, const std::string& name);
// why the points with other inputs than now's run again: each reason (the status after
// "outdated: ") with how many points it holds for, in the order first met
using Reasons = std::vector<std::pair<std::string, int>>;
Reasons rerun_reasons(const Results& results);
// what a sweep says of them before it runs them (or puts them in a Slurm array), a line each:
// "sweep NAME: 6 points run again: the file /a/b.lua has changed"
std::vector<std::string> reason_lines(const std::string& name, const Reasons& reasons);
// whose names a sweep's figures are, for the units of summary_units.csv: a sweep file's run(p)
// names its own (a unit only where the name ends with one in brackets, "hub load [N]": "slip" is
// no element's m/s there); the quick form's are the fields of scene:run{}'s result table, whose
// units the program's table has (io/units.hpp, run_result_unit: omega.driver rad/s)
enum class Figures { kOwn, kRunResult };
// DIR/summary.csv written whole from results[k] of points[k] (an outdated point counted not run),
// and DIR/summary_units.csv
SummaryCounts write_summary(const OutputDir& top, const std::vector<Point>& points, const Results& results,
                            Figures figures);
// the same from every point's point.csv
SummaryCounts write_summary(const std::string& dir, const std::vector<Point>& points, Definition now, Figures figures);

}  // namespace beltsim::sweep
