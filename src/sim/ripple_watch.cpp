#include "sim/ripple_watch.hpp"

#include <algorithm>
#include <cmath>

#include "io/number_text.hpp"

namespace beltsim {

std::string RippleWatch::add(const std::vector<double>& tension, const std::vector<double>& mean,
                             const std::vector<std::string>& names) {
  if (warned_ || mean.empty() || std::isnan(mean[0])) return "";  // a run's first row: no interval yet
  for (double T : tension)
    if (std::isfinite(T)) largest_ = std::max(largest_, std::abs(T));
  double dev = 0;
  size_t at = 0;
  for (size_t k = 0; k < tension.size() && k < mean.size(); ++k)
    if (std::isfinite(tension[k]) && std::isfinite(mean[k]) && std::abs(tension[k] - mean[k]) > dev)
      dev = std::abs(tension[k] - mean[k]), at = k;
  samples_++;
  if (largest_ > 0 && dev > kRippleShare * largest_) {
    rippled_++;
    if (dev / largest_ > (worst_largest_ > 0 ? worst_ / worst_largest_ : 0))
      worst_ = dev, worst_largest_ = largest_, worst_span_ = at < names.size() ? names[at] : "";
  }
  if (rippled_ < kRippleSamples || rippled_ <= kRippleFraction * samples_) return "";
  warned_ = true;
  return "the span tensions ripple as the belt's elements pass: " + worst_span_ + " swings by up to " +
         rounded_text(worst_, 3) + " N about its mean over a sample's interval (" +
         rounded_text(100 * worst_ / worst_largest_, 2) + " % of the largest tension, " +
         rounded_text(worst_largest_, 3) + " N) in " + std::to_string(rippled_) + " of " + std::to_string(samples_) +
         " samples so far, and so large a ripple's value at an instant is only as right as the belt's travel (on a "
         "two-pulley 6PK drive with a ripple of 4.6 % the span tensions were 3.8 times the contract's 10×rtol off at "
         "rtol 1e-4; at 1.8 %, 1.1 times): the tension_mean columns are the steady figures, and more elements make "
         "the ripple smaller";
}

}  // namespace beltsim
