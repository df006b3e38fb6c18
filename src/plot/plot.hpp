// Time histories drawn to a PNG by gnuplot (pngcairo, through plot/gnuplot.hpp: no shell), and a
// plain reader of timeseries.csv to feed it.
//
// Axes: x is "t [s]"; series are grouped by unit in the order they come. One unit: one y axis;
// two units: the first on the left axis (y), the second on the right (y2); three or more: one
// panel per unit, stacked, sharing the time axis. An axis is labelled "name [unit]" (one series),
// "<last dotted component> [unit]" (several series of one quantity, e.g. "omega [rad/s]") or the
// names joined by commas; no brackets for "" (dimensionless or unknown). The legend names each
// series (with its unit when there are two axes). Undefined values (NaN, inf) leave a gap.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "plot/table.hpp"

namespace beltsim::plot {

struct Series {
  std::string name, unit;   // unit "" for none
  std::vector<double> t, y;  // same length; t in s
  // the unit is not known (a sweep's own figure): the series gets an axis of its own (shared with
  // those of its name only), where two such series could differ by any scale
  bool unknown_unit = false;
  // the series is `name` at one value of another column, as the legend says ("load = 40 N·m"; a
  // sweep's summary drawn --by load); "" for none
  std::string variant = "";
  int colour = 0;  // its line type (1..: the colours of gnuplot.hpp); 0: its place in the spec
  int shape = 0;   // with points: the shape of its marks (0: a filled circle, 1: a square, ...)
};

// a vertical line across the plot at x with a label beside it (a run's event)
struct Mark {
  double x;
  std::string label;
};

struct PlotSpec {
  std::string title;          // "" for none
  std::vector<Series> series;
  std::string file;           // the PNG to write; its folder must exist
  int width = 1280, height = 720;  // [pixels]
  std::string x_label = "t [s]";   // the x axis (Series::t holds its values)
  bool points = false;             // a mark per value, unjoined (a sweep's points), instead of lines
  bool joined = false;             // with points: each series' marks joined by a line, in its order
  std::vector<Mark> marks = {};    // drawn where they fall inside the x range (every panel; labels on the top one)
};

// The plot of columns of a sweep's summary.csv (x the first, a mark per point): a figure's unit
// is the one summary_units.csv beside it gives, else the one in brackets at the end of its name,
// else unknown (its own axis). Fewer than two columns: an error whose example of a command line
// names columns the file has (plot_example). A column with no finite value is left out (as
// plot_summary_csv's); `by`: a series per value of that column (plot_summary_csv).
PlotSpec summary_spec(const std::string& csv_path, const std::vector<std::string>& columns, const std::string& out_png,
                      const std::string& by = "");
// "beltsim plot <csv> pretension 'slip_max [1]'": a command line that draws the summary, built
// from its columns (x: the one of `columns` given, else the parameter of most values; y: the first
// figure with a number that does not repeat a parameter); "" when it has no column of numbers
std::string plot_example(const std::string& csv_path, const std::vector<std::string>& columns);

// Writes spec.file, its missing folders made (as every output's). Throws std::runtime_error naming
// the problem: no series, a series with no finite values or t and y of different lengths, a file
// that cannot be written, gnuplot missing or failing (with gnuplot's own message).
void plot_png(const PlotSpec& spec);
// the gnuplot script plot_png runs, drawing spec into the PNG file `png`
std::string plot_script(const PlotSpec& spec, const std::string& png);

// The events of a run as marks: the rows `t,what,value` of an events.csv (outputs.hpp), labelled
// "what value" (shortened to 40 characters), the events of one time in one mark joined by "; ".
// No file: none; a row that is not `number,text,text` (a row cut by a kill) is left out.
std::vector<Mark> read_event_marks(const std::string& events_csv);

// What plot_csv left out of its picture, for the warnings it gives (left_out_warnings)
struct PlotReport {
  std::vector<std::string> columns;  // with no finite value there
  // a sweep summary's points without a mark, in its order: "point 1 (load=40, pretension=-100):
  // error: ..." (its status, shortened), "point 3 (...): ok, but without a value of slip"
  std::vector<std::string> points;
  std::string points_why;  // how many of them for what ("2 failed, 1 not run")
  size_t of_points = 0;    // the summary's points
  // what else the picture may hide (a series drawn by another column's value whose points differ
  // in a third: its line zigzags)
  std::vector<std::string> notes;
};

// Plots `columns` of a timeseries.csv (empty: every '<pulley>.omega' column) against its 't'
// column, samples with from_t <= t <= to_t only, units from io/units.hpp, titled with the CSV's path; the
// events of the events.csv beside it, if there is one, as vertical lines with their labels.
// A sweep's summary.csv (is_sweep_summary) is drawn as points: the first of `columns` is the x
// axis, the others y; its x is not time, so a from_t above -inf or a to_t below inf is refused (an error); a point
// without a value (failed, not run) is left out and named in the result with its status. A column
// with no finite value there (a creep undefined at rest, a figure every point failed to give) is
// left out of the picture and named in the result; when every column is, it fails naming them.
// `by` (a sweep's summary only: an error for a time series): one series per value of that column
// (plot_summary_csv).
PlotReport plot_csv(const std::string& csv_path, const std::vector<std::string>& columns, double from_t,
                    const std::string& out_png, double to_t = INFINITY, const std::string& by = "");

// plot_csv of a sweep's summary.csv (is_sweep_summary): summary_spec drawn, its columns with no
// finite value and its points without a mark left out and named. With `by`, a column not drawn
// (a parameter: an error when the file has no such column, or it is x or y), one series per value
// of it, told apart by colour (and by shape, the columns) and titled "load = 40" (with the
// column's unit, if it has one), its points joined by a line in x order; unjoined when a series
// has several points at one x (they differ in a third parameter too), as the report notes.
PlotReport plot_summary_csv(const std::string& csv_path, const std::vector<std::string>& columns,
                            const std::string& out_png, const std::string& by = "");

// leaves out the series with no finite (t, y) pair and returns their names; fails naming them
// when that is every series
std::vector<std::string> drop_empty(PlotSpec& spec, const std::string& csv_path);

// the warning for plot_csv's left-out columns ("" for none)
std::string left_out_warning(const std::vector<std::string>& names);
// the warnings of a PlotReport, one for its columns and one for its points (a line each, the
// first "left out of the plot, with nothing to draw: 2 of the 6 points (2 failed):"), then its
// notes; none when nothing was left out
std::vector<std::string> left_out_warnings(const PlotReport& report);

// at most n characters (UTF-8 code points) of s, the last an ellipsis when it was longer
std::string shortened(const std::string& s, size_t n);

}  // namespace beltsim::plot
