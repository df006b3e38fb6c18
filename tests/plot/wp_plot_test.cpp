// The wp picture (plot/wp_plot.hpp) and its layout: labels clear of each other, of the points and
// of the lines, crowded ones left out; unfinished runs as crosses; the span tensions dashed.
#include "plot/wp_plot.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "io/number_text.hpp"
#include "media/png_writer.hpp"
#include "plot/gnuplot.hpp"
#include "plot_test_support.hpp"

namespace beltsim::plot {
namespace {

namespace fs = std::filesystem;

// a finished run of a study, its error the largest speed error (the figure's without a metric)
WpRow finished_run(const std::string& integrator, double rtol, double wall, double err) {
  WpRow w;
  w.integrator = integrator, w.rtol = rtol, w.finished = true, w.wall = wall, w.err_speed = err;
  return w;
}

WpRow unfinished_run(const std::string& integrator, double rtol, double wall) {
  WpRow w;
  w.integrator = integrator, w.rtol = rtol, w.wall = wall, w.note = "wall-time limit";
  return w;
}

// n integrators, rtols 1e-2, 1e-3, ...; integrator k's run i at
// wall = wall0·10^(i·dwall + k·shift_wall) s, error = err0·10^(-i·derr + k·shift_err)
WpResult study(int n, int rtols, double wall0, double dwall, double shift_wall, double err0, double derr,
               double shift_err) {
  static const char* const kNames[] = {"esdirk32", "trbdf2", "rkf45", "cvode_bdf", "rk4", "sdirk2"};
  WpResult r;
  r.title = "a study";
  for (int k = 0; k < n; ++k) {
    r.integrators.push_back(kNames[k]);
    for (int i = 0; i < rtols; ++i)
      r.rows.push_back(finished_run(kNames[k], std::pow(10.0, -2 - i),
                                    wall0 * std::pow(10.0, i * dwall + k * shift_wall),
                                    err0 * std::pow(10.0, -i * derr + k * shift_err)));
  }
  return r;
}

// three integrators, six rtols each, their lines well apart
WpResult spread_study() {
  return study(3, 6, 0.01, 0.5, 0.25, 0.05, 0.8, 1.5);
}

// one integrator across the decades and five more with eight runs each in one corner
WpResult crowded_study() {
  WpResult r = study(6, 8, 0.011, 0.04, 0.01, 2e-6, 0.04, 0.01);
  for (int i = 0; i < 8; ++i)
    r.rows[i].wall = 0.01 * std::pow(10.0, 0.55 * i), r.rows[i].err_speed = 0.09 * std::pow(10.0, -0.9 * i);
  return r;
}

// runs that did not finish: rkf45's last three at its wall-time limit (one cross), sdirk2 none
WpResult unfinished_study() {
  WpResult r = study(2, 6, 0.02, 0.45, 0.3, 0.03, 0.9, 0.7);
  r.integrators[1] = "rkf45";
  for (int i = 6; i < 12; ++i) {
    r.rows[i].integrator = "rkf45";
    if (i >= 9) r.rows[i] = unfinished_run("rkf45", r.rows[i].rtol, 120 + 0.3 * i);
  }
  r.integrators.push_back("sdirk2");
  for (double wall : {3.0, 40.0, 120.0}) r.rows.push_back(unfinished_run("sdirk2", wall / 1e4, wall));
  return r;
}

// every wall time and every error in one decade
WpResult one_decade_study() {
  return study(3, 5, 0.12, 0.15, 0.05, 8.5e-3, 0.12, -0.02);
}

// the segment a-b [px] passes through the inside of box (Liang-Barsky clipping)
bool crosses(const WpLayout::Box& box, double ax, double ay, double bx, double by) {
  double t0 = 0, t1 = 1;
  const double d[2] = {bx - ax, by - ay};
  const double lo[2] = {box.x0 - ax, box.y0 - ay}, hi[2] = {box.x1 - ax, box.y1 - ay};
  for (int k = 0; k < 2; ++k) {
    if (d[k] == 0) {
      if (lo[k] >= 0 || hi[k] <= 0) return false;
      continue;
    }
    double ta = lo[k] / d[k], tb = hi[k] / d[k];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta), t1 = std::min(t1, tb);
  }
  return t0 < t1;
}

// every point's label is placed or left out, and each placed one lies inside the plot area and
// overlaps no other label, no point's mark and no line (its boxes, and the line itself)
void expect_labels_clear(const WpLayout& l) {
  ASSERT_EQ(l.marks.size(), l.points.size());
  const auto labelled =
      std::count_if(l.points.begin(), l.points.end(), [](const WpLayout::Point& p) { return !p.tension; });
  EXPECT_EQ(static_cast<long>(l.labels.size() + l.left_out.size()), labelled);
  for (size_t j = 0; j < l.points.size(); ++j) {  // the marks are where the points are
    EXPECT_DOUBLE_EQ(l.marks[j].x0 + l.marks[j].x1, 2 * l.points[j].px);
    EXPECT_DOUBLE_EQ(l.marks[j].y0 + l.marks[j].y1, 2 * l.points[j].py);
  }
  for (size_t i = 0; i < l.labels.size(); ++i) {
    const WpLayout::Box& b = l.labels[i].box;
    const std::string what =
        "label '" + l.points[l.labels[i].point].text + "' of " + l.series[l.points[l.labels[i].point].series].name;
    EXPECT_TRUE(b.x0 >= 0 && b.x1 <= l.area_w && b.y0 >= 0 && b.y1 <= l.area_h) << what << " outside the plot area";
    for (size_t j = i + 1; j < l.labels.size(); ++j)
      EXPECT_FALSE(b.overlaps(l.labels[j].box)) << what << " overlaps '" << l.points[l.labels[j].point].text << "'";
    for (size_t j = 0; j < l.points.size(); ++j)
      EXPECT_FALSE(b.overlaps(l.marks[j])) << what << " overlaps the point of '" << l.points[j].text << "'";
    for (const WpLayout::Box& t : l.line_boxes) EXPECT_FALSE(b.overlaps(t)) << what << " overlaps a line";
    for (size_t j = 0; j + 1 < l.points.size(); ++j) {
      const WpLayout::Point &p = l.points[j], &q = l.points[j + 1];
      if (p.series == q.series && p.finished && q.finished && p.tension == q.tension) {
        EXPECT_FALSE(crosses(b, p.px, p.py, q.px, q.py)) << what << " on the line " << p.text << " - " << q.text;
      }
    }
  }
}

TEST(WpPlot, DrawsTheStudyFromItsCsv) {
  const fs::path d = dir("wp's");
  WpResult r;
  r.integrators = {"esdirk32", "rkf45"};
  r.title = "a 'study'";
  WpRow row;
  row.integrator = "esdirk32";
  row.finished = true;
  row.rtol = 1e-2, row.wall = 0.1, row.err_speed = 0.1;
  r.rows = {row, row, row, WpRow{}, WpRow{}};
  r.rows[1].rtol = 1e-3, r.rows[1].wall = 0.3, r.rows[1].err_speed = 0.01;
  r.rows[2].rtol = 1e-4, r.rows[2].wall = 0.31, r.rows[2].err_speed = 0.011;  // labels that would collide
  for (int k : {3, 4}) r.rows[k].integrator = "rkf45", r.rows[k].wall = 1, r.rows[k].note = "wall-time limit";
  expect_labels_clear(wp_layout(r));  // (its first error, 0.1, is the top of the errors' decades)
  const std::string png = (d / "wp.png").string();
  plot_wp_png(r, png);
  const Image img = read_png(png);
  EXPECT_EQ(img.width, 1000);
  EXPECT_EQ(img.height, 700);
  // with a metric its error is drawn
  r.metric = "driven.creep";
  for (WpRow& w : r.rows) w.err_metric = 2 * w.err_speed;
  plot_wp_png(r, png);
  EXPECT_EQ(read_png(png).width, 1000);
  for (WpRow& w : r.rows) w.err_metric = std::nan("");  // (a creep undefined at t_end)
  expect_error([&] { plot_wp_png(r, png); }, {"no finished run has an error of driven.creep above 0"});
  r.rows = {r.rows[3]};
  expect_error([&] { plot_wp_png(r, png); }, {"no run finished"});
}

// well apart lines: every label placed, clear of the rest
TEST(WpLayout, EveryLabelOfAnUncrowdedStudyIsPlacedClear) {
  const WpResult r = spread_study();
  const WpLayout l = wp_layout(r);
  ASSERT_EQ(l.points.size(), r.rows.size());
  expect_labels_clear(l);
  EXPECT_TRUE(l.left_out.empty());
  EXPECT_EQ(l.labels.size(), r.rows.size());
}

// 40 runs in one corner: labels left out rather than overlapping
TEST(WpLayout, ACrowdedCornerLeavesLabelsOut) {
  const WpLayout l = wp_layout(crowded_study());
  ASSERT_EQ(l.points.size(), 48u);
  expect_labels_clear(l);
  EXPECT_GT(l.left_out.size(), 10u);
  EXPECT_GT(l.labels.size(), 10u);
}

// unfinished runs: crosses above the errors, those at one wall time sharing a cross and label
TEST(WpLayout, UnfinishedRunsAreCrossesAboveTheErrors) {
  const WpLayout l = wp_layout(unfinished_study());
  ASSERT_EQ(l.series.size(), 3u);
  EXPECT_TRUE(l.unfinished);
  EXPECT_EQ(l.y_hi, 10 * l.y_errors);
  EXPECT_TRUE(l.series[1].any_finished && l.series[1].any_unfinished);
  EXPECT_FALSE(l.series[2].any_finished);
  std::vector<std::string> crosses;
  const double errors_top = l.area_h * std::log(l.y_errors / l.y_lo) / std::log(l.y_hi / l.y_lo);
  for (const WpLayout::Point& p : l.points) {
    EXPECT_EQ(p.finished, p.py < errors_top) << p.text;
    if (!p.finished) crosses.push_back(l.series[p.series].name + " " + p.text);
  }
  EXPECT_EQ(crosses,
            (std::vector<std::string>{"rkf45 1e-05, 1e-06, 1e-07", "sdirk2 0.0003", "sdirk2 0.004", "sdirk2 0.012"}));
  expect_labels_clear(l);
}

// the script has the layout's labels, at their offsets, and no other
TEST(WpLayout, TheScriptDrawsTheLayoutsLabels) {
  const WpLayout l = wp_layout(crowded_study());
  const std::string script = wp_script(l, "wp.png");
  size_t n = 0;
  for (size_t at = 0; (at = script.find("set label ", at)) != std::string::npos; ++at) ++n;
  EXPECT_EQ(n, l.labels.size());
  for (const WpLayout::Label& a : l.labels) {
    std::ostringstream offset;
    offset << "offset screen " << a.dx / 1000 << ", screen " << a.dy / 700;
    EXPECT_NE(script.find("set label " + gnuplot_string(l.points[a.point].text) + " at first " +
                          number_text(l.points[a.point].x)),
              std::string::npos);
    EXPECT_NE(script.find(offset.str()), std::string::npos) << offset.str();
  }
}

// all wall times and errors in one decade: the axes span that decade
TEST(WpLayout, OneDecadeStudy) {
  const WpLayout l = wp_layout(one_decade_study());
  EXPECT_DOUBLE_EQ(l.x_lo, 0.1);
  EXPECT_DOUBLE_EQ(l.x_hi, 1);
  EXPECT_DOUBLE_EQ(l.y_lo, 1e-3);
  EXPECT_DOUBLE_EQ(l.y_hi, 1e-2);
  expect_labels_clear(l);
}

// the span tensions' errors: a dashed line of open marks per integrator beside its speeds', no
// labels, inside the axes' range; a study with a metric shows the metric alone
TEST(WpLayout, SpanTensionsAreDashedUnlabelledAndInRange) {
  WpResult r = spread_study();
  for (WpRow& w : r.rows) w.err_tension = 30 * w.err_speed;  // (the contract's 10·rtol against 3·rtol)
  const WpLayout l = wp_layout(r);
  ASSERT_EQ(l.points.size(), 2 * r.rows.size());
  size_t tensions = 0;
  for (size_t i = 0; i < l.points.size(); ++i) {
    const WpLayout::Point& p = l.points[i];
    if (!p.tension) continue;
    ++tensions;
    EXPECT_GE(p.y, l.y_lo);
    EXPECT_LE(p.y, l.y_hi);
    for (const WpLayout::Label& a : l.labels) EXPECT_NE(a.point, i) << "a span tension's point is labelled";
  }
  EXPECT_EQ(tensions, r.rows.size());
  expect_labels_clear(l);
  const std::string script = wp_script(l, "x.png");
  for (size_t k = 0; k < r.integrators.size(); ++k)
    EXPECT_NE(script.find("$t" + std::to_string(k) + " using 1:2 with linespoints lw 1.5 dt 2"), std::string::npos);
  EXPECT_NE(script.find("title 'span tensions'"), std::string::npos);
  r.metric = "driven.creep";
  for (WpRow& w : r.rows) w.err_metric = w.err_speed;
  const WpLayout m = wp_layout(r);
  EXPECT_EQ(m.points.size(), r.rows.size());
  EXPECT_EQ(wp_script(m, "x.png").find("span tensions"), std::string::npos);
}

// a point past the contract's bound for its rtol is ringed, the legend naming the ring: the
// speeds past 3·rtol, the span tensions past 10·rtol, only at rtol <= 1e-3 (promised there) and
// not for a metric (a user's trial: wp.png showed no bound)
TEST(WpLayout, PointsPastTheContractAreRinged) {
  WpResult r;
  r.title = "a study";
  r.integrators = {"trbdf2"};
  for (double rtol : {1e-2, 1e-3, 1e-4}) r.rows.push_back(finished_run("trbdf2", rtol, 0.1 / rtol * 1e-3, 0));
  r.rows[0].err_speed = 0.5, r.rows[0].err_tension = 0.9;        // rtol 1e-2: no promise
  r.rows[1].err_speed = 3.5e-3, r.rows[1].err_tension = 9e-3;    // past 3·rtol; within 10·rtol
  r.rows[2].err_speed = 2.9e-4, r.rows[2].err_tension = 1.1e-3;  // within 3·rtol; past 10·rtol
  const WpLayout l = wp_layout(r);
  std::vector<std::pair<double, bool>> past;  // (y, tension) of each ringed point
  for (const WpLayout::Point& p : l.points)
    if (p.past) past.emplace_back(p.y, p.tension);
  EXPECT_EQ(past, (std::vector<std::pair<double, bool>>{{3.5e-3, false}, {1.1e-3, true}}));
  const std::string script = wp_script(l, "x.png");
  EXPECT_NE(script.find("$past using 1:2 with points pt 6"), std::string::npos) << script;
  EXPECT_NE(script.find("title 'past the contract'"), std::string::npos);
  for (WpRow& w : r.rows) w.err_speed = w.err_tension = 1e-9;
  EXPECT_EQ(wp_script(wp_layout(r), "x.png").find("past the contract"), std::string::npos);
  r.metric = "driven.creep";
  for (WpRow& w : r.rows) w.err_metric = 0.5;
  EXPECT_FALSE(wp_layout(r).any_past);
}

// a run whose wall time lies just below a decade's end takes the next decade: its mark is not cut
// by the axis
TEST(WpLayout, APointNearADecadesEndIsNotOnTheAxis) {
  WpResult r = study(1, 3, 0.5, 0.5, 0, 0.05, 0.8, 0);
  r.rows.back().wall = 9.6;
  const WpLayout l = wp_layout(r);
  EXPECT_DOUBLE_EQ(l.x_hi, 100);
  EXPECT_DOUBLE_EQ(l.x_lo, 0.1);
}

}  // namespace
}  // namespace beltsim::plot
