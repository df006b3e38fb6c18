// FrameBuilder's text band and legend (declared in draw_list.hpp): the time, the colour
// quantity and each pulley's line above the drive, the colour bar and the marks' legend beside it,
// and what of them a frame size cannot show (cut_text).
#include <algorithm>
#include <cmath>
#include <string>

#include "render/draw_list.hpp"
#include "render/frame_style.hpp"
#include "render/text.hpp"
#include "scene/scene.hpp"

namespace beltsim::render {

using namespace frame;

void FrameBuilder::draw_text_and_legend(double t, const Observation& seen, bool arrows, double arrow_w,
                                        DrawList& out) const {
  const Model& m = sc_.model;
  const double area_right = fs_.width - panel_;
  // text band: time, colour quantity, magnification; each pulley's speed and slip
  // what the colour is: the quantity's name and unit, or those the settings give
  const FrameQuantityInfo& qi = frame_quantity_info(fs_.quantity);
  const std::string label = fs_.given ? fs_.given->label : qi.label, unit = fs_.given ? fs_.given->unit : qi.unit;
  const double line = 1.4 * font_px_;
  const double x0 = 0.6 * font_px_;
  Rgba paper = out.background;  // the boxes under the text
  paper.a = 0.85f;
  // the time to 4 decimals, or as many more as tell consecutive frames apart (fps = 30 with
  // slowdown = 1000, frames 3.3e-5 s apart, read 0.3000, 0.3000, 0.3001 at 4)
  const int decimals = std::max(4, static_cast<int>(std::ceil(-std::log10(fs_.frame_dt()) - 1e-9)));
  std::string head = (fs_.caption.empty() ? "" : fs_.caption + "      ") +
                     "t = " + format(("%." + std::to_string(decimals) + "f").c_str(), t) + " s      colour: " + label +
                     (unit.empty() ? "" : " [" + unit + "]");
  if (fs_.magnify != 1) head += "      deformation \u00d7" + format("%g", fs_.magnify);
  out.boxed_text(Vec2(x0, line), head, font_px_, kInk, paper);
  for (int j = 0; j < m.n_p(); ++j)
    out.boxed_text(
        Vec2(line_at_[j].first, line * (2 + line_at_[j].second)),
        static_cast<size_t>(j) < fs_.pulley_lines.size() ? fs_.pulley_lines[j] : pulley_text(j, seen.pulleys[j]),
        font_px_, kInk, paper);

  // colour bar: bands from lo (bottom) to hi (top), edges labelled where they fit, on the
  // background's colour (in a zoomed view the drawing reaches under the panel)
  const double panel_top = band_wide_ ? top_ : 0;  // (under a wide text band, from its bottom)
  out.quad(Vec2(area_right, panel_top), Vec2(fs_.width, panel_top), Vec2(fs_.width, fs_.height),
           Vec2(area_right, fs_.height), out.background);
  const double panel_x = fs_.width - panel_ + 0.5 * font_px_;
  const double bar_w = std::max(8.0, 0.022 * fs_.width);
  const double bar_top = top_ + 2.2 * line;
  // the legend's lines below the bar (at most five): the bar leaves room for five where it is four
  // lines long or more, the same in every frame of a run whatever its legend holds. A smaller frame
  // gets a shorter bar (two lines at least) and, where its legend still does not fit, loses the
  // lines a reader needs least first: the sign's, the travel arrow's (the arrows on the spans show
  // it), the grey of the free spans (a 320x180 frame's legend ran off its bottom)
  bool any_wet = false;
  for (const ElementDraw& el : out.elements) any_wet = any_wet || el.wet;
  // (a scene with spray zones has a sixth line for them, in every frame)
  const bool spray_line = !sc_.drive.spray.zones.empty();
  const std::string sign_text = fs_.given ? fs_.given->plus : "+ : along travel";
  bool sign_line = fs_.given || qi.is_signed, arrow_line = arrows,
       off_swatch = !fs_.given && fs_.quantity != FrameQuantity::tension && fs_.quantity != FrameQuantity::mu;
  auto legend_lines = [&] { return sign_line + any_wet + 1 + spray_line + arrow_line + off_swatch; };
  double bar_bot = fs_.height - (6.2 + spray_line) * line;
  if (bar_bot < bar_top + 4.0 * line) {
    const int room = static_cast<int>(std::floor((fs_.height - bar_top) / line - 3.2));
    for (const auto& [drop, what] :
         {std::pair{&sign_line, sign_text}, std::pair{&arrow_line, std::string("belt travel")},
          std::pair{&off_swatch, std::string("off the pulleys")}})
      if (legend_lines() > room && *drop) *drop = false, out.left_out.push_back(what);
    bar_bot = std::max(fs_.height - (legend_lines() + 1.2) * line, bar_top + 2.0 * line);
  }
  out.boxed_text(Vec2(panel_x, bar_top - 1.6 * line), label, font_px_, kInk, paper);
  out.boxed_text(Vec2(panel_x, bar_top - 0.6 * line), unit.empty() ? "[\u2013]" : "[" + unit + "]", font_px_, kInk,
                 paper);
  const int bands = scale_.levels > 0 ? scale_.levels : 64;
  const double bh = (bar_bot - bar_top) / bands;
  for (int k = 0; k < bands; ++k) {
    const double y1 = bar_bot - k * bh, y0 = y1 - bh;
    const Rgba col = colour_at(scale_.map, (k + 0.5) / bands);
    out.quad(Vec2(panel_x, y0), Vec2(panel_x + bar_w, y0), Vec2(panel_x + bar_w, y1), Vec2(panel_x, y1), col);
  }
  // values beyond the bar's ends (their elements drawn in its end colours): a triangle of that
  // colour at that end, pointing away, in the gap to the text above or below
  double v_lo = INFINITY, v_hi = -INFINITY;
  for (const ElementDraw& el : out.elements)
    if (std::isfinite(el.value)) v_lo = std::min(v_lo, el.value), v_hi = std::max(v_hi, el.value);
  const double tip = 0.45 * font_px_;
  if (v_hi > scale_.hi)
    out.triangle(Vec2(panel_x, bar_top), Vec2(panel_x + bar_w, bar_top), Vec2(panel_x + 0.5 * bar_w, bar_top - tip),
                 scale_.colour(v_hi));
  if (v_lo < scale_.lo)
    out.triangle(Vec2(panel_x, bar_bot), Vec2(panel_x + 0.5 * bar_w, bar_bot + tip), Vec2(panel_x + bar_w, bar_bot),
                 scale_.colour(v_lo));
  const int edges = scale_.levels > 0 ? scale_.levels : 4;
  int every = 1;
  while (every < edges && (bar_bot - bar_top) / edges * every < 1.3 * font_px_) every *= 2;
  // labelled: both ends and a zero edge always (a short bar read 0.030 / -0.010 / -0.050 for
  // -0.05..0.05: no top, no zero), then every `every`-th edge clear of those by `every`
  std::vector<int> labelled{0, edges};
  const double zero = -scale_.lo / (scale_.hi - scale_.lo) * edges;
  if (scale_.lo < 0 && scale_.hi > 0 && std::abs(zero - std::round(zero)) < 1e-9) {
    const int kz = static_cast<int>(std::round(zero));
    if (kz >= every && edges - kz >= every) labelled.push_back(kz);
  }
  for (int k = every; k < edges; k += every) {
    bool clear = true;
    for (int c : labelled) clear = clear && std::abs(k - c) >= every;
    if (clear) labelled.push_back(k);
  }
  for (int k : labelled) {
    const double val = scale_.lo + (scale_.hi - scale_.lo) * k / edges;
    const double yk = bar_bot - (bar_bot - bar_top) * k / edges;
    out.line(Vec2(panel_x + bar_w, yk), Vec2(panel_x + bar_w + 0.4 * font_px_, yk), 1.2, kInk);
    out.boxed_text(Vec2(panel_x + bar_w + 0.6 * font_px_, yk + 0.35 * font_px_), tick(val, scale_.hi - scale_.lo),
                   font_px_, kInk, paper);
  }
  // legend
  double ly = bar_bot + 1.3 * line;
  auto swatch = [&](Rgba col, const std::string& what) {
    out.quad(Vec2(panel_x, ly - 0.7 * font_px_), Vec2(panel_x + bar_w, ly - 0.7 * font_px_), Vec2(panel_x + bar_w, ly),
             Vec2(panel_x, ly), col);
    out.boxed_text(Vec2(panel_x + bar_w + 0.5 * font_px_, ly), what, font_px_, kInk, paper);
    ly += line;
  };
  if (sign_line) out.boxed_text(Vec2(panel_x, ly), sign_text, font_px_, kInk, paper), ly += line;
  swatch(kSlip, "slipping");
  if (spray_line) {  // a disc as the zones are drawn: filled while it sprays, its outline while not
    const double r = std::min(0.22 * bar_w, 0.4 * font_px_);
    const Vec2 on(panel_x + 0.25 * bar_w, ly - 0.35 * font_px_), off(panel_x + 0.75 * bar_w, ly - 0.35 * font_px_);
    out.disc(on, r, kSprayFill, 24);
    out.ring(on, std::max(r - 1.2, 0.0), r, kWet, 24);
    out.ring(off, std::max(r - 1.2, 0.0), r, kWet, 24);
    out.boxed_text(Vec2(panel_x + bar_w + 0.5 * font_px_, ly), "spray: on, off", font_px_, kInk, paper);
    ly += line;
  }
  if (arrow_line) {
    out.arrow(Vec2(panel_x, ly - 0.35 * font_px_), Vec2(panel_x + bar_w, ly - 0.35 * font_px_), arrow_w,
              std::min(0.8 * font_px_, 0.6 * bar_w), kInk);
    out.boxed_text(Vec2(panel_x + bar_w + 0.5 * font_px_, ly), "belt travel", font_px_, kInk, paper);
    ly += line;
  }
  if (off_swatch) swatch(scale_.none, "off the pulleys");
  // the wet line last: it comes when the belt first gets wet, and above the others it moved each of
  // them down a line in that frame (a user's trial: the legend jumped in a video at the very event
  // it showed)
  if (any_wet) {  // dashed, as on the belt
    for (int k = 0; k < 3; ++k) {
      const double d0 = panel_x + bar_w * k / 3.0, d1 = d0 + 0.6 * bar_w / 3.0;
      out.quad(Vec2(d0, ly - 0.5 * font_px_), Vec2(d1, ly - 0.5 * font_px_), Vec2(d1, ly - 0.2 * font_px_),
               Vec2(d0, ly - 0.2 * font_px_), kWet);
    }
    out.boxed_text(Vec2(panel_x + bar_w + 0.5 * font_px_, ly), "wet (\u03bc < " + format("%.3g", mu_dry_) + ")",
                   font_px_, kInk, paper);
    ly += line;
  }
}

// "driver: ω = −57.05 rad/s, slip_pitch −0.021 m/s": the pulley's speed and its slip_pitch (the
// belt on its wrap minus the rim's pitch line, model/observables.hpp: the gross-slip arc's slip,
// without the radial part that slip_speed adds), named as the CSV and sim:pulley name it (a user's
// trial read "slip" against sim:pulley's slip_speed), ", off the belt" while no element touches it; on
// a tensioner arm ", arm 2.572 rad" (the arm's angle, as the CSV's arm_angle), with a coupled rotor
// ", rotor −185.11 rad/s" (its speed, as rotor_speed)
std::string FrameBuilder::pulley_text(int j, const PulleyObs& o) const {
  const Pulley& p = sc_.model.pulleys[j];
  std::string text = p.name + ": \u03c9 = " + format("%.2f", o.omega) + " rad/s" +
                     (std::isnan(o.slip_pitch) ? ", off the belt" : ", slip_pitch " + format("%+.3f", o.slip_pitch) + " m/s");
  if (p.arm >= 0) text += ", arm " + format("%.3f", o.arm_angle) + " rad";
  if (p.coupling >= 0) text += ", rotor " + format("%.2f", o.rotor_speed) + " rad/s";
  return text;
}

std::string FrameBuilder::cut_text(double t, const double* y) const {
  // with every line the legend can have: an element wet (a dry start's legend gets the wet line
  // when an event or a spray zone wets the belt)
  Drive wet = sc_.drive;
  if (!wet.mu.empty()) wet.mu[0] = 0.5 * mu_dry_;
  DrawList dl;
  build(t, y, dl, &wet);
  std::string cut;
  if (lines_right_ > fs_.width) cut = "the pulleys' lines run off its right edge";
  for (const DrawList::TextBox& b : dl.boxes)
    if (cut.empty() && (b.lo.x() < 0 || b.hi.x() > fs_.width || b.lo.y() < 0 || b.hi.y() > fs_.height))
      cut = "'" + b.text + "' runs off its " +
            (b.hi.x() > fs_.width    ? "right edge"
             : b.hi.y() > fs_.height ? "bottom"
                                     : "left or top edge");
  if (!dl.left_out.empty()) {
    std::string lines;
    for (const std::string& l : dl.left_out) lines += (lines.empty() ? "'" : ", '") + l + "'";
    cut += (cut.empty() ? "" : "; ") + std::string("its legend leaves out ") + lines;
  }
  return cut;
}

}  // namespace beltsim::render
