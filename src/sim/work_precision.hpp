// Error against run time (`beltsim wp`): every integrator over a range of tolerances, each run
// measured against one reference run at a tight tolerance, on the same sample times.
//
// Errors are relative to the reference's largest magnitude of each channel over the run:
//   speed error   = max over pulleys j and samples k of |Ω_j(t_k) - Ω_j,ref(t_k)| / max_k |Ω_j,ref|
//   end error     = the same at t_end only (what the paper's Figs 5–6 read off)
//   tension error = max over spans and samples of |T(t_k) - T_ref(t_k)| / max_k |T_ref|
//   metric error  = |m - m_ref| / |m_ref| for a timeseries column m at t_end (--metric), or
//                   |m - m_ref| where m_ref = 0
// A run that exceeds the wall-time limit, diverges or is interrupted is recorded with finished =
// false, why in its note and no errors. A finished run whose error passes 10 % gets a warning.
#pragma once

#include <atomic>
#include <string>
#include <vector>

#include "sim/simulation.hpp"

namespace beltsim {

// the integrators a study runs when none are named: those that finish the paper's dry second at
// every rtol of 1e-2..1e-6 well within the wall-time limit (docs/performance.md)
const std::vector<std::string>& default_wp_integrators();

// a finished run with an error above this is warned about (its answer is not to be trusted)
constexpr double kWpErrorWarning = 0.1;

struct WpSettings {
  std::vector<std::string> integrators;   // empty: default_wp_integrators()
  std::vector<double> rtols{1e-2, 1e-3, 1e-4, 1e-5, 1e-6};
  // the reference: trbdf2 at 1e-7 is within 4.6e-8 of the pulley speeds and 6.5e-7 of the span
  // tensions of trbdf2 at 1e-8 on the paper's dry second; esdirk32 at 1e-7 within 8.0e-7 and
  // 1.6e-5, more than trbdf2's own error at rtol 1e-6 (7.0e-6), the tightest of the default rtols
  // (docs/accuracy.md, The reference)
  std::string ref_integrator = "trbdf2";
  double ref_rtol = 1e-7;
  double wall_limit = 120;                // [s] per run (the reference has none)
  RunSettings base;                       // t_end, sample interval, out_dir, probe of the script
  std::string metric;                     // a timeseries column compared at t_end ("" for none)
};

struct WpRow {
  std::string integrator;
  double rtol = 0;
  bool finished = false;
  double t_reached = 0, wall = 0;
  WorkCounters work;
  double err_speed = 0, err_speed_end = 0, err_tension = 0;
  double metric = 0, err_metric = 0;  // the metric's value at t_end and its error (NaN without one)
  std::string note;                   // why an unfinished run stopped
};

struct WpResult {
  std::vector<WpRow> rows;
  WpRow reference;
  std::string csv_path;
  std::vector<std::string> integrators;   // those studied, in order (the plot's lines)
  std::string title;                      // for the plot: elements, t_end, the reference
  std::string metric;                     // the metric's column ("" for none: the plot shows err_speed)
};

// a finished run kept the accuracy contract's bounds (docs/accuracy.md; sim/run_check.hpp): its
// pulley speeds within kCheckSpeedLimit·rtol and its span tensions within kCheckTensionLimit·rtol
// of their largest values (the contract promises that for rtol <= 1e-3)
bool within_contract(const WpRow& r);

// The errors of a finished run above kWpErrorWarning ("speed error 13.2 %, driven.creep error
// 31.9 %"), or "" (metric: the study's, "" for none)
std::string large_errors(const WpRow& r, const std::string& metric);

// Runs the study; an unknown metric column fails first (std::invalid_argument naming the columns);
// writes DIR/wp.csv and DIR/<integrator>-<rtol>/timeseries.csv. DIR/wp.png is
// drawn from the result by plot::plot_wp_png (plot/wp_plot.hpp, library beltsim_plot), so the
// engine never launches a process.
WpResult work_precision(const Scene& scene, const WpSettings& settings, const std::atomic<bool>* stop = nullptr);

}  // namespace beltsim
