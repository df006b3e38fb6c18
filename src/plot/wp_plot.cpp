#include "plot/wp_plot.hpp"

#include <algorithm>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "plot/gnuplot.hpp"

namespace beltsim::plot {

void plot_wp_png(const WpResult& res, const std::string& png) {
  if (std::none_of(res.rows.begin(), res.rows.end(), [](const WpRow& r) { return r.finished; }))
    throw std::runtime_error("wp: no run finished, nothing to plot");
  const PrivateOutput out;  // gnuplot writes there; the picture is then written to png
  std::ostringstream g;
  g << "set encoding utf8\n"
    << "set terminal pngcairo size 1000,700 font 'DejaVu Sans,11'\n"
    << "set output " << gnuplot_string(out.path()) << "\n"
    << "set logscale xy\nset grid xtics ytics mxtics mytics lc rgb '#dddddd'\n"
    << "set format x '10^{%L}'\nset format y '10^{%L}'\n"
    << "set xlabel 'wall time per run [s]'\n"
    << "set ylabel 'largest relative error in the pulley speeds over the run'\n"
    << "set title " << gnuplot_string(res.title) << " noenhanced\n"
    << "set key outside right top noenhanced\n"
    << "set datafile separator ','\n";
  // columns of wp.csv: 1 integrator, 2 rtol, 3 finished, 5 wall_s, 12 err_speed; row 0 is the reference
  const std::string csv = gnuplot_string(res.csv_path);
  // one colour per integrator, its points and its rtol labels alike (gnuplot's own cycle counts
  // the label items too and gave the fifth integrator the first one's colour)
  static const char* const kColours[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                         "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
  constexpr size_t kNumColours = sizeof kColours / sizeof kColours[0];
  g << "plot ";
  for (size_t k = 0; k < res.integrators.size(); ++k) {
    const std::string colour = gnuplot_string(kColours[k % kNumColours]);
    const std::string& name = res.integrators[k];
    const bool any = std::any_of(res.rows.begin(), res.rows.end(),
                                 [&](const WpRow& r) { return r.integrator == name && r.finished; });
    const std::string label = any ? name : name + " (no run finished)";
    const std::string when = "(strcol(1) eq " + gnuplot_string(name) + " && $3 == 1 && $0 > 0 ? $5 : NaN)";
    g << (k ? ", \\\n     " : "") << csv << " using " << when << ":12 with linespoints lw 2 lc rgb " << colour
      << " pt " << 5 + 2 * static_cast<int>(k) << " title " << gnuplot_string(label) << ", \\\n     '' using "
      << when << ":12:(sprintf('%g', $2)) with labels offset 0,1 font ',8' tc rgb " << colour << " notitle";
  }
  g << "\nset output\n";
  run_gnuplot(g.str());
  out.deliver(png, "wp");
}

}  // namespace beltsim::plot
