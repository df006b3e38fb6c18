#include "model/model.hpp"

#include <algorithm>

namespace beltsim {

double TimeSpeedLaw::table(double time) const {
  if (t.empty()) return 0.0;
  if (time <= t.front()) return value.front();
  if (time >= t.back()) return value.back();
  const auto it = std::upper_bound(t.begin(), t.end(), time);
  const size_t k = static_cast<size_t>(it - t.begin());  // t[k-1] <= time < t[k]
  const double s = (time - t[k - 1]) / (t[k] - t[k - 1]);
  return value[k - 1] + s * (value[k] - value[k - 1]);
}

double TimeSpeedLaw::table_slope(double time) const {
  if (t.size() < 2 || time < t.front() || time >= t.back()) return 0.0;
  const auto it = std::upper_bound(t.begin(), t.end(), time);
  const size_t k = static_cast<size_t>(it - t.begin());
  return (value[k] - value[k - 1]) / (t[k] - t[k - 1]);
}

double Model::mass_of(int k) const {
  if (k < 3 * belt.n) return (k % 3 == 2) ? belt.rot_inertia : belt.mass;
  const Pulley& p = pulleys[k - 3 * belt.n];
  return p.kinematic ? 1.0 : p.inertia;
}

std::vector<double> Model::breakpoints() const {
  std::vector<double> out;
  for (const Pulley& p : pulleys) {
    out.insert(out.end(), p.torque.t.begin(), p.torque.t.end());
    out.insert(out.end(), p.speed.t.begin(), p.speed.t.end());
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace beltsim
