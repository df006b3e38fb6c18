// The CPU-side draw list of one frame (MuJoCo's abstract scene): coloured triangles and glyph
// quads in pixel coordinates (origin top-left, y down), built from the Scene and a state, with
// no GL involved, so tests can check what will be drawn. The GL backend (gl_renderer) only
// uploads and draws it.
//
// A frame shows
// - pulleys: disc, rim, six spokes and one red marker spoke (rotation and slip show as the marks
//   turn), the name below the hub, or beside the pulley where it does not fit on the disc;
// - the belt element by element: a band through the element centres, each element a quad from
//   the joint with its predecessor to the joint with its successor, coloured by the chosen
//   quantity on a banded colour map; the centres' deviation from the nominal path (the pitch
//   line round the pulleys where they are now, a tensioner's moving with its arm, sunk by the
//   static penetration on each pulley) magnified by `magnify`;
// - wet elements (μ below the largest μ of the belt as the scene built it) with a dashed blue line along the outer
// (back) edge;
// - elements that slip (model/observables.hpp: |slip| > Δv, outside the friction band) with a
//   magenta band along the inner edge (a colour neither colour map has), so stick and slip arcs
//   read at a glance whatever the quantity;
// - an arrow beside the belt on its outer side showing the direction of travel, at the middle of
//   each span (in a view that shows no span's middle, beside the visible element nearest the
//   centre);
// - a colour bar with the quantity, its unit, its range and band edges; a legend;
// - time, each pulley's speed and its slip (belt speed minus rim speed) as text, the pulleys' lines
//   in columns beside the colour bar, or in two across the whole width above it.
// Text stands on a box of the background's colour, so it stays readable where the belt runs under
// it (zoomed views).
#pragma once

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "media/image.hpp"
#include "model/model.hpp"
#include "render/colormap.hpp"
#include "scene/route.hpp"
#include "sim/frames.hpp"

namespace beltsim {
struct Scene;
}

namespace beltsim::render {

class Font;

// Antialiasing is analytic (cheaper than MSAA on llvmpipe, measured 3×): a shape's geometry is
// grown by a pixel across each antialiased edge, and each vertex carries its signed distance
// [px] from up to two such edges (positive inside); the fragment shader scales the alpha by
// the pixel's coverage clamp(d + 0.5, 0, 1) for each. Edges shared by neighbouring shapes (the
// joints between belt elements) are not antialiased, so no seams appear between them.
struct SolidVertex {
  float x, y;  // [px]
  Rgba c;
  float da = 1e4f, db = 1e4f;  // [px] distances from the two antialiased edges (1e4: none)
};
struct GlyphVertex {
  float x, y;  // [px]
  float u, v;  // atlas coordinates in [0, 1]
  Rgba c;
};

// the band along the inner edge of a slipping element: magenta, a colour neither colour map
// (colormap.cpp: viridis, cool-warm) comes near
inline constexpr Rgba kSlipColour{0.90f, 0.00f, 0.90f, 1};

// what one element looks like in the frame (kept for tests and for the reader of the code)
struct ElementDraw {
  Vec2 centre;      // [px] where its centre is drawn
  Vec2 corners[4];  // [px] inner and outer corners: inner-A, inner-B, outer-B, outer-A, where A is
                    // the joint with the predecessor and B with the successor
  double value = 0; // the quantity (NaN off the pulleys for contact quantities)
  int band = -1;    // colour band, -1 for NaN
  Rgba colour;
  bool wet = false, slipping = false;
};

struct DrawList {
  int width = 0, height = 0;
  Rgba background{1, 1, 1, 1};
  std::vector<SolidVertex> triangles;  // three vertices per triangle, drawn in order
  std::vector<GlyphVertex> glyphs;     // drawn after the triangles
  Font* font = nullptr;                // owner of the glyph atlas
  std::vector<ElementDraw> elements;
  std::vector<std::string> texts;      // every string drawn, in order (for tests)
  struct TextBox {
    std::string text;
    Vec2 lo, hi;  // [px] the box's top-left and bottom-right corners
  };
  std::vector<TextBox> boxes;          // every boxed text with its box, in order (for tests)
  // [px] where each piece of text drawn lies, in order: a boxed text's box, a plain text's extent
  // (its width, the font's ascent over the baseline and descent under it), rounded outward to
  // whole pixels and grown by 1 px for the antialiasing; not clipped to the frame. The renderer
  // hands them on with the picture (Image::text_boxes).
  std::vector<PixelRect> text_rects;
  std::vector<std::pair<Vec2, Vec2>> travel;  // tail and tip [px] of the direction-of-travel arrows (for tests)
  std::vector<std::string> left_out;          // the legend's lines left out for want of room
  ColourScale scale;

  void triangle(Vec2 a, Vec2 b, Vec2 c, Rgba col);
  // a-b-c-d in order round the quad, edges not antialiased (for pixel-aligned boxes)
  void quad(Vec2 a, Vec2 b, Vec2 c, Vec2 d, Rgba col);
  // a strip piece with antialiased long sides: inner edge a_in-b_in, outer edge b_out-a_out;
  // the ends (a_in-a_out, b_in-b_out) are left sharp, to be shared with the neighbours
  void band(Vec2 a_in, Vec2 b_in, Vec2 b_out, Vec2 a_out, Rgba col);
  void line(Vec2 a, Vec2 b, double width_px, Rgba col);  // antialiased along its sides
  void disc(Vec2 centre, double radius_px, Rgba col, int segments = 96);
  void ring(Vec2 centre, double r_in_px, double r_out_px, Rgba col, int segments = 96);
  enum Align { left, centre, right };
  // text with its baseline at y; returns the width [px]
  float text(Vec2 at, const std::string& utf8, int px, Rgba col, Align align = left);
  // text on a box of colour `box` a few pixels larger than it (readable over the belt): the box
  // reaches `above` over the baseline, `below` under it and `pad` beyond the text's ends [px]
  struct BoxMargins {
    double pad, above, below;
  };
  static BoxMargins box_margins(int px) { return {std::max(2.0, 0.2 * px), 0.95 * px, 0.35 * px}; }
  float boxed_text(Vec2 at, const std::string& utf8, int px, Rgba col, Rgba box, Align align = left);
  // an arrow from tail to tip, its head `head_px` long
  void arrow(Vec2 tail, Vec2 tip, double width_px, double head_px, Rgba col);
};

// world [m] to pixels
struct Camera {
  Vec2 centre{0, 0};     // [m] at the centre of the drawing area
  double scale = 1000;   // [px/m]
  Vec2 area_centre{0, 0};  // [px]
  Vec2 to_px(const Vec2& w) const { return {area_centre.x() + scale * (w.x() - centre.x()), area_centre.y() - scale * (w.y() - centre.y())}; }
};

// The default colour-bar range of a quantity for a scene (ends rounded up to 1, 1.2, 1.6, 2,
// 2.5, 3, 4, 5, 6 or 8 × 10^k): tension 0..2·static tension; normal force 0..4·N0, N0 = T0·pitch/r the static normal
// force of an element on the largest pulley; friction ±2·N0; slip ±0.05 m/s; μ 0..largest μ.
void default_range(const Scene& scene, FrameQuantity q, double& lo, double& hi);

// The quantity per element at a state (NaN where undefined, e.g. slip off the pulleys); drive:
// the drive as it is now (events may have changed μ or a law), null for the scene's own.
std::vector<double> element_values(const Scene& scene, FrameQuantity q, double t, const double* y,
                                   const Drive* drive = nullptr);

// "" when the frames of these settings show all their text (FrameBuilder::cut_text, at the state y
// at t: the scene's initial state at the first frame's time when y is null), else "WxH is too small
// for the frame's text with every line of its legend (what it cuts): W'xH' is the smallest of its
// shape that shows it all; the frames are drawn as they are". Throws std::runtime_error as Font
// does.
std::string frame_size_problem(const Scene& scene, const FrameSettings& settings, double t = 0,
                               const double* y = nullptr);

class FrameBuilder {
 public:
  // settings are validated by the caller (sim/frames.hpp validate)
  FrameBuilder(const Scene& scene, const FrameSettings& settings, Font* font);
  // the draw list of the state y at time t (replaces the contents of `out`); drive: the drive as
  // it is now (run events may change μ or a law while running), null for the scene's own
  // obs: what is observed at t (contact forces from the integrator's step ends), null to observe y;
  // values: each element's colour value when the settings give their own (FrameSettings::given)
  void build(double t, const double* y, DrawList& out, const Drive* drive = nullptr, const Observation* obs = nullptr,
             const std::vector<double>* values = nullptr) const;
  // the title before the time in the text band (FrameSettings::caption), for the next builds
  void set_caption(std::string caption) { fs_.caption = std::move(caption); }
  // each pulley's line of the text band (FrameSettings::pulley_lines), for the next builds
  void set_pulley_lines(std::vector<std::string> lines) { fs_.pulley_lines = std::move(lines); }
  const Camera& camera() const { return cam_; }
  const ColourScale& scale() const { return scale_; }
  // what of its text the frame of the state y at t cannot show ("" when it shows it all), with every
  // line its legend can have (the wet one too): a line running off an edge (the pulleys' lines as
  // long as they can be), the legend's lines left out
  std::string cut_text(double t, const double* y) const;
  // the nominal path of the state y: the scene's route with each pulley where it is in y (a
  // pulley on a tensioner arm moves with it; the scene's own route when the drive has no arm)
  Route nominal(const double* y) const;
  // world position at which an element centre p is drawn (the nearest point of the nominal path
  // plus magnify times the deviation from it); tangent (if not null) receives the nominal path's
  // direction of travel there
  Vec2 displayed(const Route& nominal, const Vec2& p, Vec2* tangent = nullptr) const;

 private:
  const Scene& sc_;
  FrameSettings fs_;
  Font* font_;
  Camera cam_;
  ColourScale scale_;
  double thickness_ = 0;        // [m] drawn belt thickness
  double mu_dry_ = 0;           // the largest μ of the belt as the scene built it: elements below it are wet
  std::vector<int> sense_;      // per pulley: +1 the belt wraps it anticlockwise, -1 clockwise
  std::vector<double> sink_;    // per route arc: static penetration of its pulley [m]
  int font_px_ = 14;
  int columns_ = 1;             // pulley lines per row of the text band
  // each pulley's line in the text band: its x [px] and its row (0: the first under the time line)
  std::vector<std::pair<double, int>> line_at_;
  bool band_wide_ = false;      // the text band runs over the panel's width too (above the bar)
  double top_ = 0, panel_ = 0;  // [px] height of the text band, width of the colour-bar panel
  double lines_right_ = 0;      // [px] the right end of the longest the pulleys' lines can be
  // where each pulley's name goes, from its centre [px] (chosen once, so it stays put frame to
  // frame): on the disc or beside it; none when it has no place in view
  struct NamePlace {
    bool shown = false, on_disc = false;
    Vec2 offset{0, 0};
    DrawList::Align align = DrawList::centre;
  };
  std::vector<NamePlace> names_;
  void place_names();
  std::string pulley_text(int j, const PulleyObs& o) const;
  // a pixel inside the drawing area (below the text band, left of the colour-bar panel)
  bool in_view(const Vec2& p_px) const;
  // build's stages: spray zones; tensioner arms and pulleys with their names; the text band, colour
  // bar and legend (arrows: whether the belt got direction-of-travel arrows, arrow_w their width [px])
  void draw_spray_zones(const Drive& dr, DrawList& out) const;
  void draw_pulleys(const double* q, DrawList& out) const;
  void draw_text_and_legend(double t, const Observation& seen, bool arrows, double arrow_w, DrawList& out) const;
};

}  // namespace beltsim::render
