// The picture of `beltsim wp`: error against wall time, log-log, one line per integrator with
// its points labelled by their rtol where a label overlaps no other label or point; the error is
// the metric's when the study has one, else the largest speed error (solid line, filled marks)
// and, unlabelled, the largest span-tension error (dashed, open marks: the accuracy contract holds
// the speeds to 3·rtol and the tensions to 10·rtol, docs/accuracy.md); runs that did not finish are
// crosses at their wall time in a band above the errors. Kept out of the engine (beltsim_sim
// launches no process): work_precision() writes the CSV, this draws the result.
//
// Two stages: wp_layout() computes what is drawn and where (no gnuplot, for tests), and
// wp_script() writes the gnuplot script that draws that layout.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "sim/work_precision.hpp"

namespace beltsim::plot {

// What the wp picture shows and where. Pixel positions are pixels of the 1000×700 picture,
// measured from the plot area's bottom-left corner, x right and y up; the plot area is
// area_w × area_h pixels.
struct WpLayout {
  struct Box {
    double x0, y0, x1, y1;  // [px] the lower-left and upper-right corners
    bool overlaps(const Box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
  };
  // one integrator's line: its name, colour ("#rrggbb") and gnuplot point type
  struct Series {
    std::string name, colour;
    int point_type = 0;
    bool any_finished = false;    // drawn as a line; else only named in the legend
    bool any_unfinished = false;  // has crosses above the errors
  };
  // a run's mark: a finished run at (wall time, error), or the cross of an integrator's
  // unfinished runs of about the same wall time at their wall time on the integrator's row above
  // the errors
  struct Point {
    double x, y;       // the data's coordinates: wall time [s] and error (or the row's height)
    double px, py;     // [px]
    std::string text;  // its label: the rtol, or the unfinished runs' rtols ("1e-05, 1e-06")
    size_t series;     // index in `series` (and in WpResult::integrators)
    bool finished;
    bool tension = false;  // a span-tension error (no label; dashed); else the speeds' or the metric's
    // past the accuracy contract's bound for its rtol (kCheckSpeedLimit·rtol for the speeds,
    // kCheckTensionLimit·rtol for the span tensions; only where it is promised, rtol <= kContractRtol,
    // and not for a metric): ringed
    bool past = false;
  };
  // a placed label: centred at (px, py) of its point plus (dx, dy), within `box`
  struct Label {
    size_t point;   // index in `points`
    double dx, dy;  // [px]
    Box box;
  };

  std::string title, y_title;
  double x_lo, x_hi, y_lo, y_hi;  // the axes' ranges: whole decades (wall time [s], error)
  double y_errors;                // the errors' top; unfinished runs are marked above it
  bool unfinished = false;        // any run did not finish (y_hi is then y_errors·10)
  double area_w, area_h;          // [px] the plot area
  std::vector<Series> series;     // one per integrator, in WpResult::integrators' order
  std::vector<Point> points;      // by series; within one the finished runs in the rows' order
  bool any_past = false;          // a point is past its bound (the legend names the ring)
  std::vector<Box> marks;         // each point's mark, as points
  std::vector<Box> line_boxes;    // small boxes along each line from a finished point to the next
  std::vector<Label> labels;      // in the points' order (the span tensions' points have none)
  std::vector<size_t> left_out;   // the points with a label that found no free place
};

// The layout of the picture of r. Throws std::runtime_error when no run finished or no finished
// run has an error above 0 (NaN: a metric undefined at t_end).
WpLayout wp_layout(const WpResult& r);

// The gnuplot script that draws `layout` as a 1000×700 PNG into `output`.
std::string wp_script(const WpLayout& layout, const std::string& output);

// Draws `png` (1000×700) from r; integrators with no finished run are marked so in the
// legend. Throws std::runtime_error as wp_layout() does, or when gnuplot fails (plot/gnuplot.hpp).
void plot_wp_png(const WpResult& r, const std::string& png);

}  // namespace beltsim::plot
