// The integrators' test problem with a known solution: a harmonic oscillator y1' = y2, y2' = -y1
// beside a Prothero–Robinson component y3' = λ·(y3 - sin t) + cos t (non-autonomous, so the ∂F/∂t
// terms of the Rosenbrock method are exercised; stiff for λ ≪ -1); exact solution
// (cos t, -sin t, sin t). It brings its own dense 3x3 linear solver.
#pragma once

#include <cmath>

#include <Eigen/Dense>

#include "integrate/system.hpp"

namespace beltsim::test {

class SmoothProblem final : public OdeProblem, public LinearSolver {
 public:
  explicit SmoothProblem(double lambda) : lambda_(lambda) {}
  int size() const override { return 3; }
  void rhs(double t, const double* y, double* dy) override {
    dy[0] = y[1];
    dy[1] = -y[0];
    dy[2] = lambda_ * (y[2] - std::sin(t)) + std::cos(t);
  }
  bool prepare_jacobian(double t, const double*) override {
    J_.setZero();
    J_(0, 1) = 1;
    J_(1, 0) = -1;
    J_(2, 2) = lambda_;
    t_ = t;
    return true;
  }
  void time_derivative(double* ft) const override {
    ft[0] = ft[1] = 0;
    ft[2] = -lambda_ * std::cos(t_) - std::sin(t_);
  }
  bool factor(double s) override {
    lu_.compute(s * Eigen::Matrix3d::Identity() - J_);
    return true;
  }
  void solve(const double* r, double* u) override {
    Eigen::Map<Eigen::Vector3d> out(u);
    out = lu_.solve(Eigen::Map<const Eigen::Vector3d>(r));
  }
  // the exact solution at t
  static Eigen::Vector3d exact(double t) { return {std::cos(t), -std::sin(t), std::sin(t)}; }

 private:
  double lambda_, t_ = 0;
  Eigen::Matrix3d J_;
  Eigen::PartialPivLU<Eigen::Matrix3d> lu_;
};

}  // namespace beltsim::test
