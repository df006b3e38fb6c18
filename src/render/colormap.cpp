#include "render/colormap.hpp"

#include <algorithm>
#include <cmath>

namespace beltsim::render {

namespace {

struct Anchor {
  double x;
  float r, g, b;
};

// matplotlib's viridis sampled at these x (its 256-entry table, rounded to 4 digits)
constexpr Anchor kViridis[] = {
    {0.000, 0.2670f, 0.0049f, 0.3294f}, {0.125, 0.2826f, 0.1409f, 0.4575f}, {0.250, 0.2539f, 0.2653f, 0.5300f},
    {0.375, 0.2068f, 0.3718f, 0.5531f}, {0.500, 0.1636f, 0.4711f, 0.5581f}, {0.625, 0.1276f, 0.5669f, 0.5506f},
    {0.750, 0.1347f, 0.6586f, 0.5176f}, {0.875, 0.2669f, 0.7488f, 0.4406f}, {0.9375, 0.6266f, 0.8546f, 0.2234f},
    {1.000, 0.9932f, 0.9062f, 0.1439f},
};

// Moreland's cool-warm diverging map (his 8-bit table at eighths), symmetric in CIE L*
constexpr Anchor kCoolWarm[] = {
    {0.000, 0.2314f, 0.2980f, 0.7529f}, {0.125, 0.3843f, 0.5098f, 0.9176f}, {0.250, 0.5529f, 0.6902f, 0.9961f},
    {0.375, 0.7216f, 0.8157f, 0.9765f}, {0.500, 0.8667f, 0.8667f, 0.8667f}, {0.625, 0.9608f, 0.7686f, 0.6784f},
    {0.750, 0.9569f, 0.6039f, 0.4824f}, {0.875, 0.8706f, 0.3765f, 0.3020f}, {1.000, 0.7059f, 0.0157f, 0.1490f},
};

template <size_t N>
Rgba interpolate(const Anchor (&a)[N], double x) {
  x = std::clamp(x, 0.0, 1.0);
  size_t k = 1;
  while (k < N - 1 && a[k].x < x) ++k;
  const double s = (x - a[k - 1].x) / (a[k].x - a[k - 1].x);
  auto mix = [&](float u, float v) { return static_cast<float>(u + s * (v - u)); };
  return {mix(a[k - 1].r, a[k].r), mix(a[k - 1].g, a[k].g), mix(a[k - 1].b, a[k].b), 1.0f};
}

}  // namespace

Rgba colour_at(ColourMap map, double x) {
  return map == ColourMap::viridis ? interpolate(kViridis, x) : interpolate(kCoolWarm, x);
}

int ColourScale::band(double value) const {
  if (std::isnan(value)) return -1;
  const double x = (value - lo) / (hi - lo);
  if (levels <= 0) return 0;
  return std::clamp(static_cast<int>(std::floor(x * levels)), 0, levels - 1);
}

Rgba ColourScale::colour(double value) const {
  if (std::isnan(value)) return none;
  if (levels <= 0) return colour_at(map, (value - lo) / (hi - lo));
  return colour_at(map, (band(value) + 0.5) / levels);
}

}  // namespace beltsim::render
