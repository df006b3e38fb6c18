#include "render/text.hpp"

#include <ft2build.h>
#include FT_FREETYPE_H

#include <cmath>
#include <cstdlib>
#include <stdexcept>

#ifndef BELTSIM_FONT_PATH
#define BELTSIM_FONT_PATH "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"
#endif

namespace beltsim::render {

struct Font::Impl {
  FT_Library lib = nullptr;
  FT_Face face = nullptr;
  int size = 0;
};

namespace {
std::string& default_font() {
  static std::string path = BELTSIM_FONT_PATH;
  return path;
}
}  // namespace

std::string Font::default_path() { return default_font(); }
void Font::set_default_path(const std::string& path) { default_font() = path.empty() ? BELTSIM_FONT_PATH : path; }

Font::Font(const std::string& path) : impl_(std::make_unique<Impl>()), path_(path), atlas_(atlas_size * atlas_size, 0) {
  if (FT_Init_FreeType(&impl_->lib)) throw std::runtime_error("FreeType could not be initialised");
  if (FT_New_Face(impl_->lib, path.c_str(), 0, &impl_->face)) {
    FT_Done_FreeType(impl_->lib);
    throw std::runtime_error("cannot load the font " + path +
                             " (Debian package fonts-dejavu-core, or set BELTSIM_FONT to a .ttf file)");
  }
}

Font::~Font() {
  FT_Done_Face(impl_->face);
  FT_Done_FreeType(impl_->lib);
}

const Glyph& Font::glyph(char32_t code, int px) {
  const auto key = std::make_pair(code, px);
  if (auto it = glyphs_.find(key); it != glyphs_.end()) return it->second;
  FT_Face f = impl_->face;
  if (impl_->size != px) FT_Set_Pixel_Sizes(f, 0, px), impl_->size = px;
  Glyph g;
  if (FT_Load_Char(f, code, FT_LOAD_RENDER) == 0) {
    const FT_Bitmap& b = f->glyph->bitmap;
    g.w = static_cast<int>(b.width);
    g.h = static_cast<int>(b.rows);
    g.left = f->glyph->bitmap_left;
    g.top = f->glyph->bitmap_top;
    g.advance = static_cast<float>(f->glyph->advance.x) / 64.0f;
    // shelf packing with a 1 px border so bilinear sampling never bleeds between glyphs
    if (shelf_x_ + g.w + 1 > atlas_size) shelf_x_ = 0, shelf_y_ += shelf_h_ + 1, shelf_h_ = 0;
    if (shelf_y_ + g.h + 1 > atlas_size) throw std::runtime_error("glyph atlas full");
    g.x = shelf_x_ + 1;
    g.y = shelf_y_ + 1;
    for (int r = 0; r < g.h; ++r)
      for (int c = 0; c < g.w; ++c) atlas_[(g.y + r) * atlas_size + g.x + c] = b.buffer[r * b.pitch + c];
    shelf_x_ += g.w + 1;
    shelf_h_ = std::max(shelf_h_, g.h + 1);
    version_++;
  }
  return glyphs_.emplace(key, g).first->second;
}

float Font::width(const std::string& utf8, int px) {
  float w = 0;
  for (char32_t c : decode_utf8(utf8)) w += glyph(c, px).advance;
  return w;
}

float Font::ascent(int px) {
  FT_Face f = impl_->face;
  if (impl_->size != px) FT_Set_Pixel_Sizes(f, 0, px), impl_->size = px;
  return static_cast<float>(f->size->metrics.ascender) / 64.0f;
}

float Font::descent(int px) {
  FT_Face f = impl_->face;
  if (impl_->size != px) FT_Set_Pixel_Sizes(f, 0, px), impl_->size = px;
  return static_cast<float>(-f->size->metrics.descender) / 64.0f;
}

std::u32string decode_utf8(const std::string& s) {
  std::u32string out;
  for (size_t i = 0; i < s.size();) {
    const unsigned char c = s[i];
    int n = c < 0x80 ? 0 : (c >> 5) == 6 ? 1 : (c >> 4) == 14 ? 2 : (c >> 3) == 30 ? 3 : -1;
    if (n < 0) {
      out.push_back(0xFFFD), ++i;
      continue;
    }
    char32_t cp = n == 0 ? c : c & (0x3F >> n);
    bool ok = true;
    for (int k = 1; k <= n; ++k) {
      if (i + k >= s.size() || (static_cast<unsigned char>(s[i + k]) >> 6) != 2) {
        ok = false;
        break;
      }
      cp = (cp << 6) | (static_cast<unsigned char>(s[i + k]) & 0x3F);
    }
    if (!ok) {
      out.push_back(0xFFFD), ++i;
      continue;
    }
    out.push_back(cp);
    i += n + 1;
  }
  return out;
}

}  // namespace beltsim::render
