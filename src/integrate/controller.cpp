#include "integrate/controller.hpp"

#include <algorithm>
#include <cmath>

namespace beltsim {

StepController::StepController(OdeProblem& sys, const Tolerances& tol, int q, int p, bool reduced)
    : sys_(sys), rtol_(tol.rtol), exponent_(1.0 / (q + 1)) {
  const double tighter = p > 0 ? std::min(1.0, std::pow(tol.rtol / kProportionalFrom, 1.0 / p)) : 1.0;
  rtol_ *= tighter;
  const double atol = tol.absolute() * tighter;
  atol_.resize(sys.size());
  for (int k = 0; k < sys.size(); ++k) atol_[k] = atol * sys.atol_scale(k);
  const int na = sys.answer_size();
  in_norm_.setOnes(sys.size());
  if (na > 0 && reduced)
    for (int k = 0; k < sys.size(); ++k) in_norm_[k] = sys.in_state_norm(k) ? 1.0 : 0.0;
  if (na > 0)
    for (int k = 0; k < sys.size(); ++k)
      if (sys.held_each(k)) held_.push_back(k), in_norm_[k] = 0.0;
  n_in_norm_ = std::max(1.0, in_norm_.sum());
  aatol_.resize(na), a0_.resize(na), a1_.resize(na), da_.resize(na);
  for (int a = 0; a < na; ++a) aatol_[a] = atol * sys.answer_scale(a);
  for (int a = 0; a < na; ++a)
    if (sys.checked_inside(a)) inside_.push_back(a);
}

double StepController::interior_norm(double t, const Eigen::VectorXd& y0, const Eigen::VectorXd& Z,
                                     const Eigen::VectorXd& e) {
  if (inside_.empty()) return 0;
  // the quantities up to the last one checked inside (the span tensions after them are not)
  const int count = inside_.back() + 1;
  sys_.answer(t, y0.data(), a0_.data(), count);
  sys_.answer(t, Z.data(), a1_.data(), count);
  sys_.answer_error(t, Z.data(), e.data(), da_.data(), count);
  double n = 0;
  for (int a : inside_)
    n = std::max(n, std::abs(da_[a]) / (aatol_[a] + rtol_ * std::max(std::abs(a0_[a]), std::abs(a1_[a]))));
  return std::isfinite(n) ? n : 1e300;
}

double StepController::error_norm(double t1, const Eigen::VectorXd& y0, const Eigen::VectorXd& y1,
                                  const Eigen::VectorXd& err, int* worst) {
  double sum = 0, big = -1;
  for (Eigen::Index k = 0; k < err.size(); ++k) {
    const double w = atol_[k] + rtol_ * std::max(std::abs(y0[k]), std::abs(y1[k]));
    const double r = err[k] / w;
    sum += in_norm_[k] * r * r;
    if (worst && std::abs(r) > big) big = std::abs(r), *worst = static_cast<int>(k);
  }
  double e = std::sqrt(sum / n_in_norm_);
  if (aatol_.size() > 0) {
    e /= kStateLooseness;
    for (int k : held_)
      e = std::max(e, std::abs(err[k]) / (atol_[k] + rtol_ * std::max(std::abs(y0[k]), std::abs(y1[k]))));
    const int na = static_cast<int>(da_.size());
    sys_.answer(t1, y0.data(), a0_.data(), na);
    sys_.answer(t1, y1.data(), a1_.data(), na);
    sys_.answer_error(t1, y1.data(), err.data(), da_.data(), na);
    for (Eigen::Index a = 0; a < da_.size(); ++a) {
      const double w = aatol_[a] + rtol_ * std::max(std::abs(a0_[a]), std::abs(a1_[a]));
      e = std::max(e, std::abs(da_[a]) / w);
    }
  }
  return std::isfinite(e) ? e : 1e300;
}

// Eigen's sum keeps several partial sums in vector registers: a loop adding into one double waits on
// each addition before the next (the serpentine's Newton iterations spent some 6 % of their time
// in that wait; perf, 2026-12-01)
double StepController::weighted_norm(const Eigen::VectorXd& y, const Eigen::VectorXd& v) const {
  const double sum = (v.array() / (atol_.array() + rtol_ * y.array().abs())).square().sum();
  return std::sqrt(sum / static_cast<double>(v.size()));
}

double StepController::propose(double h, double e) const {
  // safety 0.7, not the textbook 0.9: a rejected step costs a whole implicit step, and on the
  // belt's friction kinks 0.9 aims too close to the limit: 0.7 takes more steps but rejects fewer
  // (docs/integration.md, "Step-size control").
  constexpr double safety = 0.7, shrink = 0.2;
  if (e <= 0) return h * kGrowMax;
  const double factor = safety * std::pow(e, -exponent_);
  return h * std::clamp(factor, shrink, kGrowMax);  // (after a rejection, e > 1: factor < 0.7)
}

}  // namespace beltsim
