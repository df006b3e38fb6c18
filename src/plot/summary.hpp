// A run's review figures over a time window, from its output folder (timeseries.csv and
// parameters.csv, docs/outputs.md): `beltsim summary DIR` and a run's `r:summary{}` (docs/summary.md).
//
// Every figure is one Figure (section, item, quantity, value, unit); the printed table, the CSV and
// the Lua table are all made from that one list. Over the window's samples (t in [from, to]):
//   spans    span_<a>_<b>: tension_mean, tension_min, tension_max [N]
//   pulleys  omega_mean [rad/s]; slip_speed_mean [m/s] (belt minus rim, as the CSV's slip_speed);
//            speed_loss = slip_speed_mean / belt speed; creep_mean, creep_pitch_mean
//   wraps    wrap [rad] from parameters.csv (the pitch line's wrap at t = 0); mu, mu_min: the mean
//            and least of the wrap's μ (<p>.mu, the mean μ of the elements on it at a sample);
//            slip_arc_share = mean slip_arc / mean contact_arc, slip_arc_share_max (the worst
//            sample); capstan_ratio = (T1 − m'v²)/(T2 − m'v²) of the mean tensions of the spans
//            either side (T1 the larger); capstan_limit = e^{μθ} (μ = mu); capstan_margin, _mean:
//            the least and the mean over the samples of e^{μθ}/ratio with each sample's μ,
//            tensions and belt speed (below 1 the wrap cannot hold the ratio: gross slip);
//            slip_arc_share_capstan = ln(ratio)/(μθ), the creep theory's share of the wrap that slips
//   hubs     hub_load_mean, hub_load_max [N] (the CSV's hub_load); hub_load_spans [N] =
//            √(F1² + F2² − 2·F1·F2·cos θ), F = T − m'v² of the mean span tensions either side
//            (v the belt speed): the force the wrap θ exerts on the hub, without the centrifugal
//   arms     arm_angle_mean, _min, _max, arm_angle_swing = max − min [rad], arm_rate_peak [rad/s]
//   rotors   rotor_speed_mean [rad/s]; overrun_count, overrun_time [s], overrun_longest [s]: the
//            intervals where s·coupling_torque < 0, s the sign of the pulley's mean speed (the
//            rotor runs ahead and the coupling holds it back: a one-way clutch open, a two-way
//            spring driving the pulley), their ends interpolated linearly between samples
//   loss     (with the energy.* columns, `energy = true`) axial, bending, contact, friction,
//            total [W]: the channels' dissipated energy over the window / its duration; input,
//            output [W]: the sums of the pulleys' mean powers M·ω over the window (ω the rotor's
//            where coupled; M the interval means `torque_mean`) that are > 0 (the drivers) and
//            < 0 (the loads, as a positive power); stored [W]: the change of energy.mechanical
//            over the window / its duration (input − output = total + stored; a run at a loose
//            tolerance misses it: the table says so, Summary::imbalance); share = total / input
//   window   from, to [s] (the first and last sample's times), rows, belt_speed [m/s] (the mean
//            of |ω|·R + slip_speed of the first pulley: the belt's speed along the travel on its
//            wrap, model/observables.hpp)
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace beltsim::plot {

struct Figure {
  std::string section, item;  // item "" in the sections of one item (window, loss)
  std::string quantity;
  double value;
  std::string unit;    // "" for none
  bool count = false;  // a whole number of things (rows, overrun_count): a Lua integer
};

struct Overrun {
  std::string pulley;
  std::vector<std::pair<double, double>> intervals;  // [s] from, to
};

struct Summary {
  std::string dir;
  std::vector<Figure> figures;
  std::vector<Overrun> overruns;  // one per coupled pulley
  bool losses = false;            // the run carried the energy.* columns
  bool mu_per_sample = true;      // the run carried the wraps' <pulley>.mu (else: belt.mu_min throughout)
  // how the run ended (parameters.csv's end.status and its note; "" when it has none: a run still
  // running or killed outright): the table says so first when that is not "ok", since the figures of
  // a run that diverged or was stopped read like a result otherwise (trial 16: a runaway's creep of
  // -158 under a plain header)
  std::string end_status, end_note;
  std::string integrator;  // parameters.csv's run.integrator ("" when it has none)
  // [W] input − output − (total + stored): 0 but for the bias of the interval means of the belt
  // torques at the run's tolerance, which a kinematic pulley's torque_mean and so input and output
  // carry (docs/outputs.md, interval means); the table says so past kImbalanceShare of the input
  double imbalance = 0;
  static constexpr double kImbalanceShare = 0.02;
  // the states a script set inside the window (events.csv's <pulley>.speed, .arm, .rotor rows, as
  // "crankshaft.speed at t = 0.08 s"): each puts in or takes out energy that no torque does work
  // for, which `stored` counts and `input` does not (docs/outputs.md, the energy columns)
  std::vector<std::string> jumps;
};

// Throws std::runtime_error naming the file (and line) for a missing or unreadable file, a
// parameters.csv row the figures need, a window with no samples or from > to.
Summary summarize(const std::string& dir, double from, double to);

// the table printed by `beltsim summary`: a header line, then per section its items as rows and
// its quantities as columns with their units, numbers to 4 significant digits
std::string summary_table(const Summary& s);

// the CSV's header names, "<item or section>.<quantity>_<unit>" (units as wp.csv's: N, rad_s,
// m_s, W, s, rad; none for a count or a ratio), and its one row
std::vector<std::string> summary_columns(const Summary& s);
void write_summary_csv(const Summary& s, const std::string& path);

// span tensions, arm angles and coupled pulleys' and rotors' speeds over the window, through
// plot_png; the overruns' starts and the run's events as marks
void plot_summary(const Summary& s, const std::string& png);

}  // namespace beltsim::plot
