// The helpers every integrator shares (integrate/integrator.hpp).
#include <cmath>
#include <sstream>

#include "integrate/integrator.hpp"
#include "io/number_text.hpp"

namespace beltsim {

void hermite(double th, double h, const Eigen::VectorXd& y0, const Eigen::VectorXd& f0, const Eigen::VectorXd& y1,
             const Eigen::VectorXd& f1, Eigen::VectorXd& out) {
  // y(θ) = (1-θ)y0 + θy1 + θ(θ-1)[(1-2θ)(y1-y0) + (θ-1)h·f0 + θh·f1]
  out = (1 - th) * y0 + th * y1 + (th * (th - 1)) * ((1 - 2 * th) * (y1 - y0) + ((th - 1) * h) * f0 + (th * h) * f1);
}

std::string diverged_text(double t, double t1, const std::string& bad) {
  return "the run diverged at t = " + rounded_text(t, 9) + " s: " + bad + " in the step to t = " + rounded_text(t1, 9) +
         " s";
}

std::string rtol_problem(double rtol) {
  if (!(rtol >= kRtolMin && rtol < 1)) {
    const std::string bad = "must be in [1e-12, 1) (got " + rounded_text(rtol, 9) + ")";
    if (rtol > 0 && rtol < kRtolMin)
      return bad + ": double precision cannot honour a smaller one (the run would shorten its steps without end)";
    return bad;
  }
  return "";
}

std::string atol_problem(double atol) {
  if (atol > 0 && std::isfinite(atol)) return "";
  return "must be > 0 and finite, or left out to mean rtol (got " + rounded_text(atol, 9) + ")";
}

void check_tolerances(const Tolerances& tol) {
  if (const std::string bad = rtol_problem(tol.rtol); !bad.empty()) throw std::invalid_argument("rtol: " + bad);
  // (the unset value alone stands for rtol: a checkpoint's atol -2 is no tolerance a run was given)
  if (tol.atol == Tolerances::kAtolUnset) return;
  if (const std::string bad = atol_problem(tol.atol); !bad.empty()) throw std::invalid_argument("atol: " + bad);
}

}  // namespace beltsim
