// PNG files through libpng: 8-bit RGB, no interlace. Throws std::runtime_error with the path and
// libpng's message on failure. A PNG is written whole (io/output_dir.hpp: never through a link, a
// reader finds the old file or the new one).
#pragma once

#include <string>

#include "io/output_dir.hpp"
#include "media/image.hpp"

namespace beltsim {

// its missing folders made (io/output_dir.hpp, output_place)
void write_png(const std::string& path, const Image& img);
// DIR/NAME
void write_png(const OutputDir& dir, const std::string& name, const Image& img);
// the PNG file's bytes, in memory (the live view's frames); errors name `what`
std::string encode_png(const Image& img, const std::string& what);
// The largest PNG read: kMaxPngSide pixels a side (libpng's user limit) and kMaxPngPixels in all
// (300 MB as 8-bit RGB; beltsim's own frames are at most 8192x8192, its plots 20000 a side and
// 1280x720 by default)
inline constexpr unsigned kMaxPngSide = 20000;
inline constexpr long kMaxPngPixels = 100'000'000;
// reads any 8-bit or 16-bit PNG (grey, palette, alpha are converted) as 8-bit RGB: only a regular
// file (io/input_file.hpp), and only a header whose size lies within the limits above and within
// what the file's bytes can hold, checked before anything of that size is allocated
Image read_png(const std::string& path);

}  // namespace beltsim
