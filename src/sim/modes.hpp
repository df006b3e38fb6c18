// Modes of a drive about an operating point (docs/modes.md): the linearization of the equations
// of motion at a state and its eigen-analysis (natural frequencies, damping ratios, mode shapes,
// and where each mode's kinetic energy lies: which spans, pulleys, arms and rotors move).
//
// At rest the modes are those of the right-hand side's Jacobian J at the state. The belt's
// elements are Lagrangian: they travel with the belt, and a running drive in its steady state is
// not a fixed point but, in the space-fixed frame, a motion that repeats itself every element
// passing (T = 1/ν, ν elements passing a fixed point per second, the mean over the elements of
// their speed along the belt over their spacing). A running belt's modes are the Floquet modes of
// that motion (sim/floquet.hpp). A slow one's (ν < kFloquetRate) are those of J with the transport
// of the space-fixed (Eulerian) frame added: the perturbation U of the elements' states as a
// function of the element slot obeys
//   ∂U/∂t = J·U − ν·D·U,   (D·U)_i = (U_{i+1} − U_{i−1})/2
// (a material derivative d/dt = ∂/∂t + ν·∂/∂i; central differences along the ring, which add no
// damping; the pulleys', arms' and rotors' coordinates are not transported). On a straight span it
// is the axially moving string (Wickert & Mote): f_k = k·(c² − v²)/(2L·c), c² = T/m′; on a wrap that
// slips it gives modes the drive does not have (docs/modes.md).
//
// The eigenvalues λ (Eigen's dense EigenSolver; the energy integrals are left out: they feed
// nothing back) with Im λ > 0 are the oscillating modes: f = Im λ/2π, ζ = −Re λ/|λ|. Real
// eigenvalues (overdamped motion) and the zero ones (the pulleys' angles are cyclic; the belt's
// position along the ring is held by friction, a rate law) are not modes; below f_min neither.
#pragma once

#include <Eigen/Core>
#include <complex>
#include <string>
#include <vector>

#include "model/drive.hpp"
#include "scene/scene.hpp"

namespace beltsim {

// [1/s] the element rate from which a running belt's modes are its motion's Floquet modes: a
// passing of at most 50 ms. The passing takes 40·kFloquetResolution·T steps (4 000 at 50 ms), each a
// factorisation and solves of the whole state: a slower belt's would take minutes (a choice of
// cost; the transport term it falls back on is not checked on a slipping wrap, docs/modes.md)
constexpr double kFloquetRate = 20;
// a motion that repeats itself less closely over a passing is not steady (the command warns):
// a velocity defect of 1 % (the paper's drive at 0.5 s: 0.06 %; a belt set running on held
// pulleys: 52 %), a position defect of 5 % of a pitch (0.3 %; 27 %)
constexpr double kSteadyVelocity = 0.01, kSteadyPosition = 0.05;
// [1/s] a law changing faster than this, relative to its value, within kForcingWindow [s] of the
// time, forces the drive (a crankshaft's ±4 rad/s of 2nd-order ripple on 84 rad/s: 8 /s)
constexpr double kForcingRate = 1, kForcingWindow = 0.05;

struct ModeSettings {
  double f_min = 1;       // [Hz] lower modes are left out (the cyclic and frictional zero modes)
  double f_max = 2000;    // [Hz] higher modes are left out (the elements' own axial, bending and contact ringing)
  double zeta_max = 0.9;  // modes damped more are left out (nearly critically damped: the friction's stiff
                          // rate law between the belt and its pulleys, whose real eigenvalues split in pairs)
  bool transport = true;  // false: J alone (the material frame: the belt's points held where they are)
  // a running belt (ν ≥ kFloquetRate): the Floquet modes of its motion over one element passing
  // (floquet.hpp); false, or a slower belt: the state's Jacobian with the transport term
  bool floquet = true;
  bool balance = true;  // balance the matrix before the eigensolver (modes.cpp; false for tests)
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
  double period = 0;        // [s] the passing analysed (floquet.hpp), 1/|ν|; 0: the state's Jacobian alone
  // over that passing, how far the motion is from repeating itself (FloquetModes)
  double position_defect = 0, velocity_defect = 0;
  // a pulley whose law changes in time near t (a speed's harmonics, a ramp; -1: none) and how
  // fast, relative to its value [1/s] (kForcingRate): it changes the motion from one passing to the
  // next
  int forced = -1;
  double forcing_rate = 0;
  int states = 0;  // size of the matrix analysed
  // span_<a>_<b> (the route's spans, as timeseries.csv names them: the elements on no pulley,
  // by the nearest span), wrap_<p> (the elements on pulley p), pulley_<p> (its rotation; none for
  // a kinematic pulley, which does not move), arm_<p>, rotor_<p> (a coupled rotor and its clutch hub)
  std::vector<std::string> groups;
  std::vector<Mode> modes;  // by frequency, then damping
  // [m] each pulley's slip arc at the state (PulleyObs::slip_arc: its elements sliding, saturated
  // friction), by pulley index
  std::vector<double> slip_arc;
};

// the modes of the drive d at the state y at time t (y: Model::n_state values). Throws
// std::runtime_error when the eigensolver fails, std::invalid_argument for settings out of range.
ModeAnalysis analyze_modes(const Scene& sc, const Drive& d, double t, const Eigen::VectorXd& y,
                           const ModeSettings& s = {});

// the group of every coordinate q (-1: none, a kinematic pulley's), as analyze_modes assigns them
std::vector<int> coordinate_groups(const Scene& sc, const Drive& d, double t, const Eigen::VectorXd& y,
                                   std::vector<std::string>& names);

// the state q0 + amplitude·Re(shape·e^{i·phase}) (positions only; the velocities are y's)
Eigen::VectorXd mode_state(const Eigen::VectorXd& y, const Mode& m, double amplitude, double phase);

// The mode's change of each element's tension (ElementObs::tension) over its cycle, linearised
// about y: c_k such that the deflection q0 + ε·Re(shape·e^{iφ}) (the velocities y's) changes
// element k's tension by ε·s·Re(c_k·e^{iφ}), scaled (s) so that the largest |c_k| is 1 (which
// spans stretch, which slacken: the mode's pictures colour the belt by it, render/mode_frames.hpp)
std::vector<std::complex<double>> mode_tension_change(const Scene& sc, const Drive& d, double t,
                                                      const Eigen::VectorXd& y, const Mode& m);

// modes.csv's header and a mode's row: mode, frequency_Hz, damping_ratio, decay_1_s (−Re λ), then
// the participation of each group
std::vector<std::string> mode_columns(const ModeAnalysis& a);
std::vector<double> mode_row(const ModeAnalysis& a, size_t k);

// where a mode's kinetic energy is, for the table of `beltsim modes`: the groups holding at least
// kWhereShare of it, largest first ("arm_tensioner 54 %, pulley_idler 21 %"); when none does, the
// energy is spread and the kWhereSpread largest are given after "spread: " (so no row is blank)
constexpr double kWhereShare = 0.2;
constexpr size_t kWhereSpread = 2;
std::string where_text(const std::vector<std::string>& groups, const std::vector<double>& participation);

}  // namespace beltsim
