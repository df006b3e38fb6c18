// The modes of a running drive as the Floquet exponents of its motion over one element passing
// (docs/modes.md, "A running drive").
//
// The belt's elements travel with the belt: a running drive in its steady state is not a fixed
// point of the equations of motion but, in the space-fixed frame, a periodic motion of period
// T = 1/ν (ν elements pass a fixed point per second): after T every element stands where its
// neighbour stood, in its neighbour's state. A small perturbation x of the state obeys the
// variational equation along that motion,
//   x' = J(t)·x,   J(t) = ∂ẏ/∂y at the drive's own state y(t),
// whose solution over one passing is x(t0 + T) = Φ·x(t0). Taken back to the slots the elements
// stood in at t0 (the shift P: element i's rows to slot i + 1, the pulleys', arms' and rotors'
// coordinates as they are), M = P·Φ maps a perturbation of the space-fixed state at t0 to the
// same one a passing later. Its eigenvalues μ are the Floquet multipliers: a mode grows or decays
// by |μ| and turns by arg μ each passing, λ = ln μ / T. The frequency Im λ/2π is known from μ
// only up to multiples of ν (arg μ is an angle); the mode's own turning over the passing decides
// which: the eigenvector is carried through the passing again and the phase it turns through is
// followed sample by sample, as an Eulerian reading of the elements (each slot read off the two
// elements that pass it).
//
// Φ is integrated with BDF2 (implicit Euler for its first step) on equal steps of at most
// 1/(40·kFloquetResolution), whatever frequencies are listed: L-stable, so the belt's stiff contact
// and friction motion (10⁴ to 10¹⁰ s⁻¹) is damped out as it is in the drive, and second order: on
// y' = iω·y at these steps it puts a mode at kFloquetResolution 0.8 % low in frequency with a
// damping ratio of 9e-4 of its own, one at a tenth of it 8e-5 low with 1e-6, one at twice it 3 %
// low (the principal root of (1 − ⅔iωh)·r² − (4/3)·r + 1/3 = 0).
//
// What it replaces: the state's Jacobian with a transport term (the material derivative taken
// at one instant, modes.hpp) is the same on a straight span (the axially moving string), but on a
// wrap that slips it mixes the sticking elements' stiff friction with the transport and lists
// modes, some growing, that the drive does not have (docs/modes.md).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <complex>
#include <vector>

#include "model/drive.hpp"
#include "scene/scene.hpp"

namespace beltsim {

// [Hz] the frequency the BDF2 steps resolve (40 steps a period): the steps are the same whatever
// band of frequencies is listed, so that the band does not change the modes in it (a step taken
// from the band's top moved the paper's drive's heavily damped modes near half the passing rate
// across the band's 180 Hz edge, docs/modes.md)
constexpr double kFloquetResolution = 2000;

struct FloquetModes {
  double period = 0;  // [s] T = 1/|ν|
  int steps = 0;      // BDF2 steps over the period
  // how far the drive's motion is from repeating itself over the passing (0 in a steady state): the
  // RMS over the elements of the distance between an element and the one ahead of it a passing
  // before, over the pitch, and of the difference of their velocities, over the belt's RMS speed
  double position_defect = 0, velocity_defect = 0;
  // λ [1/s] with Im λ > 0 (each mode once), and its eigenvector (the perturbation of the kept
  // coordinates at t0, as `keep` lists them), column by column
  std::vector<std::complex<double>> lambda;
  Eigen::MatrixXcd vectors;
};

// ∂ẏ/∂y of the drive d of m at (t, y) (the right-hand side's analytic Jacobian, as the implicit
// integrators use it) over the coordinates `keep` of the state, in that order
Eigen::SparseMatrix<double> ode_matrix(const Model& m, const Drive& d, double t, const Eigen::VectorXd& y,
                                       const std::vector<int>& keep);

// The Floquet modes of the drive d of sc about its motion from (t0, y0), the elements passing at
// nu per second (signed: > 0 when element i runs towards element i + 1), over the coordinates
// `keep` of the state ([q | v | z] without the energy integrals: n_el elements' 3 rows first in q and
// in v, one bristle per element in z). Modes whose decay rate over the passing exceeds
// `max_decay` [1/s] are left out (their multipliers are rounding). Throws what a run throws.
FloquetModes floquet_modes(const Scene& sc, const Drive& d, double t0, const Eigen::VectorXd& y0, double nu,
                           double max_decay, const std::vector<int>& keep);

}  // namespace beltsim
