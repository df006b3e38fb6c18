// What the frame builder's drawing and its text band share (frame_builder.cpp, frame_text.cpp):
// the colours of a frame's parts and how its numbers are written.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <string>

#include "render/draw_list.hpp"

namespace beltsim::render::frame {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
inline constexpr Rgba kInk{0.08f, 0.08f, 0.10f, 1};
inline constexpr Rgba kWet{0.10f, 0.42f, 0.95f, 1};
inline constexpr Rgba kSprayFill{0.10f, 0.42f, 0.95f, 0.25f};  // a spraying zone's disc: the wet colour, translucent
inline constexpr Rgba kSlip = kSlipColour;
inline constexpr Rgba kPulley{0.86f, 0.87f, 0.89f, 1};
inline constexpr Rgba kRim{0.42f, 0.43f, 0.46f, 1};
inline constexpr Rgba kSpoke{0.58f, 0.59f, 0.62f, 1};
inline constexpr Rgba kMarker{0.80f, 0.10f, 0.12f, 1};
inline constexpr Rgba kEdge{0.15f, 0.15f, 0.17f, 1};
// [px] the shortest element drawn with dark joints at its ends, and with its own two wet dashes
inline constexpr double kJointsShown = 4;

inline std::string format(const char* f, double v) {
  char b[64];
  std::snprintf(b, sizeof b, f, v);
  std::string s = b;
  // a value that rounds to zero has no sign ("slip -0.000" for a slip of -2e-5 m/s), or "+" where
  // the format asks for one; else a typographic minus
  if (!s.empty() && s[0] == '-') {
    if (s.find_first_of("123456789") == std::string::npos)
      s = std::strchr(f, '+') ? "+" + s.substr(1) : s.substr(1);
    else
      s = "\u2212" + s.substr(1);
  }
  return s;
}

// a tick label: up to 3 significant digits, no exponent for the ranges we draw
inline std::string tick(double v, double span) {
  if (std::abs(v) < 1e-12 * span) v = 0;
  const double mag = std::abs(span);
  const char* f = mag >= 100 ? "%.0f" : mag >= 10 ? "%.1f" : mag >= 1 ? "%.2f" : mag >= 0.1 ? "%.3f" : "%.2g";
  return format(f, v);
}


}  // namespace beltsim::render::frame
