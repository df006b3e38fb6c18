// PNG files through libpng: 8-bit RGB, no interlace. Throws std::runtime_error with the path and
// libpng's message on failure. An image's text boxes (Image::text_boxes) travel in a tEXt chunk
// before the pixels, keyword kTextBoxesKey, its text "x,y,w,h;x,y,w,h;..." (pixels, origin top-left);
// none is written for an image without them. A PNG is written whole (io/output_dir.hpp: never through a link, a
// reader finds the old file or the new one).
#pragma once

#include <string>

#include "io/output_dir.hpp"
#include "media/image.hpp"

namespace beltsim {

inline constexpr const char* kTextBoxesKey = "beltsim:text-boxes";

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
// what the file's bytes can hold, checked before anything of that size is allocated; the text boxes
// too when the file has them (a chunk that is not a list of four whole numbers each, sides > 0, is
// an error)
Image read_png(const std::string& path);

}  // namespace beltsim
