// The helpers every integrator shares (integrate/integrator.hpp).
#include <cmath>
#include <sstream>

#include "integrate/integrator.hpp"

namespace beltsim {

void hermite(double th, double h, const Eigen::VectorXd& y0, const Eigen::VectorXd& f0, const Eigen::VectorXd& y1,
             const Eigen::VectorXd& f1, Eigen::VectorXd& out) {
  // y(θ) = (1-θ)y0 + θy1 + θ(θ-1)[(1-2θ)(y1-y0) + (θ-1)h·f0 + θh·f1]
  out = (1 - th) * y0 + th * y1 + (th * (th - 1)) * ((1 - 2 * th) * (y1 - y0) + ((th - 1) * h) * f0 + (th * h) * f1);
}

std::string fmt_time(double v) {
  std::ostringstream s;
  s.precision(9);
  s << v;
  return s.str();
}

void check_tolerances(const Tolerances& tol) {
  if (!(tol.rtol > 0 && tol.rtol < 1))
    throw std::invalid_argument("rtol: must be in (0, 1) (got " + fmt_time(tol.rtol) + ")");
  if (!(tol.atol < 0 || (tol.atol > 0 && std::isfinite(tol.atol))) || std::isnan(tol.atol))
    throw std::invalid_argument("atol: must be > 0 and finite, or left out to mean rtol (got " + fmt_time(tol.atol) +
                                ")");
}

}  // namespace beltsim
