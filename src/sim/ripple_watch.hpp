// A run's warning that its span tensions ripple too much for the accuracy contract (docs/accuracy.md).
//
// A span's tension ripples as the belt's elements pass the pulleys (the belt's division: a 6PK belt
// of 60 elements on a two-pulley drive at 9.6 m/s swings its slack span by ±28 N, 4.6 % of the
// largest tension, at 570 Hz). The value at an instant is then only as right as where the belt has
// travelled to: an error of the belt's travel a thousandth of an element's pitch shifts the ripple's
// phase by that much, and the tension by 2π·10^-3 of its swing. The step control holds the speeds
// to the contract, not the travel to a thousandth of a pitch, and such a run's span tensions were
// 2.5 to 3.8 times the contract's 10·rtol off at rtol 1e-4 (two pulleys, the crankshaft's speed
// ramped to 120 rad/s, a 6PK belt at 40, 60 and 69 elements: ripples of 11, 4.6 and 4.4 % of the
// largest tension; at 100 elements 1.8 % and 1.1 times), where the rows of the accuracy matrix,
// whose ripple passes 1.5 % of the largest tension in at most 3 % of their samples (the
// decoupler's, warned of already, in 77 %), keep it. `beltsim wp` against rtol 1e-7, commit
// `710d4ed`, 2026-12-01.
//
// So at every sample of a run that does not check its own error, each span's tension is compared
// with its mean over the sample's interval (the timeseries' tension and tension_mean columns); a
// sample whose largest |tension - mean| passes kRippleShare of the largest tension so far counts,
// and the run warns once when kRippleSamples or more samples, and more than kRippleFraction of
// them, have counted.
#pragma once

#include <string>
#include <vector>

namespace beltsim {

constexpr double kRippleShare = 0.015;
constexpr double kRippleFraction = 0.25;
constexpr long kRippleSamples = 20;

class RippleWatch {
 public:
  // one sample: each span's tension [N] and its mean over the interval since the last sample
  // (NaN in a run's first row), the spans' names as the timeseries' columns have them. Returns
  // the reason to warn the first time the criterion above holds, "" otherwise (and ever after)
  std::string add(const std::vector<double>& tension, const std::vector<double>& mean,
                  const std::vector<std::string>& names);

 private:
  long samples_ = 0, rippled_ = 0;
  double largest_ = 0;        // [N] the largest span tension so far
  double worst_ = 0;          // [N] the largest |tension - mean| so far
  double worst_largest_ = 0;  // [N] the largest tension when it was seen
  std::string worst_span_;
  bool warned_ = false;
};

}  // namespace beltsim
