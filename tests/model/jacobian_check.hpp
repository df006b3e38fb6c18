// The checks and states the Jacobian tests share (jacobian_test.cpp, bristles_jacobian_test.cpp).
// Their tolerances and why are at the top of jacobian_test.cpp.
#pragma once

#include <Eigen/Core>

#include "model/drive.hpp"
#include "model/model.hpp"
#include "scene/scene.hpp"

namespace beltsim::test {

// distance of the state from the nearest kink of the contact and friction laws, in units of each
// quantity's own scale (p: 1e-6 m, N: 1e-2 N, |v_T| - Δv: 1e-7 m/s)
double kink_margin(const Model& m, const Drive& dr, double t, const Eigen::VectorXd& y);

// how many pairs are on each piece of the laws
struct Coverage {
  int free = 0, ramp = 0, deep = 0, clamped = 0, stick = 0, slip = 0;
};
Coverage coverage(const Model& m, const Drive& dr, double t, const Eigen::VectorXd& y);

// max over columns of (max |analytic - fd| / max |analytic|) for one matrix; a column's scale is
// at least `floor`
double column_error(const Eigen::MatrixXd& an, const Eigen::MatrixXd& fd, int* worst_col, double floor = 0);

// the force Jacobian (K, C, ∂f/∂t) against central differences of the forces, each column to 1e-6
void expect_jacobian_matches(const Model& m, const Drive& dr, double t, const Eigen::VectorXd& y);

// A running state: pulleys turning, each element in contact given a chosen slip, a few elements
// pushed deep or pulled out fast, random velocities on the free spans; tensioner arms turning at
// arm_rate (slips and rates are relative to the moving centre).
Eigen::VectorXd running_state(const Scene& sc, double time, double omega_scale, unsigned seed, double arm_rate = 0);

}  // namespace beltsim::test
