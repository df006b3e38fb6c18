// A duration as text for the progress lines (a run's, a sweep's): whole seconds below 90 s
// ("42 s"), minutes and seconds below 90 min ("2 min 05 s"), hours and minutes above ("3 h 07 min");
// "?" when it is not finite (nothing to estimate from yet). The duration is rounded to the unit
// shown last before it is split, so that no field reads 60.
#pragma once

#include <string>

namespace beltsim {

std::string duration_text(double seconds);

}  // namespace beltsim
