#include "media/image_compare.hpp"

#include <algorithm>
#include <cstdlib>
#include <vector>

namespace beltsim {

ImageComparison compare_images(const Image& a, const Image& b, int level_tol, const std::vector<PixelRect>& mask) {
  ImageComparison c;
  if (a.width != b.width || a.height != b.height) {
    c.bad = static_cast<long>(a.width) * a.height + 1;
    return c;
  }
  c.same_size = true;
  c.diff = Image(a.width, a.height);
  // one flag a pixel: overlapping rectangles count once
  std::vector<char> out(static_cast<size_t>(a.width) * a.height, 0);
  for (const PixelRect& r : mask) {
    const int x0 = std::max(r.x, 0), y0 = std::max(r.y, 0);
    const int x1 = std::min(r.x + r.w, a.width), y1 = std::min(r.y + r.h, a.height);
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) out[static_cast<size_t>(y) * a.width + x] = 1;
  }
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const std::uint8_t *p = a.pixel(x, y), *q = b.pixel(x, y);
      std::uint8_t* o = c.diff.pixel(x, y);
      if (out[static_cast<size_t>(y) * a.width + x]) {
        c.masked++;
        const int g = (p[0] + p[1] + p[2]) / 3;  // dark blue, lighter where a is light: text stays legible
        o[0] = o[1] = static_cast<std::uint8_t>(g / 6), o[2] = static_cast<std::uint8_t>(90 + g / 4);
        continue;
      }
      int d = 0;
      for (int k = 0; k < 3; ++k) d = std::max(d, std::abs(int(p[k]) - int(q[k])));
      if (d > c.worst) c.worst = d, c.worst_x = x, c.worst_y = y;
      if (d > level_tol) {
        c.bad++;
        o[0] = 255, o[1] = 0, o[2] = 0;
      } else {
        o[0] = o[1] = o[2] = static_cast<std::uint8_t>(128 + (p[0] + p[1] + p[2]) / 12);
      }
    }
  return c;
}

}  // namespace beltsim
