// A drive run on from a state, sampled on a grid: the short runs the mode analyses make beside the
// simulation (sim/floquet.cpp, sim/mode_check.cpp).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "integrate/driver.hpp"
#include "model/drive.hpp"
#include "model/model.hpp"

namespace beltsim {

// the drive d of m run from (t0, y0) over `window` with esdirk32 at rtol (atol the same), sample
// called at t0 + k·dt and at t0 + window (where it falls on the grid's last point, twice). Throws
// what a run throws.
void run_on(const Model& m, const Drive& d, double t0, const Eigen::VectorXd& y0, double window, double dt, double rtol,
            const SampleFn& sample);
// the same run sampled on several grids, each at its t0 + k·dt <= t0 + window (and not at the
// window's end off its grid)
void run_on(const Model& m, const Drive& d, double t0, const Eigen::VectorXd& y0, double window, double rtol,
            std::vector<DriveOptions::Stream> grids);

}  // namespace beltsim
