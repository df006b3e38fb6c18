// The golden images' metric, shared by the project's golden tests (tests/render/golden_test.cpp)
// and `beltsim compare` on two PNGs.
//
// A pixel differs when any channel differs by more than `level_tol` of 255 levels; two images
// match when they have the same size and at most `max_bad_pixels` pixels differ.
// - Why the defaults catch a wrong picture: one colour band of the 10-band maps moves a channel by
//   10–40 levels over every pixel of the elements concerned (thousands of pixels); a belt element
//   shifted by half its thickness changes over a hundred pixels along its edges (both measured by
//   the golden tests, which must fail the comparison).
// - Why they are not too strict: llvmpipe differs across CPUs and Mesa versions by a level or two
//   (pygfx uses 3), antialiased edges by a few more where coverage rounds differently; 16 levels
//   leaves room for that on every pixel, and 12 pixels for a few edge pixels whose coverage flips.
// A mask leaves pixels out: inside any of its rectangles a pixel is neither compared nor counted
// (`beltsim compare --mask`, and --ignore-text with the frames' text boxes: a font's version moves
// antialiased glyph pixels by far more than these tolerances).
#pragma once

#include <vector>

#include "media/image.hpp"

namespace beltsim {

struct ImageTolerance {
  int level_tol = 16;        // [levels of 255] a channel may differ by this much
  long max_bad_pixels = 12;  // pixels that may differ by more
};

struct ImageComparison {
  bool same_size = false;
  long bad = 0;                  // pixels beyond level_tol (width·height + 1 when the sizes differ)
  int worst = 0;                 // largest channel difference
  int worst_x = 0, worst_y = 0;  // the first pixel with the largest difference
  long masked = 0;               // pixels left out (inside the mask, clipped to the image)
  // differing pixels red, masked ones dark blue (shaded by a), the others grey (from a); empty when
  // the sizes differ
  Image diff;

  bool match(const ImageTolerance& tol) const { return same_size && bad <= tol.max_bad_pixels; }
};

// mask: the rectangles left out, in pixels (clipped to the images; they may overlap)
ImageComparison compare_images(const Image& a, const Image& b, int level_tol = ImageTolerance{}.level_tol,
                               const std::vector<PixelRect>& mask = {});

}  // namespace beltsim
