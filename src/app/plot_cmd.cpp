// `beltsim plot CSV|DIR [COLUMNS...] [--by PARAM]`: columns of a time series drawn to a PNG (commands.hpp).
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "app/commands.hpp"
#include "io/output_dir.hpp"
#include "plot/plot.hpp"
#include "term/term_image.hpp"

namespace beltsim::app {

namespace fs = std::filesystem;

int cmd_plot(const std::string& given, const std::vector<std::string>& columns, const Raw& raw,
             term::ImageMode images) {
  const std::string csv = run_csv(given);  // a run's folder for its timeseries.csv, as summary takes it
  const double from = raw.from ? number("--from", *raw.from) : -INFINITY;
  const double to = raw.to ? number("--to", *raw.to) : INFINITY;
  if (raw.from && raw.to && !(from <= to)) throw UsageError("--from " + *raw.from + " lies after --to " + *raw.to);
  if (raw.out) require_png("--out", *raw.out);
  const std::string png = raw.out ? *raw.out : (fs::path(csv).parent_path() / "plot.png").string();
  try {
    // a sweep's summary is drawn against a column of its own, so a start time would be ignored
    // there: refused as bad usage before anything is drawn (a file that cannot be read: exit 1)
    if ((raw.from || raw.to) && plot::is_sweep_summary(csv))
      throw UsageError(std::string(raw.from ? "--from" : "--to") + ": " + csv +
                       " is a sweep's summary, drawn against " +
                       (columns.empty() ? std::string("the column named first") : "its column " + columns[0]) +
                       ", not against time, so " + (raw.from ? "--from (a start time)" : "--to (an end time)") +
                       " does not apply; it is for a run's timeseries.csv");
    // --by: a sweep summary's column other than those drawn (known from the command line: bad
    // usage); its file's kind is known once it is read (one that cannot be: exit 1)
    if (raw.by && std::find(columns.begin(), columns.end(), *raw.by) != columns.end())
      throw UsageError("--by " + *raw.by + ": " + *raw.by + " is drawn, as " + (*raw.by == columns[0] ? "x" : "y") +
                       "; --by takes another column (a parameter of the sweep), a series per value of it");
    if (raw.by && !plot::is_sweep_summary(csv))
      throw UsageError("--by: " + csv +
                       " is a run's time series, drawn against t; --by (a series per value of a column) is for a "
                       "sweep's summary.csv");
    for (const std::string& w :
         plot::left_out_warnings(plot::plot_csv(csv, columns, from, png, to, raw.by.value_or(""))))
      std::fprintf(stderr, "beltsim plot: warning: %s\n", w.c_str());
  } catch (const UsageError&) {
    throw;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "beltsim: %s\n", e.what());
    mark_output_failure_shown(e.what());
    return 1;
  }
  // the picture on a terminal (or wherever BELTSIM_TERM_IMAGES forces it), then the path
  std::fflush(stdout);
  std::string why;
  if (!term::show_image_in_terminal(png, stdout, images, &why) && ::isatty(STDOUT_FILENO))
    std::fprintf(stderr, "beltsim plot: not shown in the terminal: %s\n", why.c_str());
  std::printf("%s\n", png.c_str());
  return 0;
}

}  // namespace beltsim::app
