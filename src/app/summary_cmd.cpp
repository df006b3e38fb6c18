// `beltsim summary DIR`: a run's review figures over a window, printed as a table, and on request
// written to a CSV and drawn (commands.hpp, plot/summary.hpp).
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "app/commands.hpp"
#include "io/output_dir.hpp"
#include "plot/summary.hpp"

namespace beltsim::app {

namespace fs = std::filesystem;

std::string run_folder(const std::string& given) {
  // the run's timeseries.csv given for its folder: the folder ("cannot read
  // DIR/timeseries.csv/timeseries.csv: Not a directory" said nothing useful; a missing one is
  // named as given)
  std::error_code ec;
  if (fs::path(given).filename() != "timeseries.csv" || fs::is_directory(given, ec)) return given;
  const std::string dir = fs::path(given).parent_path().lexically_normal().string();
  return dir.empty() ? "." : dir;  // (the one in the folder beltsim runs in)
}

std::string run_csv(const std::string& given) {
  // a run's folder given for its timeseries.csv (summary takes the folder; plot said "cannot read
  // DIR: it is a folder"); a sweep's folder for its summary.csv, which plot draws too
  std::error_code ec;
  if (!fs::is_directory(given, ec)) return given;
  const fs::path dir(given);
  if (!fs::exists(dir / "timeseries.csv", ec) && fs::exists(dir / "summary.csv", ec))
    return (dir / "summary.csv").string();
  return (dir / "timeseries.csv").string();
}

int cmd_summary(const std::string& given, const Raw& raw) {
  if (raw.plot_out) require_png("--plot", *raw.plot_out);
  std::error_code ec;
  const std::string dir = run_folder(given);
  // a sweep's folder holds a run's folder per point, not a run's outputs
  if (!fs::exists(fs::path(dir) / "timeseries.csv", ec) && fs::exists(fs::path(dir) / "summary.csv", ec)) {
    std::fprintf(stderr,
                 "beltsim summary: %s is a sweep's folder (its summary.csv holds the sweep's figures): give the folder "
                 "of one of its points, %s/<point>\n",
                 dir.c_str(), dir.c_str());
    return 1;
  }
  const double from = raw.from ? number("--from", *raw.from) : -INFINITY;
  const double to = raw.to ? number("--to", *raw.to) : INFINITY;
  if (raw.from && raw.to && !(from <= to)) throw UsageError("--from " + *raw.from + " lies after --to " + *raw.to);
  plot::Summary s;
  try {
    s = plot::summarize(dir, from, to);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "beltsim summary: %s\n", e.what());
    return 1;
  }
  // a run closes parameters.csv with its end rows (end.status ...): without them it was killed
  // outright (SIGKILL, a crash) or still runs (a user's trial read a killed run's figures unwarned)
  if (s.end_status.empty())
    std::fprintf(stderr,
                 "beltsim summary: warning: %s/parameters.csv has no end rows: the run did not finish (it was killed, "
                 "or it is still running); these figures are of its samples so far\n",
                 dir.c_str());
  std::fputs(plot::summary_table(s).c_str(), stdout);
  std::fflush(stdout);
  // each output asked for is written, its missing folders made; one that cannot be written is
  // named and fails the exit status, and the other is still written
  int status = 0;
  for (const auto& [file, write] :
       {std::pair{raw.csv_out, &plot::write_summary_csv}, std::pair{raw.plot_out, &plot::plot_summary}}) {
    if (!file) continue;
    try {
      write(s, *file);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "beltsim summary: %s\n", e.what());
      mark_output_failure_shown(e.what());
      status = 1;
      continue;
    }
    std::printf("%s\n", file->c_str());
  }
  return status;
}

}  // namespace beltsim::app
