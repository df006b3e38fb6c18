// The Campbell diagram (docs/modes.md): the modes' frequencies over the crankshaft's speed, one
// marker per mode coloured by where its energy lies (spans, pulleys, arms, rotors; damped modes,
// ζ > 0.2, hollow), and a line per engine order k: f = k·rpm/60. Drawn by gnuplot (gnuplot.hpp).
#pragma once

#include <string>
#include <vector>

#include "sim/campbell.hpp"

namespace beltsim::plot {

// the gnuplot script (for tests) and the picture; throws std::runtime_error as run_gnuplot does
std::string campbell_script(const std::vector<CampbellPoint>& points, const std::vector<double>& orders,
                            const std::string& title, const std::string& output);
void plot_campbell_png(const std::vector<CampbellPoint>& points, const std::vector<double>& orders,
                       const std::string& title, const std::string& png);

}  // namespace beltsim::plot
