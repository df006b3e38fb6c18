// Error against run time (`beltsim wp`): every integrator over a range of tolerances, each run
// measured against one reference run at a tight tolerance, on the same sample times.
//
// Errors are relative to the reference's largest magnitude of each channel over the run:
//   speed error   = max over pulleys j and samples k of |Ω_j(t_k) - Ω_j,ref(t_k)| / max_k |Ω_j,ref|
//   end error     = the same at t_end only (what the paper's Figs 5–6 read off)
//   tension error = max over spans and samples of |T(t_k) - T_ref(t_k)| / max_k |T_ref|
// A run that exceeds the wall-time limit is recorded with finished = false and no errors.
#pragma once

#include <atomic>
#include <string>
#include <vector>

#include "sim/simulation.hpp"

namespace beltsim {

struct WpSettings {
  std::vector<std::string> integrators;   // empty: every name of integrator_names()
  std::vector<double> rtols{1e-2, 1e-3, 1e-4, 1e-5, 1e-6};
  std::string ref_integrator = "esdirk32";
  double ref_rtol = 1e-7;
  double wall_limit = 120;                // [s] per run (the reference has none)
  RunSettings base;                       // t_end, sample interval, out_dir, probe of the script
};

struct WpRow {
  std::string integrator;
  double rtol = 0;
  bool finished = false;
  double t_reached = 0, wall = 0;
  WorkCounters work;
  double err_speed = 0, err_speed_end = 0, err_tension = 0;
};

struct WpResult {
  std::vector<WpRow> rows;
  WpRow reference;
  std::string csv_path;
  std::vector<std::string> integrators;   // those studied, in order (the plot's lines)
  std::string title;                      // for the plot: elements, t_end, the reference
};

// Runs the study; writes DIR/wp.csv and DIR/<integrator>-<rtol>/timeseries.csv. DIR/wp.png is
// drawn from the result by plot::plot_wp_png (plot/wp_plot.hpp, library beltsim_plot), so the
// engine never launches a process.
WpResult work_precision(const Scene& scene, const WpSettings& settings, const std::atomic<bool>* stop = nullptr);

}  // namespace beltsim
