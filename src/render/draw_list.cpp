// DrawList's primitives: triangles, quads, antialiased bands and lines, discs, rings, text and
// arrows in pixel coordinates (draw_list.hpp); what a frame shows is frame_builder.cpp's.
#include "render/draw_list.hpp"

#include <algorithm>
#include <cmath>

#include "render/text.hpp"

namespace beltsim::render {

// ---- primitives -------------------------------------------------------------------------------

void DrawList::triangle(Vec2 a, Vec2 b, Vec2 c, Rgba col) {
  for (const Vec2& p : {a, b, c}) triangles.push_back({static_cast<float>(p.x()), static_cast<float>(p.y()), col});
}

void DrawList::quad(Vec2 a, Vec2 b, Vec2 c, Vec2 d, Rgba col) {
  triangle(a, b, c, col);
  triangle(a, c, d, col);
}

namespace {
SolidVertex vx(const Vec2& p, Rgba c, double da, double db) {
  return {static_cast<float>(p.x()), static_cast<float>(p.y()), c, static_cast<float>(da), static_cast<float>(db)};
}
}  // namespace

void DrawList::band(Vec2 ai, Vec2 bi, Vec2 bo, Vec2 ao, Rgba col) {
  // grow each end's cross-section by a pixel on both sides; da: distance from the inner edge,
  // db: from the outer edge
  const double wa = (ao - ai).norm(), wb = (bo - bi).norm();
  if (wa <= 0 || wb <= 0) return;
  const Vec2 ua = (ao - ai) / wa, ub = (bo - bi) / wb;
  const SolidVertex v[4] = {vx(ai - ua, col, -1, wa + 1), vx(bi - ub, col, -1, wb + 1), vx(bo + ub, col, wb + 1, -1),
                            vx(ao + ua, col, wa + 1, -1)};
  triangles.insert(triangles.end(), {v[0], v[1], v[2], v[0], v[2], v[3]});
}

void DrawList::line(Vec2 a, Vec2 b, double w, Rgba col) {
  const Vec2 d = b - a;
  const double len = d.norm();
  if (len <= 0) return;
  const Vec2 n = Vec2(-d.y(), d.x()) * (0.5 * w / len);
  band(a - n, b - n, b + n, a + n, col);
}

void DrawList::disc(Vec2 c, double r, Rgba col, int seg) {
  // a fan grown by a pixel; da falls linearly from r at the centre to -1 on the grown rim
  const double R = r + 1;
  for (int k = 0; k < seg; ++k) {
    const double a0 = 2 * M_PI * k / seg, a1 = 2 * M_PI * (k + 1) / seg;
    triangles.insert(triangles.end(), {vx(c, col, r, 1e4), vx(c + R * Vec2(std::cos(a0), std::sin(a0)), col, -1, 1e4),
                                       vx(c + R * Vec2(std::cos(a1), std::sin(a1)), col, -1, 1e4)});
  }
}

void DrawList::ring(Vec2 c, double r0, double r1, Rgba col, int seg) {
  for (int k = 0; k < seg; ++k) {
    const double a0 = 2 * M_PI * k / seg, a1 = 2 * M_PI * (k + 1) / seg;
    const Vec2 u0(std::cos(a0), std::sin(a0)), u1(std::cos(a1), std::sin(a1));
    band(c + r0 * u0, c + r0 * u1, c + r1 * u1, c + r1 * u0, col);
  }
}

namespace {

// the whole pixels covering [lo, hi] and 1 px around them (antialiased edges reach into it)
PixelRect pixel_rect(double x0, double y0, double x1, double y1) {
  const int l = static_cast<int>(std::floor(x0)) - 1, t = static_cast<int>(std::floor(y0)) - 1;
  const int r = static_cast<int>(std::ceil(x1)) + 1, b = static_cast<int>(std::ceil(y1)) + 1;
  return {l, t, r - l, b - t};
}

}  // namespace

float DrawList::text(Vec2 at, const std::string& utf8, int px, Rgba col, Align align) {
  texts.push_back(utf8);
  if (!font) return 0;
  const float w = font->width(utf8, px);
  float x = static_cast<float>(at.x()) - (align == centre ? 0.5f * w : align == right ? w : 0.0f);
  // whole pixels: glyph bitmaps are sampled texel for pixel, so text stays crisp
  x = std::round(x);
  const float y = std::round(static_cast<float>(at.y()));
  text_rects.push_back(pixel_rect(x, y - font->ascent(px), x + w, y + font->descent(px)));
  const float inv = 1.0f / Font::atlas_size;
  for (char32_t c : decode_utf8(utf8)) {
    const Glyph& g = font->glyph(c, px);
    if (g.w > 0 && g.h > 0) {
      const float x0 = x + g.left, y0 = y - g.top, x1 = x0 + g.w, y1 = y0 + g.h;
      const float u0 = g.x * inv, v0 = g.y * inv, u1 = (g.x + g.w) * inv, v1 = (g.y + g.h) * inv;
      const GlyphVertex q[6] = {{x0, y0, u0, v0, col}, {x1, y0, u1, v0, col}, {x1, y1, u1, v1, col},
                                {x0, y0, u0, v0, col}, {x1, y1, u1, v1, col}, {x0, y1, u0, v1, col}};
      glyphs.insert(glyphs.end(), q, q + 6);
    }
    x += g.advance;
  }
  return w;
}

float DrawList::boxed_text(Vec2 at, const std::string& utf8, int px, Rgba col, Rgba box, Align align) {
  const double w = font ? font->width(utf8, px) : 0;
  const double x = at.x() - (align == centre ? 0.5 * w : align == right ? w : 0.0);
  const BoxMargins b = box_margins(px);
  const Vec2 lo(x - b.pad, at.y() - b.above), hi(x + w + b.pad, at.y() + b.below);
  quad(lo, Vec2(hi.x(), lo.y()), hi, Vec2(lo.x(), hi.y()), box);
  boxes.push_back({utf8, lo, hi});
  const size_t before = text_rects.size();
  const float drawn = text(at, utf8, px, col, align);
  // one rectangle for the two: the box, grown over the text's extent should a glyph reach past it
  PixelRect r = pixel_rect(lo.x(), lo.y(), hi.x(), hi.y());
  if (text_rects.size() > before) {
    const PixelRect t = text_rects.back();
    text_rects.pop_back();
    const int x1 = std::max(r.x + r.w, t.x + t.w), y1 = std::max(r.y + r.h, t.y + t.h);
    r.x = std::min(r.x, t.x), r.y = std::min(r.y, t.y), r.w = x1 - r.x, r.h = y1 - r.y;
  }
  text_rects.push_back(r);
  return drawn;
}

void DrawList::arrow(Vec2 tail, Vec2 tip, double w, double head, Rgba col) {
  const double len = (tip - tail).norm();
  if (len <= 0) return;
  const Vec2 u = (tip - tail) / len, n(-u.y(), u.x());
  head = std::min(head, len);
  const Vec2 base = tip - head * u;
  line(tail, base + 0.5 * w * u, w, col);
  triangle(tip, base + 0.5 * head * n, base - 0.5 * head * n, col);
}

}  // namespace beltsim::render
