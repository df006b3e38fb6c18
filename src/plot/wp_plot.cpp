#include "plot/wp_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "io/number_text.hpp"
#include "plot/gnuplot.hpp"
#include "sim/run_check.hpp"

namespace beltsim::plot {

namespace {

// the picture's geometry [px]: the plot area between these screen fractions of 1000×700
constexpr double kWidth = 1000, kHeight = 700;
constexpr double kLeft = 0.10, kRight = 0.70, kBottom = 0.10, kTop = 0.90;
constexpr double kCharPx = 6.0, kLabelPx = 12.0;  // a label's character width and height at 8 pt
constexpr double kPointPx = 5.0;                  // half the size of a point's mark
constexpr double kRingPx = 10.0;                  // the radius of the ring about a point past its bound (ps 3)

// one colour per integrator, its points and its rtol labels alike (gnuplot.hpp's)
constexpr size_t kNumColours = sizeof kLineColours / sizeof kLineColours[0];

// an rtol as the user gave it (1e-4 reads 0.0001, as %g writes it)
std::string tol_text(double r) { return rounded_text(r, 6); }

// the error the figure shows: the metric's at t_end, or the largest speed error over the run
double shown_error(const WpResult& res, const WpRow& r) {
  return res.metric.empty() ? r.err_speed : r.err_metric;
}

// whole decades around the positive values (one decade when they all lie in one), with a margin:
// a value within kMargin of a decade's end takes the next decade, so that its mark and label are
// not cut by the axis (CVODE's runs at 9.6 s sat on the edge of a range ending at 10 s)
constexpr double kMargin = 1.15;  // 6 % of a decade, some 12 px on the picture's three decades
void decades(const std::vector<double>& v, double& lo, double& hi) {
  double a = INFINITY, b = 0;
  for (double x : v)
    if (x > 0 && std::isfinite(x)) a = std::min(a, x), b = std::max(b, x);
  if (!(b > 0)) a = b = 1;
  lo = std::pow(10.0, std::floor(std::log10(a / kMargin)));
  hi = std::pow(10.0, std::ceil(std::log10(b * kMargin)));
  if (hi <= lo) hi = 10 * lo;
}

// the ranges: whole decades of the wall times and of the errors shown; runs that did not finish
// are marked in one more decade above the errors, at their wall time
void set_ranges(const WpResult& res, WpLayout& l) {
  if (std::none_of(res.rows.begin(), res.rows.end(), [](const WpRow& r) { return r.finished; }))
    throw std::runtime_error("wp: no run finished, nothing to plot");
  std::vector<double> walls, errors;
  for (const WpRow& r : res.rows) {
    if (r.finished && shown_error(res, r) > 0) walls.push_back(r.wall), errors.push_back(shown_error(res, r));
    if (r.finished && res.metric.empty() && r.err_tension > 0) walls.push_back(r.wall), errors.push_back(r.err_tension);
    if (!r.finished) walls.push_back(std::max(r.wall, 1e-3)), l.unfinished = true;
  }
  if (errors.empty())
    throw std::runtime_error("wp: no finished run has an error of " +
                             (res.metric.empty() ? std::string("the speeds") : res.metric) + " above 0 to draw");
  decades(walls, l.x_lo, l.x_hi);
  decades(errors, l.y_lo, l.y_hi);
  l.y_errors = l.y_hi;
  if (l.unfinished) l.y_hi *= 10;
  l.area_w = (kRight - kLeft) * kWidth, l.area_h = (kTop - kBottom) * kHeight;
}

void add_point(WpLayout& l, double x, double y, std::string text, size_t k, bool finished, bool tension = false,
               bool past = false) {
  const double px = l.area_w * std::log(x / l.x_lo) / std::log(l.x_hi / l.x_lo);
  const double py = l.area_h * std::log(y / l.y_lo) / std::log(l.y_hi / l.y_lo);
  l.points.push_back({x, y, px, py, std::move(text), k, finished, tension, past});
  l.any_past |= past;
}

// a finished run's error past the contract's bound for its rtol, where the contract promises one
// (sim/run_check.hpp; not for a study's own metric)
bool past_bound(const WpResult& res, const WpRow& r, bool tension) {
  if (!res.metric.empty() || !r.finished || r.rtol > kContractRtol) return false;
  return tension ? r.err_tension > kCheckTensionLimit * r.rtol : r.err_speed > kCheckSpeedLimit * r.rtol;
}

// each integrator's finished runs, then its unfinished ones on a row of their own above the
// errors; unfinished runs of about the same wall time (a wall-time limit) share one cross and label
void collect_points(const WpResult& res, WpLayout& l) {
  const size_t n_int = std::max<size_t>(1, res.integrators.size());
  for (size_t k = 0; k < res.integrators.size(); ++k) {
    const std::string& name = res.integrators[k];
    WpLayout::Series s{name, kLineColours[k % kNumColours], 5 + 2 * static_cast<int>(k % 4)};
    for (const WpRow& r : res.rows)
      if (r.integrator == name && r.finished && shown_error(res, r) > 0) {
        add_point(l, r.wall, shown_error(res, r), tol_text(r.rtol), k, true, false, past_bound(res, r, false));
        s.any_finished = true;
      }
    if (res.metric.empty())
      for (const WpRow& r : res.rows)
        if (r.integrator == name && r.finished && r.err_tension > 0)
          add_point(l, r.wall, r.err_tension, tol_text(r.rtol), k, true, true, past_bound(res, r, true));
    const double y_row = l.y_errors * std::pow(10.0, (k + 0.5) / static_cast<double>(n_int));
    const size_t first_unfinished = l.points.size();
    for (const WpRow& r : res.rows) {
      if (r.integrator != name || r.finished) continue;
      const double x = std::max(r.wall, 1e-3);
      auto same = std::find_if(l.points.begin() + static_cast<long>(first_unfinished), l.points.end(),
                               [&](const WpLayout::Point& p) { return std::abs(std::log(p.x / x)) < 0.02; });
      if (same != l.points.end())
        same->text += ", " + tol_text(r.rtol);
      else
        add_point(l, x, y_row, tol_text(r.rtol), k, false);
    }
    s.any_unfinished = l.points.size() > first_unfinished;
    l.series.push_back(std::move(s));
  }
}

// what labels must keep off: the points' marks (a ringed one's ring) and, as small boxes every 3 pixels, the line from
// each finished point to its integrator's next
void collect_obstacles(WpLayout& l) {
  const std::vector<WpLayout::Point>& p = l.points;
  for (size_t i = 0; i < p.size(); ++i) {
    const double x = p[i].px, y = p[i].py, r = p[i].past ? kRingPx : kPointPx;
    l.marks.push_back({x - r, y - r, x + r, y + r});
    if (i + 1 < p.size() && p[i + 1].series == p[i].series && p[i].finished && p[i + 1].finished &&
        p[i + 1].tension == p[i].tension) {
      const double x1 = p[i + 1].px, y1 = p[i + 1].py;
      const int n = static_cast<int>(std::hypot(x1 - x, y1 - y) / 3);
      for (int s = 1; s < n; ++s) {
        const double u = static_cast<double>(s) / n, cx = x + u * (x1 - x), cy = y + u * (y1 - y);
        l.line_boxes.push_back({cx - 1.5, cy - 1.5, cx + 1.5, cy + 1.5});
      }
    }
  }
}

// rtol labels where they overlap no other label, point or line and stay inside the plot area:
// above, below, right, left of their point, then the diagonals, then further out; a label with
// no free place is left out. The span tensions' points go unlabelled: each lies at the wall time
// of the labelled speed point of its run
void place_labels(WpLayout& l) {
  std::vector<WpLayout::Box> taken = l.marks;
  taken.insert(taken.end(), l.line_boxes.begin(), l.line_boxes.end());
  for (size_t i = 0; i < l.points.size(); ++i) {
    const WpLayout::Point& p = l.points[i];
    if (p.tension) continue;
    const double x = p.px, y = p.py;
    const double w = kCharPx * static_cast<double>(p.text.size()) + 2, h = kLabelPx;
    const double r = p.past ? kRingPx : kPointPx;
    const double side = 0.5 * w + r + 2, up = 0.5 * h + r + 1;
    const double offsets[][2] = {{0, up},     {0, -up},    {side, 0},    {-side, 0},  {side, up},
                                 {-side, up}, {side, -up}, {-side, -up}, {0, up + h}, {0, -up - h}};
    bool placed = false;
    for (const auto& o : offsets) {
      const WpLayout::Box b{x + o[0] - 0.5 * w, y + o[1] - 0.5 * h, x + o[0] + 0.5 * w, y + o[1] + 0.5 * h};
      if (b.x0 < 0 || b.x1 > l.area_w || b.y0 < 0 || b.y1 > l.area_h) continue;
      if (std::any_of(taken.begin(), taken.end(), [&](const WpLayout::Box& t) { return t.overlaps(b); })) continue;
      taken.push_back(b);
      l.labels.push_back({i, o[0], o[1], b});
      placed = true;
      break;
    }
    if (!placed) l.left_out.push_back(i);
  }
}

}  // namespace

WpLayout wp_layout(const WpResult& res) {
  WpLayout l;
  l.title = res.title;
  l.y_title =
      res.metric.empty() ? "largest relative error over the run" : "relative error of " + res.metric + " at t_end";
  set_ranges(res, l);
  collect_points(res, l);
  collect_obstacles(l);
  place_labels(l);
  return l;
}

std::string wp_script(const WpLayout& l, const std::string& output) {
  std::ostringstream g;
  g << "set encoding utf8\n"
    << "set terminal pngcairo size " << kWidth << "," << kHeight << " font 'DejaVu Sans,11'\n"
    << "set output " << gnuplot_string(output) << "\n"
    << "set lmargin at screen " << kLeft << "\nset rmargin at screen " << kRight << "\n"
    << "set bmargin at screen " << kBottom << "\nset tmargin at screen " << kTop << "\n"
    << "set logscale xy\nset grid xtics ytics mxtics mytics lc rgb '#dddddd'\n"
    << "set xrange [" << number_text(l.x_lo) << ":" << number_text(l.x_hi) << "]\n"
    << "set yrange [" << number_text(l.y_lo) << ":" << number_text(l.y_hi) << "]\n"
    << "set format x '10^{%L}'\nset format y '10^{%L}'\n"
    << "set xlabel 'wall time per run [s]'\n"
    << "set ylabel " << gnuplot_string(l.y_title) << " noenhanced\n"
    << "set title " << gnuplot_string(l.title) << " noenhanced\n"
    << "set key at screen " << kRight + 0.02 << ", screen " << kTop << " left top Left reverse noenhanced\n";
  if (l.unfinished)
    g << "set arrow from graph 0, first " << number_text(l.y_errors) << " to graph 1, first " << number_text(l.y_errors)
      << " nohead dt 2 lc rgb '#999999'\n";
  // each integrator's finished runs ($fK: speeds or the metric; $tK: span tensions) and crosses of
  // its unfinished ones ($uK)
  std::ostringstream plots;
  bool any_tension = false;
  for (size_t k = 0; k < l.series.size(); ++k) {
    const WpLayout::Series& s = l.series[k];
    bool tension = false;
    for (const char* block : {"$f", "$t", "$u"}) {
      g << block << k << " << EOD\n";
      for (const WpLayout::Point& p : l.points)
        if (p.series == k && p.finished == (block[1] != 'u') && p.tension == (block[1] == 't')) {
          g << number_text(p.x) << ' ' << number_text(p.y) << '\n';
          tension |= p.tension;
        }
      g << "EOD\n";
    }
    any_tension |= tension;
    const std::string colour = gnuplot_string(s.colour);
    const std::string style = "linespoints lw 2 lc rgb " + colour + " pt " + std::to_string(s.point_type);
    plots << (k ? ", \\\n     " : "")
          << (s.any_finished ? "$f" + std::to_string(k) + " using 1:2 with " : std::string("keyentry with ")) << style
          << " title " << gnuplot_string(s.any_finished ? s.name : s.name + " (no run finished)");
    // the open mark of the same shape (gnuplot's point type one below the filled one)
    if (tension)
      plots << ", \\\n     $t" << k << " using 1:2 with linespoints lw 1.5 dt 2 lc rgb " << colour << " pt "
            << s.point_type - 1 << " notitle";
    if (s.any_unfinished)
      plots << ", \\\n     $u" << k << " using 1:2 with points pt 2 ps 2 lw 2 lc rgb " << colour << " notitle";
  }
  if (any_tension)
    plots << ", \\\n     keyentry with linespoints lw 2 pt 5 lc rgb '#444444' title 'pulley speeds'"
          << ", \\\n     keyentry with linespoints lw 1.5 dt 2 pt 4 lc rgb '#444444' title 'span tensions'";
  if (l.unfinished) plots << ", \\\n     keyentry with points pt 2 ps 2 lw 2 lc rgb '#444444' title 'did not finish'";
  // a ring about each point past its bound (the bounds are in the lines wp prints: the legend has
  // room for a name alone)
  if (l.any_past) {
    g << "$past << EOD\n";
    for (const WpLayout::Point& p : l.points)
      if (p.past) g << number_text(p.x) << ' ' << number_text(p.y) << '\n';
    g << "EOD\n";
    plots << ", \\\n     $past using 1:2 with points pt 6 ps 3 lw 2 lc rgb '#d62728' title "
          << gnuplot_string("past the contract");
  }
  for (const WpLayout::Label& a : l.labels) {
    const WpLayout::Point& p = l.points[a.point];
    g << "set label " << gnuplot_string(p.text) << " at first " << number_text(p.x) << ", first " << number_text(p.y)
      << " center offset screen " << a.dx / kWidth << ", screen " << a.dy / kHeight << " font ',8' tc rgb "
      << gnuplot_string(l.series[p.series].colour) << " front\n";
  }
  g << "plot " << plots.str() << "\nset output\n";
  return g.str();
}

void plot_wp_png(const WpResult& res, const std::string& png) {
  const WpLayout layout = wp_layout(res);
  const PrivateOutput out;  // gnuplot writes there; the picture is then written to png
  run_gnuplot(wp_script(layout, out.path()));
  out.deliver(png, "wp");
}

}  // namespace beltsim::plot
