#include "plot/campbell_plot.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "io/number_text.hpp"
#include "plot/gnuplot.hpp"

namespace beltsim::plot {

namespace {

// the kinds of group a mode's energy lies in, by the group names' prefixes (sim/modes.hpp)
struct Kind {
  const char* prefix;
  const char* title;
  const char* colour;
  int point;  // gnuplot's point type, filled
};
constexpr Kind kKinds[] = {{"span_", "spans", "#1f77b4", 7},
                           {"wrap_", "belt on a pulley", "#ff7f0e", 11},
                           {"pulley_", "pulleys", "#d62728", 5},
                           {"arm_", "tensioner arms", "#2ca02c", 9},
                           {"rotor_", "coupled rotors", "#9467bd", 13}};
constexpr double kDamped = 0.2;  // ζ above this: a hollow marker; below 0: a cross
// a mode's marker class: 0 lightly damped, 1 damped (ζ > kDamped), 2 growing (ζ < 0)
int damping_class(double zeta) {
  return zeta < 0 ? 2 : zeta > kDamped ? 1 : 0;
}

}  // namespace

std::string campbell_script(const std::vector<CampbellPoint>& points, const std::vector<double>& orders,
                            const std::string& title, const std::string& pulley, const std::string& output) {
  double rpm_hi = 0, f_hi = 0, f_max = 0;
  for (const CampbellPoint& p : points) {
    rpm_hi = std::max(rpm_hi, p.rpm);
    for (const Mode& m : p.analysis.modes) f_hi = std::max(f_hi, m.frequency);
  }
  // up to twice the highest order's line at the highest speed, where the modes reach that far
  for (double o : orders) f_max = std::max(f_max, 2 * o * rpm_hi / 60);
  if (f_max > 0) f_hi = std::min(f_hi, f_max);
  rpm_hi = rpm_hi > 0 ? 1.05 * rpm_hi : 1;
  f_hi = f_hi > 0 ? 1.05 * f_hi : 1;
  std::ostringstream g;
  g << "set encoding utf8\n"
    << "set terminal pngcairo size 1200,800 font 'DejaVu Sans,11'\n"
    << "set output " << gnuplot_string(output) << "\n"
    << "set grid lc rgb '#dddddd'\n"
    << "set xrange [0:" << number_text(rpm_hi) << "]\nset yrange [0:" << number_text(f_hi) << "]\n"
    << "set xlabel " << gnuplot_string(pulley + " speed [rpm]") << " noenhanced\nset ylabel 'frequency [Hz]'\n"
    << "set title " << gnuplot_string(title) << " noenhanced\n"
    << "set key outside right top noenhanced\n";
  // the modes above the axis, said on the picture: a reader would take the picture for all of them
  size_t above = 0, all = 0;
  double f_top = 0;
  for (const CampbellPoint& p : points)
    for (const Mode& m : p.analysis.modes) {
      ++all;
      if (m.frequency > f_hi) ++above, f_top = std::max(f_top, m.frequency);
    }
  if (above > 0)
    g << "set label "
      << gnuplot_string(std::to_string(above) + " of " + std::to_string(all) + " modes lie above " +
                        number_text(std::round(f_hi)) + " Hz, up to " + number_text(std::round(f_top)) +
                        " Hz: campbell.csv lists them")
      << " at graph 0.02, graph 0.97 left front font ',10' tc rgb '#444444' noenhanced\n";
  std::ostringstream plots;
  const char* sep = "";
  static const char* suffix[] = {"", " (ζ > 0.2)", " (ζ < 0)"};
  for (size_t k = 0; k < std::size(kKinds); ++k)
    for (int c = 0; c < 3; ++c) {
      std::ostringstream data;
      for (const CampbellPoint& p : points)
        for (const Mode& m : p.analysis.modes)
          if (p.analysis.groups[m.dominant].rfind(kKinds[k].prefix, 0) == 0 && damping_class(m.damping) == c)
            data << number_text(p.rpm) << ' ' << number_text(m.frequency) << '\n';
      if (data.str().empty()) continue;
      const std::string block = "$k" + std::to_string(k) + "c" + std::to_string(c);
      g << block << " << EOD\n" << data.str() << "EOD\n";
      const int point = c == 0 ? kKinds[k].point : c == 1 ? kKinds[k].point - 1 : 2;
      plots << sep << block << " using 1:2 with points pt " << point << " ps 1.3 lc rgb "
            << gnuplot_string(kKinds[k].colour) << " title "
            << gnuplot_string(std::string(kKinds[k].title) + suffix[c]);
      sep = ", \\\n     ";
    }
  for (size_t k = 0; k < orders.size(); ++k) {
    plots << sep << "x*" << number_text(orders[k]) << "/60.0 with lines dt " << k + 2
          << " lw 1.5 lc rgb '#444444' title " << gnuplot_string("order " + number_text(orders[k]));
    sep = ", \\\n     ";
  }
  if (plots.str().empty()) plots << "NaN notitle";
  g << "plot " << plots.str() << "\nset output\n";
  return g.str();
}

void plot_campbell_png(const std::vector<CampbellPoint>& points, const std::vector<double>& orders,
                       const std::string& title, const std::string& pulley, const std::string& png) {
  const PrivateOutput out;
  run_gnuplot(campbell_script(points, orders, title, pulley, out.path()));
  out.deliver(png, "modes");
}

}  // namespace beltsim::plot
