// A duration as text for the progress lines (a run's, a sweep's): whole seconds below a minute
// ("42 s"), minutes and seconds below an hour ("2 min 05 s"), hours and minutes from an hour on
// ("3 h 07 min"); "?" when it is not finite (nothing to estimate from yet). The duration is rounded
// to the unit shown last before it is split, so that no field reads 60; and each duration is given
// in the largest unit it reaches, so that a count-down changes form only as it falls below an hour
// or a minute (with 90 s and 90 min as the bounds, a trial's estimate read "about 1 h 36 min left",
// then "about 88 min 31 s left").
#pragma once

#include <string>

namespace beltsim {

std::string duration_text(double seconds);

}  // namespace beltsim
