// The Campbell diagram (docs/modes.md): the modes' frequencies over the crankshaft's speed, one
// marker per mode coloured by where its energy lies (spans, the belt on a pulley, pulleys, arms,
// rotors; hollow when damped, ζ > 0.2, a cross when growing, ζ < 0), and a line per engine order
// k: f = k·rpm/60, up to twice the highest order's frequency at the highest speed. Drawn by gnuplot
// (gnuplot.hpp).
#pragma once

#include <string>
#include <vector>

#include "sim/campbell.hpp"

namespace beltsim::plot {

// the gnuplot script (for tests) and the picture; throws std::runtime_error as run_gnuplot does.
// pulley: the pulley whose speed is swept (the speed axis's name). The frequency axis ends at
// twice the highest order's line at the highest speed; the modes above it are counted in a note
// on the picture (the CSV holds them all).
std::string campbell_script(const std::vector<CampbellPoint>& points, const std::vector<double>& orders,
                            const std::string& title, const std::string& pulley, const std::string& output);
void plot_campbell_png(const std::vector<CampbellPoint>& points, const std::vector<double>& orders,
                       const std::string& title, const std::string& pulley, const std::string& png);

}  // namespace beltsim::plot
