// An 8-bit RGB image, top row first, rows packed (stride = 3·width). What the renderer produces
// and the PNG and video writers consume; no dependencies, so each writer is usable alone.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace beltsim {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // 3·width·height bytes, row 0 at the top

  Image() = default;
  Image(int w, int h) : width(w), height(h), rgb(static_cast<std::size_t>(3) * w * h, 0) {}
  std::uint8_t* pixel(int x, int y) { return rgb.data() + 3 * (static_cast<std::size_t>(y) * width + x); }
  const std::uint8_t* pixel(int x, int y) const { return rgb.data() + 3 * (static_cast<std::size_t>(y) * width + x); }
};

}  // namespace beltsim
