// PNG files through libpng: 8-bit RGB, no interlace. Throws std::runtime_error with the path and
// libpng's message on failure. A PNG is written whole (io/output_dir.hpp: never through a link, a
// reader finds the old file or the new one).
#pragma once

#include <string>

#include "io/image.hpp"
#include "io/output_dir.hpp"

namespace beltsim {

void write_png(const std::string& path, const Image& img);
// DIR/NAME
void write_png(const OutputDir& dir, const std::string& name, const Image& img);
// the PNG file's bytes, in memory (the live view's frames); errors name `what`
std::string encode_png(const Image& img, const std::string& what);
// reads any 8-bit or 16-bit PNG (grey, palette, alpha are converted) as 8-bit RGB
Image read_png(const std::string& path);

}  // namespace beltsim
