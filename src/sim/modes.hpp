// Modes of a drive about an operating point (docs/modes.md): the linearization of the equations
// of motion at a state and its eigen-analysis (natural frequencies, damping ratios, mode shapes,
// and where each mode's kinetic energy lies: which spans, pulleys, arms and rotors move).
//
// The belt's elements are Lagrangian: they travel with the belt. The Jacobian J of the right-hand
// side at a running state, taken as it stands, gives the modes of a belt whose material points are
// held where they are (a span of a running belt would ring at the fixed string's k·c/(2L)). The
// modes a sensor fixed in space sees are those of the perturbation in the space-fixed (Eulerian)
// frame: with the elements passing a fixed point at ν elements per second (ν = the mean over the
// elements of their speed along the belt over their spacing), the perturbation U of the elements'
// states as a function of the element slot obeys
//   ∂U/∂t = J·U − ν·D·U,   (D·U)_i = (U_{i+1} − U_{i−1})/2
// (a material derivative d/dt = ∂/∂t + ν·∂/∂i; central differences along the ring, which add no
// damping). The pulleys', arms' and rotors' coordinates are not transported. At rest ν = 0 and it
// is J. On a straight span it is the axially moving string (Wickert & Mote):
// f_k = k·(c² − v²)/(2L·c), c² = T/m′.
//
// The eigenvalues λ of that matrix (Eigen's dense EigenSolver; the energy integrals are left out:
// they feed nothing back) with Im λ > 0 are the oscillating modes: f = Im λ/2π, ζ = −Re λ/|λ|.
// Real eigenvalues (overdamped motion) and the zero ones (the pulleys' angles are cyclic; the belt's
// position along the ring is held by friction, a rate law) are not modes; below f_min neither.
#pragma once

#include <Eigen/Core>
#include <complex>
#include <string>
#include <vector>

#include "model/drive.hpp"
#include "scene/scene.hpp"

namespace beltsim {

struct ModeSettings {
  double f_min = 1;       // [Hz] lower modes are left out (the cyclic and frictional zero modes)
  double f_max = 2000;    // [Hz] higher modes are left out (the elements' own axial, bending and contact ringing)
  double zeta_max = 0.9;  // modes damped more are left out (nearly critically damped: the friction's stiff
                          // rate law between the belt and its pulleys, whose real eigenvalues split in pairs)
  bool transport = true;
  bool balance = true;  // balance the matrix before the eigensolver (modes.cpp; false for tests)  // false: J alone
                        // (the material frame: the belt's points held where they are)
};

struct Mode {
  std::complex<double> lambda;  // [1/s]
  double frequency = 0;         // [Hz] Im λ/2π
  double damping = 0;           // ζ = −Re λ/|λ|
  // the share of the mode's kinetic energy in each group (ModeAnalysis::groups), summing to 1
  std::vector<double> participation;
  // the displacements of the coordinates q (Model::n_coord), complex, scaled so that the largest
  // displacement of a point (an element's centre, a pulley's rim, an arm's pulley centre) is 1 m
  // and real there: q(t) = q0 + a·Re(shape·e^{iωt}) moves that point by a
  Eigen::VectorXcd shape;
  // the whole eigenvector in the analysed layout [q | v | z] (z: the bristles, Model::bristles),
  // scaled as shape (its q part is shape): y + a·Re(vector·e^{λt}) is the mode's motion in time
  Eigen::VectorXcd vector;
  int dominant = 0;  // the group with the largest share
};

struct ModeAnalysis {
  double t = 0;             // [s] the state's time
  double belt_speed = 0;    // [m/s] the elements' mean speed along the belt
  double element_rate = 0;  // ν [1/s]: elements passing a fixed point per second (0 when !transport)
  int states = 0;           // size of the matrix analysed
  // span_<a>_<b> (the route's spans, as timeseries.csv names them: the elements on no pulley,
  // by the nearest span), wrap_<p> (the elements on pulley p), pulley_<p> (its rotation; none for
  // a kinematic pulley, which does not move), arm_<p>, rotor_<p> (a coupled rotor and its clutch hub)
  std::vector<std::string> groups;
  std::vector<Mode> modes;  // by frequency
  // [m] each pulley's slip arc at the state (PulleyObs::slip_arc: its elements sliding, saturated
  // friction), by pulley index
  std::vector<double> slip_arc;
};

// Whether mode m of a is of a kind checked against a known answer (docs/modes.md): every mode at
// rest (|belt speed| below 1e-3 m/s), and at speed a span's lightly damped mode (more than 60 % of
// its energy in the spans, −0.01 < ζ < 0.05: the axially moving string). Any other mode of a running
// drive is not: check_mode (sim/mode_check.hpp) checks one in time.
bool mode_checked(const ModeAnalysis& a, const Mode& m);

// the modes of the drive d at the state y at time t (y: Model::n_state values). Throws
// std::runtime_error when the eigensolver fails, std::invalid_argument for settings out of range.
ModeAnalysis analyze_modes(const Scene& sc, const Drive& d, double t, const Eigen::VectorXd& y,
                           const ModeSettings& s = {});

// the group of every coordinate q (-1: none, a kinematic pulley's), as analyze_modes assigns them
std::vector<int> coordinate_groups(const Scene& sc, const Drive& d, double t, const Eigen::VectorXd& y,
                                   std::vector<std::string>& names);

// the state q0 + amplitude·Re(shape·e^{i·phase}) (positions only; the velocities are y's)
Eigen::VectorXd mode_state(const Eigen::VectorXd& y, const Mode& m, double amplitude, double phase);

// modes.csv's header and a mode's row: mode, frequency_Hz, damping_ratio, decay_1_s (−Re λ), then
// the participation of each group
std::vector<std::string> mode_columns(const ModeAnalysis& a);
std::vector<double> mode_row(const ModeAnalysis& a, size_t k);

}  // namespace beltsim
