#include "io/duration_text.hpp"

#include <cmath>
#include <cstdio>

namespace beltsim {

std::string duration_text(double s) {
  if (!std::isfinite(s)) return "?";
  char b[64];
  const double whole = std::round(s);  // seconds (doubles: a duration of any size has its text)
  if (whole < 60) {
    std::snprintf(b, sizeof b, "%.0f s", whole);
  } else if (whole < 3600) {  // (59 min 59.6 s is 1 h 00 min, not "60 min 00 s")
    std::snprintf(b, sizeof b, "%.0f min %02.0f s", std::floor(whole / 60), std::fmod(whole, 60));
  } else {
    const double minutes = std::round(s / 60);
    std::snprintf(b, sizeof b, "%.0f h %02.0f min", std::floor(minutes / 60), std::fmod(minutes, 60));
  }
  return b;
}

}  // namespace beltsim
