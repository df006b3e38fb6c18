// An 8-bit RGB image, top row first, rows packed (stride = 3·width). What the renderer produces
// and the PNG and video writers consume; no dependencies, so each writer is usable alone.
// A rendered frame also carries where its text is (text_boxes): a font's version moves antialiased
// glyph pixels, so golden comparisons may leave these out (`beltsim compare --ignore-text`).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace beltsim {

// a rectangle of whole pixels: columns x..x+w-1, rows y..y+h-1 (origin top-left)
struct PixelRect {
  int x = 0, y = 0, w = 0, h = 0;
  bool operator==(const PixelRect&) const = default;
};

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;      // 3·width·height bytes, row 0 at the top
  std::vector<PixelRect> text_boxes;  // a frame's text, each piece's rectangle within the image (PNG: a tEXt chunk)

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgb(static_cast<std::size_t>(3) * w * h, 0) {}
  std::uint8_t* pixel(int x, int y) { return rgb.data() + 3 * (static_cast<std::size_t>(y) * width + x); }
  const std::uint8_t* pixel(int x, int y) const { return rgb.data() + 3 * (static_cast<std::size_t>(y) * width + x); }
};

}  // namespace beltsim
