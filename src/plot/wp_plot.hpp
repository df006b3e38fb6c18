// The picture of `beltsim wp`: error against wall time, log-log, one line per integrator with
// its points labelled by their rtol where a label overlaps no other label or point; the error is
// the metric's when the study has one, else the largest speed error; runs that did not finish are
// crosses at their wall time in a band above the errors. Kept out of the engine (beltsim_core
// launches no process): work_precision() writes the CSV, this draws the result.
#pragma once

#include <string>

#include "sim/work_precision.hpp"

namespace beltsim::plot {

// Draws `png` (1000×700) from r; integrators with no finished run are marked so in the
// legend. Throws std::runtime_error when no run finished, no finished run has an error above 0
// (NaN: a metric undefined at t_end) or gnuplot fails (plot/gnuplot.hpp).
void plot_wp_png(const WpResult& r, const std::string& png);

}  // namespace beltsim::plot
