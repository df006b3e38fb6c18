// Colour maps for one scalar per belt element.
//
// Unsigned quantities (tension, normal force, μ) use a viridis-like map: perceptually uniform,
// monotonic in lightness, readable in grey and by colour-blind viewers; it is interpolated
// linearly in sRGB between anchors taken from matplotlib's viridis (van der Walt & Smith).
// Signed quantities (friction force, slip velocity along the belt's travel) use a diverging
// cool-warm map (Moreland 2009): blue for negative, light grey at zero, red for positive, so the
// sign and the magnitude read apart.
//
// The map is banded: `levels` equal steps over the range, one flat colour each, as in contour
// plots, so a colour reads back to a value interval on the colour bar (and a value one step off
// shows as another colour: the golden tests rely on it). Values outside the range take the end
// colours.
#pragma once

#include <string>

namespace beltsim::render {

struct Rgba {
  float r = 0, g = 0, b = 0, a = 1;
};

enum class ColourMap { viridis, diverging };

// continuous map at x in [0, 1] (clamped)
Rgba colour_at(ColourMap map, double x);

struct ColourScale {
  ColourMap map = ColourMap::viridis;
  double lo = 0, hi = 1;  // value range of the bar
  int levels = 10;        // bands; 0: continuous

  // band of a value: 0..levels-1 (clamped), or -1 for NaN
  int band(double value) const;
  // colour of a value; NaN gives `none`
  Rgba colour(double value) const;
  Rgba none{0.62f, 0.62f, 0.62f, 1};
};

}  // namespace beltsim::render
