// Text through FreeType: glyphs of one TrueType font (DejaVu Sans from fonts-dejavu-core unless
// BELTSIM_FONT names another file) rasterised on demand, at any pixel size, into one 8-bit
// coverage atlas that the GL backend uploads as a texture. CPU-side only: no GL here.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace beltsim::render {

struct Glyph {
  int x = 0, y = 0, w = 0, h = 0;  // place in the atlas [px]
  int left = 0, top = 0;           // bitmap offset from the pen position (top: up from the baseline)
  float advance = 0;               // [px]
};

class Font {
 public:
  // the font file built in (CMake found DejaVuSans.ttf), or the one the program's edge set
  // (src/app: BELTSIM_FONT; "" restores the built-in one). Set once, before any renderer is made.
  static std::string default_path();
  static void set_default_path(const std::string& path);
  // Throws std::runtime_error naming the file when FreeType cannot load it.
  explicit Font(const std::string& path = default_path());
  ~Font();
  Font(const Font&) = delete;
  Font& operator=(const Font&) = delete;

  const Glyph& glyph(char32_t code, int px);
  float width(const std::string& utf8, int px);
  // [px] the font's extent above and below the baseline at this size (both positive): where its
  // glyphs reach, for the frame's text boxes (Image::text_boxes)
  float ascent(int px);
  float descent(int px);
  const std::string& path() const { return path_; }

  // the atlas: atlas_size² bytes of coverage; version grows whenever glyphs are added
  static constexpr int atlas_size = 1024;
  const std::vector<std::uint8_t>& atlas() const { return atlas_; }
  long version() const { return version_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string path_;
  std::map<std::pair<char32_t, int>, Glyph> glyphs_;
  std::vector<std::uint8_t> atlas_;
  long version_ = 0;
  int shelf_x_ = 0, shelf_y_ = 0, shelf_h_ = 0;  // shelf packer
};

// UTF-8 to code points (invalid bytes become U+FFFD)
std::u32string decode_utf8(const std::string& s);

}  // namespace beltsim::render
