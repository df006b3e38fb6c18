#include "media/image_compare.hpp"

#include <algorithm>
#include <cstdlib>

namespace beltsim {

ImageComparison compare_images(const Image& a, const Image& b, int level_tol) {
  ImageComparison c;
  if (a.width != b.width || a.height != b.height) {
    c.bad = static_cast<long>(a.width) * a.height + 1;
    return c;
  }
  c.same_size = true;
  c.diff = Image(a.width, a.height);
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const std::uint8_t *p = a.pixel(x, y), *q = b.pixel(x, y);
      int d = 0;
      for (int k = 0; k < 3; ++k) d = std::max(d, std::abs(int(p[k]) - int(q[k])));
      if (d > c.worst) c.worst = d, c.worst_x = x, c.worst_y = y;
      std::uint8_t* o = c.diff.pixel(x, y);
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
