#include "integrate/controller.hpp"

#include <algorithm>
#include <cmath>

namespace beltsim {

StepController::StepController(const OdeProblem& sys, const Tolerances& tol, int q)
    : rtol_(tol.rtol), exponent_(1.0 / (q + 1)) {
  const double atol = tol.absolute();
  atol_.resize(sys.size());
  for (int k = 0; k < sys.size(); ++k) atol_[k] = atol * sys.atol_scale(k);
}

double StepController::error_norm(const Eigen::VectorXd& y0, const Eigen::VectorXd& y1, const Eigen::VectorXd& err,
                                  int* worst) const {
  double sum = 0, big = -1;
  for (Eigen::Index k = 0; k < err.size(); ++k) {
    const double w = atol_[k] + rtol_ * std::max(std::abs(y0[k]), std::abs(y1[k]));
    const double r = err[k] / w;
    sum += r * r;
    if (worst && std::abs(r) > big) big = std::abs(r), *worst = static_cast<int>(k);
  }
  const double e = std::sqrt(sum / static_cast<double>(err.size()));
  return std::isfinite(e) ? e : 1e300;
}

double StepController::weighted_norm(const Eigen::VectorXd& y, const Eigen::VectorXd& v) const {
  double sum = 0;
  for (Eigen::Index k = 0; k < v.size(); ++k) {
    const double r = v[k] / (atol_[k] + rtol_ * std::abs(y[k]));
    sum += r * r;
  }
  return std::sqrt(sum / static_cast<double>(v.size()));
}

double StepController::propose(double h, double e) const {
  // safety 0.7, not the textbook 0.9: a rejected step costs a whole implicit step, and on the
  // belt's friction kinks 0.9 aims too close to the limit: 0.7 takes more steps but rejects fewer
  // (docs/integration.md, "Step-size control").
  constexpr double safety = 0.7, shrink = 0.2, grow = 5.0;
  if (e <= 0) return h * grow;
  const double factor = safety * std::pow(e, -exponent_);
  return h * std::clamp(factor, shrink, grow);  // (after a rejection, e > 1: factor < 0.7)
}

}  // namespace beltsim
