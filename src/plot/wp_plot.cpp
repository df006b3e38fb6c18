#include "plot/wp_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "io/number_text.hpp"
#include "plot/gnuplot.hpp"

namespace beltsim::plot {

namespace {

// the picture's geometry [px]: the plot area between these screen fractions of 1000×700
constexpr double kWidth = 1000, kHeight = 700;
constexpr double kLeft = 0.10, kRight = 0.70, kBottom = 0.10, kTop = 0.90;
constexpr double kCharPx = 6.0, kLabelPx = 12.0;  // a label's character width and height at 8 pt
constexpr double kPointPx = 5.0;                  // half the size of a point's mark

std::string tol_text(double r) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", r);
  return b;
}

// the error the figure shows: the metric's at t_end, or the largest speed error over the run
double shown_error(const WpResult& res, const WpRow& r) { return res.metric.empty() ? r.err_speed : r.err_metric; }

// whole decades around the positive values (one decade when they all lie in one)
void decades(const std::vector<double>& v, double& lo, double& hi) {
  double a = INFINITY, b = 0;
  for (double x : v)
    if (x > 0 && std::isfinite(x)) a = std::min(a, x), b = std::max(b, x);
  if (!(b > 0)) a = b = 1;
  lo = std::pow(10.0, std::floor(std::log10(a)));
  hi = std::pow(10.0, std::ceil(std::log10(b)));
  if (hi <= lo) hi = 10 * lo;
}

struct Box {
  double x0, y0, x1, y1;  // [px], y up
  bool overlaps(const Box& o) const { return x0 < o.x1 && o.x0 < x1 && y0 < o.y1 && o.y0 < y1; }
};

}  // namespace

void plot_wp_png(const WpResult& res, const std::string& png) {
  if (std::none_of(res.rows.begin(), res.rows.end(), [](const WpRow& r) { return r.finished; }))
    throw std::runtime_error("wp: no run finished, nothing to plot");
  // the ranges: whole decades of the wall times and of the errors shown; runs that did not
  // finish are marked in one more decade above the errors, at their wall time
  std::vector<double> walls, errors;
  bool unfinished = false;
  for (const WpRow& r : res.rows) {
    if (r.finished && shown_error(res, r) > 0) walls.push_back(r.wall), errors.push_back(shown_error(res, r));
    if (!r.finished) walls.push_back(std::max(r.wall, 1e-3)), unfinished = true;
  }
  if (errors.empty())
    throw std::runtime_error("wp: no finished run has an error of " +
                             (res.metric.empty() ? std::string("the speeds") : res.metric) + " above 0 to draw");
  double x_lo, x_hi, y_lo, y_hi;
  decades(walls, x_lo, x_hi);
  decades(errors, y_lo, y_hi);
  // each integrator's unfinished runs on a row of their own in that decade
  const double y_errors = y_hi;
  const size_t n_int = std::max<size_t>(1, res.integrators.size());
  auto y_unfinished = [&](size_t k) { return y_errors * std::pow(10.0, (k + 0.5) / static_cast<double>(n_int)); };
  if (unfinished) y_hi *= 10;
  const double area_w = (kRight - kLeft) * kWidth, area_h = (kTop - kBottom) * kHeight;
  auto px = [&](double x, double y) {
    return std::pair{area_w * std::log(x / x_lo) / std::log(x_hi / x_lo),
                     area_h * std::log(y / y_lo) / std::log(y_hi / y_lo)};
  };

  const PrivateOutput out;  // gnuplot writes there; the picture is then written to png
  std::ostringstream g;
  g << "set encoding utf8\n"
    << "set terminal pngcairo size " << kWidth << "," << kHeight << " font 'DejaVu Sans,11'\n"
    << "set output " << gnuplot_string(out.path()) << "\n"
    << "set lmargin at screen " << kLeft << "\nset rmargin at screen " << kRight << "\n"
    << "set bmargin at screen " << kBottom << "\nset tmargin at screen " << kTop << "\n"
    << "set logscale xy\nset grid xtics ytics mxtics mytics lc rgb '#dddddd'\n"
    << "set xrange [" << number_text(x_lo) << ":" << number_text(x_hi) << "]\n"
    << "set yrange [" << number_text(y_lo) << ":" << number_text(y_hi) << "]\n"
    << "set format x '10^{%L}'\nset format y '10^{%L}'\n"
    << "set xlabel 'wall time per run [s]'\n"
    << "set ylabel "
    << gnuplot_string(res.metric.empty() ? "largest relative error in the pulley speeds over the run"
                                         : "relative error of " + res.metric + " at t_end")
    << " noenhanced\n"
    << "set title " << gnuplot_string(res.title) << " noenhanced\n"
    << "set key at screen " << kRight + 0.02 << ", screen " << kTop << " left top Left reverse noenhanced\n";
  if (unfinished)
    g << "set arrow from graph 0, first " << number_text(y_errors) << " to graph 1, first " << number_text(y_errors)
      << " nohead dt 2 lc rgb '#999999'\n";

  // one colour per integrator, its points and its rtol labels alike
  static const char* const kColours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                         "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
  constexpr size_t kNumColours = sizeof kColours / sizeof kColours[0];
  struct Point {
    double x, y;
    std::string text;
    size_t colour;
  };
  std::vector<Point> points;
  std::ostringstream plots;
  for (size_t k = 0; k < res.integrators.size(); ++k) {
    const std::string& name = res.integrators[k];
    g << "$f" << k << " << EOD\n";
    bool any = false;
    for (const WpRow& r : res.rows)
      if (r.integrator == name && r.finished && shown_error(res, r) > 0) {
        g << number_text(r.wall) << ' ' << number_text(shown_error(res, r)) << '\n';
        points.push_back({r.wall, shown_error(res, r), tol_text(r.rtol), k});
        any = true;
      }
    g << "EOD\n$u" << k << " << EOD\n";
    // unfinished runs of about the same wall time (a wall-time limit) share one cross and label
    const size_t first_unfinished = points.size();
    for (const WpRow& r : res.rows) {
      if (r.integrator != name || r.finished) continue;
      const double x = std::max(r.wall, 1e-3);
      auto same = std::find_if(points.begin() + static_cast<long>(first_unfinished), points.end(),
                               [&](const Point& p) { return std::abs(std::log(p.x / x)) < 0.02; });
      if (same != points.end()) {
        same->text += ", " + tol_text(r.rtol);
        continue;
      }
      g << number_text(x) << ' ' << number_text(y_unfinished(k)) << '\n';
      points.push_back({x, y_unfinished(k), tol_text(r.rtol), k});
    }
    g << "EOD\n";
    const std::string colour = gnuplot_string(kColours[k % kNumColours]);
    const std::string style =
        "linespoints lw 2 lc rgb " + colour + " pt " + std::to_string(5 + 2 * static_cast<int>(k % 4));
    plots << (k ? ", \\\n     " : "")
          << (any ? "$f" + std::to_string(k) + " using 1:2 with " : std::string("keyentry with ")) << style
          << " title " << gnuplot_string(any ? name : name + " (no run finished)");
    if (points.size() > first_unfinished)
      plots << ", \\\n     $u" << k << " using 1:2 with points pt 2 ps 2 lw 2 lc rgb " << colour << " notitle";
  }
  if (unfinished)
    plots << ", \\\n     keyentry with points pt 2 ps 2 lw 2 lc rgb '#444444' title 'did not finish'";

  // rtol labels where they overlap no other label, point or line: above, below, right, left of
  // their point, then the diagonals, then further out; a label with no free place is left out
  std::vector<Box> taken;
  for (size_t i = 0; i < points.size(); ++i) {
    const auto [x, y] = px(points[i].x, points[i].y);
    taken.push_back({x - kPointPx, y - kPointPx, x + kPointPx, y + kPointPx});
    // the line to the integrator's next finished point, as small boxes every 3 pixels
    if (i + 1 < points.size() && points[i + 1].colour == points[i].colour && points[i].y < y_errors &&
        points[i + 1].y < y_errors) {
      const auto [x1, y1] = px(points[i + 1].x, points[i + 1].y);
      const int n = static_cast<int>(std::hypot(x1 - x, y1 - y) / 3);
      for (int s = 1; s < n; ++s) {
        const double u = static_cast<double>(s) / n, cx = x + u * (x1 - x), cy = y + u * (y1 - y);
        taken.push_back({cx - 1.5, cy - 1.5, cx + 1.5, cy + 1.5});
      }
    }
  }
  for (const Point& p : points) {
    const auto [x, y] = px(p.x, p.y);
    const double w = kCharPx * static_cast<double>(p.text.size()) + 2, h = kLabelPx;
    const double side = 0.5 * w + kPointPx + 2, up = 0.5 * h + kPointPx + 1;
    const double offsets[][2] = {{0, up},         {0, -up},       {side, 0},   {-side, 0},     {side, up},
                                 {-side, up},     {side, -up},    {-side, -up}, {0, up + h},   {0, -up - h}};
    for (const auto& o : offsets) {
      const Box b{x + o[0] - 0.5 * w, y + o[1] - 0.5 * h, x + o[0] + 0.5 * w, y + o[1] + 0.5 * h};
      if (b.x0 < 0 || b.x1 > area_w || b.y0 < 0 || b.y1 > area_h) continue;
      if (std::any_of(taken.begin(), taken.end(), [&](const Box& t) { return t.overlaps(b); })) continue;
      taken.push_back(b);
      g << "set label " << gnuplot_string(p.text) << " at first " << number_text(p.x) << ", first "
        << number_text(p.y) << " center offset screen " << o[0] / kWidth << ", screen " << o[1] / kHeight
        << " font ',8' tc rgb " << gnuplot_string(kColours[p.colour % kNumColours]) << " front\n";
      break;
    }
  }
  g << "plot " << plots.str() << "\nset output\n";
  run_gnuplot(g.str());
  out.deliver(png, "wp");
}

}  // namespace beltsim::plot
