// The picture of `beltsim wp`: error against wall time, log-log, one line per integrator with
// its points labelled by their rtol, read by gnuplot from the study's wp.csv. Kept out of the
// engine (beltsim_core launches no process): work_precision() writes the CSV, this draws it.
#pragma once

#include <string>

#include "sim/work_precision.hpp"

namespace beltsim::plot {

// Draws `png` (1000×700) from r.csv_path; integrators with no finished run are marked so in the
// legend. Throws std::runtime_error when no run finished or gnuplot fails (plot/gnuplot.hpp).
void plot_wp_png(const WpResult& r, const std::string& png);

}  // namespace beltsim::plot
