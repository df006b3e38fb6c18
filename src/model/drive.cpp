#include "model/drive.hpp"

#include <algorithm>

namespace beltsim {

namespace {
std::vector<double> sorted_union(const Drive& d, std::vector<double> (TimeSpeedLaw::*times)() const) {
  std::vector<double> out;
  for (const PulleyDrive& p : d.pulleys)
    for (const TimeSpeedLaw* law : {&p.torque, &p.speed}) {
      const std::vector<double> k = (law->*times)();
      out.insert(out.end(), k.begin(), k.end());
    }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}
}  // namespace

std::vector<double> Drive::breakpoints() const { return sorted_union(*this, &TimeSpeedLaw::kinks); }
std::vector<double> Drive::jumps() const { return sorted_union(*this, &TimeSpeedLaw::jumps); }

}  // namespace beltsim
