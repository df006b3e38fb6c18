// A mode checked in time (docs/modes.md, "Checking a mode in time"): the drive is run on from its
// operating point twice, as it is (one run for all the modes checked together) and pushed along the
// mode (y + a·Re(eigenvector): positions, velocities and bristles, the point that moves most moved
// by a), and the difference of the two runs is watched in the space-fixed frame where the mode
// moves most: a free pulley's, an arm's or a rotor's angle, or the belt's displacement normal to a
// span at its middle (where the polygon of elements crosses the span's normal there). The
// linearization predicts that difference as a·Re(V·e^{λt}) (V the eigenvector's value there; a
// running drive's Floquet mode exactly at whole element passings, where the drive stands as it
// stood); the check reports how far the observed difference is from that over the mode's first
// period (at the whole passings in it, at least three, on a running drive), and the frequency and
// damping of the oscillation the difference holds (a Prony fit, sim/mode_check.cpp).
//
// Both runs start with every pulley's angle brought within ±π by whole turns (a coupled rotor's
// with it), which the drive's motion does not depend on: the error control weighs an angle by its
// size, and a pulley many turns round carried a noise of some 3 % of the push's response.
// The push is small: with a = 1e-8 m the velocities it gives (λ·a, 6e-6 m/s at 100 Hz) stay within
// the friction band Δv of the sticking elements (1e-5 m/s by default) and the runs' differences
// (rtol 1e-10) are far above the integrator's noise; on the paper's dry drive the response to 1e-8
// and 1e-6 m agree within a few per cent, and 1e-10 m is noise (measured).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "model/drive.hpp"
#include "scene/scene.hpp"
#include "sim/modes.hpp"

namespace beltsim {

struct ModeCheckSettings {
  double push = 1e-8;   // [m] the push along the mode: its largest point displacement
  double rtol = 1e-10;  // the runs' relative tolerance
  double periods = 6;   // the runs' length in the mode's periods
  // "agrees": the observed difference off the predicted motion by at most this (RMS over RMS) over
  // the mode's first period. A lightly damped mode 5 % off in frequency is off by ~0.2 there; the
  // paper's dry drive at 0.5 s measured 0-0.22 for 27 of its 28 Floquet modes under 180 Hz (the
  // 28th, ζ 0.72, 0.29), 0.8-1.4 for the growing modes the state's Jacobian with a transport term
  // gave and the run does not show (tests/physics/modes_running_test.cpp)
  double max_misfit = 0.25;
};

struct ModeCheck {
  std::string where;       // what was watched: "pulley_driver angle", "span_driver_driven middle", ...
  double frequency = NAN;  // [Hz] the watched difference's strongest oscillation (NaN: none)
  double damping = NAN;    // its damping ratio
  double misfit = NAN;     // RMS(observed − predicted)/RMS(predicted) over the mode's first period
  bool agrees = false;     // misfit <= the settings' max_misfit
};

// Modes ks (indices into a.modes) of the analysis a, taken at (t, y) of the drive d of sc: each
// pushed and run on, beside one plain run for them all. Throws what a run throws (a failed
// integration).
std::vector<ModeCheck> check_modes(const Scene& sc, const Drive& d, double t, const Eigen::VectorXd& y,
                                   const ModeAnalysis& a, const std::vector<size_t>& ks,
                                   const ModeCheckSettings& s = {});
// mode k alone
ModeCheck check_mode(const Scene& sc, const Drive& d, double t, const Eigen::VectorXd& y, const ModeAnalysis& a,
                     size_t k, const ModeCheckSettings& s = {});

}  // namespace beltsim
