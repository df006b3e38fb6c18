// A Campbell diagram's data (docs/modes.md): the drive's modes over the speed of one pulley (the
// crankshaft). At each speed the scene runs from rest with that pulley held at a speed law of its
// own, a cosine ramp from 0 to the speed over the first half of `settle` and the speed after (the
// scene's own law of that pulley, with its harmonics, is replaced: the operating point is steady),
// and the modes are taken at t = settle (sim/modes.hpp).
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "scene/scene.hpp"
#include "sim/modes.hpp"
#include "sim/run_settings.hpp"

namespace beltsim {

struct CampbellSettings {
  int pulley = 0;           // the pulley whose speed is swept (held at it)
  std::vector<double> rpm;  // its speeds [rpm], > 0 (turning the way the belt goes round it)
  double settle = 0.3;      // [s] the run at each speed before its modes are taken
  ModeSettings modes;
};

struct CampbellPoint {
  double rpm = 0;
  ModeAnalysis analysis;
};

// The runs' files go to base.out_dir/rpm_<speed>/ (timeseries.csv, ...). each (when set) sees
// every point as it is done. Throws std::invalid_argument for settings out of range (naming the
// key and the value), what a run throws otherwise; stops early (returning the points done) when
// *stop is set.
std::vector<CampbellPoint> campbell(const Scene& sc, const RunSettings& base, const CampbellSettings& s,
                                    const std::atomic<bool>* stop = nullptr,
                                    const std::function<void(const CampbellPoint&)>& each = {});

// campbell.csv's rows: rpm, mode, frequency_Hz, damping_ratio, group (the group with the largest
// share of the mode's energy), share
void write_campbell_csv(const std::vector<CampbellPoint>& points, const std::string& path);

}  // namespace beltsim
