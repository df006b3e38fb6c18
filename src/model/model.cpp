#include "model/model.hpp"

#include <algorithm>

namespace beltsim {

double Model::mass_of(int k) const {
  if (k < 3 * belt.n) return (k % 3 == 2) ? belt.rot_inertia : belt.mass;
  const Pulley& p = pulleys[k - 3 * belt.n];
  return p.kinematic ? 1.0 : p.inertia;
}

namespace {
std::vector<double> sorted_union(const Model& m, std::vector<double> (TimeSpeedLaw::*times)() const) {
  std::vector<double> out;
  for (const Pulley& p : m.pulleys)
    for (const TimeSpeedLaw* law : {&p.torque, &p.speed}) {
      const std::vector<double> k = (law->*times)();
      out.insert(out.end(), k.begin(), k.end());
    }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}
}  // namespace

std::vector<double> Model::breakpoints() const { return sorted_union(*this, &TimeSpeedLaw::kinks); }
std::vector<double> Model::jumps() const { return sorted_union(*this, &TimeSpeedLaw::jumps); }

}  // namespace beltsim
