#include "sim/run_error.hpp"

#include <algorithm>
#include <cmath>

#include "model/drive.hpp"
#include "scene/scene.hpp"

namespace beltsim {

void ErrorMeter::add(const double* x, const double* ref) {
  for (size_t c = 0; c < scale_.size(); ++c) {
    scale_[c] = std::max(scale_[c], std::abs(ref[c]));
    last_[c] = std::abs(x[c] - ref[c]);
    worst_[c] = std::max(worst_[c], last_[c]);
  }
}

double ErrorMeter::relative(const std::vector<double>& diff) const {
  double e = 0;
  for (size_t c = 0; c < scale_.size(); ++c) e = std::max(e, diff[c] / (scale_[c] > 0 ? scale_[c] : 1.0));
  return e;
}

double ErrorMeter::error() const { return relative(worst_); }
double ErrorMeter::error_last() const { return relative(last_); }

void speeds_and_tensions(const Scene& sc, const Drive& drive, double t, const double* y, std::vector<double>& speeds,
                         std::vector<double>& tensions) {
  const Model& m = sc.model;
  speeds.resize(static_cast<size_t>(m.n_p()));
  for (int j = 0; j < m.n_p(); ++j) speeds[j] = drive.omega(m, j, t, y + m.n_coord());
  tensions.resize(sc.route.spans.size());
  for (size_t k = 0; k < sc.route.spans.size(); ++k) tensions[k] = span_force(m, sc.route.spans[k], y);
}

}  // namespace beltsim
