// Step-size controller: weighted error norm and the next step size. A rejected step is a status
// returned to the driver, not an exception.
//   w_k = atol·scale_k + rtol·max(|y0_k|, |y1_k|),   ‖err‖ = sqrt(mean((err_k/w_k)²))
//   h_new = h·min(grow, max(shrink, 0.7·‖err‖^(-1/(q+1))))   with q the lower of the two orders
#pragma once

#include <Eigen/Core>

#include "integrate/system.hpp"

namespace beltsim {

struct Tolerances {
  double rtol = 1e-6;
  double atol = -1;  // per unit of each component's natural size; < 0: same as rtol
  double absolute() const { return atol < 0 ? rtol : atol; }  // the atol in force
};

class StepController {
 public:
  StepController(const OdeProblem& sys, const Tolerances& tol, int q);
  double error_norm(const Eigen::VectorXd& y0, const Eigen::VectorXd& y1, const Eigen::VectorXd& err,
                    int* worst = nullptr) const;
  // next step size after a step with error norm e (accepted when e <= 1)
  double propose(double h, double e) const;
  double weighted_norm(const Eigen::VectorXd& y, const Eigen::VectorXd& v) const;  // for the first step

 private:
  Eigen::VectorXd atol_;
  double rtol_;
  double exponent_;
};

}  // namespace beltsim
