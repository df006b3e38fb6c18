// FrameBuilder: what a frame shows (draw_list.hpp's list) from the Scene and a state: the
// quantities and their colour range, the camera, the pulleys, the belt and its marks; the text band
// and the legend are frame_text.cpp's.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "model/block_matrix.hpp"
#include "model/forces.hpp"
#include "model/observables.hpp"
#include "render/draw_list.hpp"
#include "render/frame_style.hpp"
#include "render/text.hpp"
#include "scene/route.hpp"
#include "scene/scene.hpp"

namespace beltsim::render {

using namespace frame;  // the frame's colours and number formats (frame_style.hpp)

// ---- quantities -------------------------------------------------------------------------------

namespace {
// the smallest of 1, 1.2, 1.6, 2, 2.5, 3, 4, 5, 6, 8 × 10^k that is >= 0.97·x (round colour-bar
// ends whose quarters, the bar's ticks, are round too; steps of at most 1.33 leave at least 3/4 of
// the bar to the values: 1, 2, 2.5, 5 put a 300 N pretension's 600 N at 1000 N)
double nice_up(double x) {
  const double p = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {1.0, 1.2, 1.6, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0})
    if (m * p >= 0.97 * x) return m * p;  // 3 % slack: 2·500.4 N still ends at 1000
  return 10 * p;
}
}  // namespace

void default_range(const Scene& sc, FrameQuantity q, double& lo, double& hi) {
  const Model& m = sc.model;
  double r_max = 0;
  for (const Pulley& p : m.pulleys) r_max = std::max(r_max, p.radius);
  const double T0 = sc.static_tension > 0 ? sc.static_tension : 1.0;
  const double N0 = T0 * m.belt.pitch / r_max;  // static normal force of an element on the largest pulley
  double mu_max = 0;
  for (double mu : sc.drive.mu) mu_max = std::max(mu_max, mu);
  switch (q) {
    case FrameQuantity::tension:
      lo = 0, hi = nice_up(2 * T0);
      break;
    case FrameQuantity::normal:
      lo = 0, hi = nice_up(4 * N0);
      break;
    case FrameQuantity::friction:
      lo = -nice_up(2 * N0), hi = nice_up(2 * N0);
      break;
    case FrameQuantity::slip:
      lo = -0.05, hi = 0.05;
      break;
    case FrameQuantity::mu:
      lo = 0, hi = mu_max > 0 ? nice_up(mu_max) : 1;  // (a flank's 1.0233 read 0.10, 0.20, 0.31 ...)
      break;
  }
}

namespace {
// the frame's quantity of one element (NaN where undefined: contact quantities off the pulleys)
double quantity_of(const ElementObs& o, FrameQuantity q) {
  switch (q) {
    case FrameQuantity::tension:
      return o.tension;
    case FrameQuantity::mu:
      return o.mu;
    case FrameQuantity::normal:
      return o.state == ContactState::free ? kNaN : o.normal;
    case FrameQuantity::friction:
      return o.friction;
    case FrameQuantity::slip:
      return o.slip;
  }
  return kNaN;
}
}  // namespace

std::vector<double> element_values(const Scene& sc, FrameQuantity q, double t, const double* y, const Drive* drive) {
  const Model& m = sc.model;
  const Drive& d = drive ? *drive : sc.drive;
  const std::vector<int> sense = sc.senses();
  Observation o;
  observe(m, d, sense, t, y, o);
  std::vector<double> out(m.n_el(), kNaN);
  for (int i = 0; i < m.n_el(); ++i) out[i] = quantity_of(o.elements[i], q);
  return out;
}

// ---- the frame --------------------------------------------------------------------------------

FrameBuilder::FrameBuilder(const Scene& sc, const FrameSettings& fs, Font* font) : sc_(sc), fs_(fs), font_(font) {
  const Model& m = sc.model;
  sense_ = sc.senses();
  for (size_t k = 0; k < sc.route_pulleys.size(); ++k) sink_.push_back(sc.penetration[sc.route_pulleys[k]]);
  for (double mu : sc.drive.mu) mu_dry_ = std::max(mu_dry_, mu);

  double lo, hi;
  default_range(sc, fs.quantity, lo, hi);
  if (fs.range_lo) lo = *fs.range_lo;
  if (fs.range_hi) hi = *fs.range_hi;
  if (!(lo < hi)) hi = lo + 1;
  scale_.map = fs.given || frame_quantity_info(fs.quantity).is_signed ? ColourMap::diverging : ColourMap::viridis;
  scale_.lo = lo, scale_.hi = hi, scale_.levels = fs.levels;

  // layout: a text band at the top (the time line, then the pulleys' lines in as many columns
  // as fit), the colour-bar panel at the right, the drive in the rest
  // the font from the height, or from three quarters of the width where that is less: a portrait
  // frame's lines ran off its right edge at a font taken from its height alone
  font_px_ = std::max(10, static_cast<int>(std::lround(std::min<double>(fs.height, 0.75 * fs.width) / 40.0)));
  const double line = 1.4 * font_px_;
  panel_ = std::max(0.17 * fs.width, 11.0 * font_px_);
  double widest = 0;
  std::vector<double> widths, longest_px;  // (with and without the gap to the next column)
  for (const Pulley& p : m.pulleys) {
    std::string longest = p.name + ": \u03c9 = \u2212000.00 rad/s, slip_pitch \u2212000.000 m/s";  // (pulley_text's)
    if (p.arm >= 0) longest += ", arm \u22120.000 rad";
    if (p.coupling >= 0) longest += ", rotor \u2212000.00 rad/s";
    longest_px.push_back(font_ ? font_->width(longest, font_px_) : 0.0);
    longest += "   ";
    widths.push_back(font_ ? static_cast<double>(font_->width(longest, font_px_))
                           : (33.0 + (p.arm >= 0) * 8 + (p.coupling >= 0) * 10) * font_px_);
    widest = std::max(widest, widths.back());
  }
  const int np = m.n_p();
  const double x0 = 0.6 * font_px_;
  columns_ = std::max(1, static_cast<int>((fs.width - panel_) / widest));
  line_at_.clear();
  for (int j = 0; j < np; ++j) line_at_.push_back({x0 + (j % columns_) * (fs.width - panel_) / columns_, j / columns_});
  // three pulleys or more in one column (a decoupled alternator's rotor or an arm lengthens a
  // line): two columns across the whole width, above the bar, where they fit, the first half of
  // the pulleys in the first (six lines took a quarter of a serpentine drive's frame from it)
  if (columns_ == 1 && np > 2) {
    const int rows = (np + 1) / 2;
    double first = 0, second = 0;
    for (int j = 0; j < np; ++j) (j < rows ? first : second) = std::max(j < rows ? first : second, widths[j]);
    if (x0 + first + second <= fs.width) {
      columns_ = 2, band_wide_ = true;
      for (int j = 0; j < np; ++j) line_at_[j] = {j < rows ? x0 : x0 + first, j < rows ? j : j - rows};
    }
  }
  int rows = 0;
  for (const auto& [x, row] : line_at_) rows = std::max(rows, row + 1);
  for (int j = 0; j < np; ++j) lines_right_ = std::max(lines_right_, line_at_[j].first + longest_px[j]);
  top_ = (1.5 + rows) * line;
  const Vec2 area0(0, top_), area1(fs.width - panel_, fs.height);
  cam_.area_centre = 0.5 * (area0 + area1);
  Vec2 lo_w(1e300, 1e300), hi_w(-1e300, -1e300);
  for (const Pulley& p : m.pulleys) {
    lo_w = lo_w.cwiseMin(p.centre - Vec2(p.radius, p.radius));
    hi_w = hi_w.cwiseMax(p.centre + Vec2(p.radius, p.radius));
  }
  for (const Arm& a : m.arms) lo_w = lo_w.cwiseMin(a.pivot), hi_w = hi_w.cwiseMax(a.pivot);  // (drawn)
  const Vec2 size = hi_w - lo_w;
  const double fit = 0.88 * std::min((area1.x() - area0.x()) / size.x(), (area1.y() - area0.y()) / size.y());
  cam_.centre = fs.view_centre ? *fs.view_centre : Vec2(0.5 * (lo_w + hi_w));
  cam_.scale = fs.view_width ? (area1.x() - area0.x()) / *fs.view_width : fit;
  // a 5PK belt is about 4.5 mm thick; at least 5 px so small frames still show it
  thickness_ = std::max(4.5e-3, 5.0 / cam_.scale);
  place_names();
}

Route FrameBuilder::nominal(const double* y) const {
  const Model& m = sc_.model;
  if (m.arms.empty()) return sc_.route;
  // the route's circles at the pulleys' centres in y; the senses and the loop's as the scene's
  std::vector<RouteCircle> circles;
  int loop_sense = -1;
  for (size_t k = 0; k < sc_.route.arcs.size(); ++k) {
    const Route::Arc& a = sc_.route.arcs[k];
    const int j = sc_.route_pulleys[k];
    circles.push_back({m.centre(j, y), a.radius, a.sense});
    if (m.pulleys[j].wrap == WrapSide::inside) loop_sense = a.sense;
  }
  try {
    return make_route(circles, loop_sense, sc_.route_names);
  } catch (const std::exception&) {
    return sc_.route;  // an arm swung where the belt has no route: drawn against the scene's
  }
}

Vec2 FrameBuilder::displayed(const Route& r, const Vec2& p, Vec2* tangent) const {
  if (fs_.magnify == 1 && !tangent) return p;
  // nearest point of the nominal path: each span's segment, each arc's circle sunk by the
  // pulley's static penetration (the belt at rest sits there)
  double best = 1e300;
  Vec2 nominal = p, tan(1, 0);
  for (const Route::Span& s : r.spans) {
    const Vec2 d = s.to - s.from;
    const double u = std::clamp((p - s.from).dot(d) / d.squaredNorm(), 0.0, 1.0);
    const Vec2 c = s.from + u * d;
    if (const double dist = (p - c).squaredNorm(); dist < best) best = dist, nominal = c, tan = d.normalized();
  }
  for (size_t k = 0; k < r.arcs.size(); ++k) {
    const Route::Arc& a = r.arcs[k];
    const Vec2 rel = p - a.centre;
    // is the point's angle within the arc (from start_angle, `angle` radians in the arc's sense)?
    double da = a.sense * (std::atan2(rel.y(), rel.x()) - a.start_angle);
    da = std::fmod(da, 2 * M_PI);
    if (da < 0) da += 2 * M_PI;
    if (da > a.angle) continue;
    const Vec2 c = a.centre + (a.radius - sink_[k]) * rel.normalized();
    if (const double dist = (p - c).squaredNorm(); dist < best)
      best = dist, nominal = c, tan = a.sense * perp(rel.normalized());
  }
  if (tangent) *tangent = tan;
  return nominal + fs_.magnify * (p - nominal);
}

// spray zones under the belt: a translucent disc of the wet colour while it sprays, the outline
// while it does not
void FrameBuilder::draw_spray_zones(const Drive& dr, DrawList& out) const {
  for (const SprayZone& z : dr.spray.zones) {
    const Vec2 c = cam_.to_px(z.centre);
    const double r = z.radius * cam_.scale;
    if (z.on) out.disc(c, r, kSprayFill, 64);
    out.ring(c, std::max(r - 1.5, 0.0), r, kWet, 64);
  }
}

void FrameBuilder::build(double t, const double* y, DrawList& out, const Drive* drive, const Observation* given,
                         const std::vector<double>* values) const {
  const Model& m = sc_.model;
  const Drive& dr = drive ? *drive : sc_.drive;
  const int n = m.n_el();
  const double* q = y;
  out.width = fs_.width, out.height = fs_.height;
  out.triangles.clear(), out.glyphs.clear(), out.elements.clear(), out.texts.clear(), out.boxes.clear(),
      out.text_rects.clear(), out.travel.clear(), out.left_out.clear();
  out.font = font_;
  out.scale = scale_;
  const double px = 1.0 / cam_.scale;  // one pixel in metres
  const double h = 0.5 * thickness_;   // [m] half the drawn belt's thickness
  auto P = [&](const Vec2& w) { return cam_.to_px(w); };

  draw_pulleys(q, out);
  draw_spray_zones(dr, out);

  // belt elements
  Observation own;
  if (!given) observe(m, dr, sense_, t, y, own);
  const Observation& seen = given ? *given : own;
  const std::vector<ElementObs>& obs = seen.elements;
  int loop_sense = -1;
  for (int j = 0; j < m.n_p(); ++j)
    if (m.pulleys[j].wrap == WrapSide::inside) loop_sense = sense_[j];
  const double band_w = std::max(0.4 * thickness_, 2.5 * px);
  // The belt as a band through the displayed element centres: element i runs from the joint
  // with its predecessor (the mid-point of the two centres, where their SDE is) to the joint with
  // its successor, so neighbours meet whatever the magnification (rigid elements on an arc are
  // chords whose ends stand off the arc by l²/8r: magnifying their ends would show that, not
  // deformation).
  std::vector<Vec2> Cd(n), J(n), O(n);
  const Route path = fs_.magnify == 1 ? Route{} : nominal(q);
  for (int i = 0; i < n; ++i) Cd[i] = displayed(path, Vec2(q[3 * i], q[3 * i + 1]));
  for (int i = 0; i < n; ++i) {
    const Vec2& prev = Cd[before(i, n)];
    J[i] = 0.5 * (prev + Cd[i]);
    const Vec2 d = (Cd[i] - prev).normalized();
    O[i] = -loop_sense * perp(d);  // outer (back) side: left of the travel for a clockwise loop
  }
  for (int i = 0; i < n; ++i) {
    const int k = after(i, n);
    const Vec2 A = J[i], B = J[k];
    const Vec2 oa = O[i], ob = O[k];
    const Vec2 d = (B - A).normalized();
    const double len = (B - A).norm();
    ElementDraw el;
    el.value = fs_.given && values ? (*values)[i] : quantity_of(obs[i], fs_.quantity);
    el.band = scale_.band(el.value);
    el.colour = scale_.colour(el.value);
    // the μ it has now (a spray zone's water included) below the belt's as the scene built it: a
    // stretch an event raises above that (contamination that grips harder) is not wet, and does not
    // make the rest of the belt wet
    el.wet = obs[i].mu < mu_dry_;
    el.slipping = obs[i].state == ContactState::slip;
    el.centre = P(Cd[i]);
    el.corners[0] = P(A - h * oa), el.corners[1] = P(B - h * ob), el.corners[2] = P(B + h * ob),
    el.corners[3] = P(A + h * oa);
    // dark edge, then the colour inset by a pixel so the elements read one by one; elements shorter
    // than kJointsShown pixels are not told apart: their colours meet end to end (a dark joint every
    // pixel or two drew a moiré of dashes over a 2 400-element belt, hiding its colours)
    out.band(el.corners[0], el.corners[1], el.corners[2], el.corners[3], kEdge);
    const double in = std::min(0.9 * px, 0.2 * h),
                 along = len >= kJointsShown * px ? std::min(0.6 * px, 0.2 * len) : 0.0;
    out.band(P(A + along * d - (h - in) * oa), P(B - along * d - (h - in) * ob), P(B - along * d + (h - in) * ob),
             P(A + along * d + (h - in) * oa), el.colour);
    // a wet element: two dashes along its back, a broken line no colour map's fill is (the slip
    // map's blue beside a solid blue band read alike)
    // (shorter elements: one dash over `run` elements, then a gap of as many, `run` elements kJointsShown pixels
    // long, the dashes travelling with the belt)
    const int run = len >= kJointsShown * px ? 1 : static_cast<int>(std::ceil(kJointsShown * px / std::max(len, 1e-3 * px)));
    if (el.wet && run == 1)
      for (const auto& [s0, s1] : {std::pair{0.08, 0.42}, std::pair{0.58, 0.92}}) {
        const Vec2 a = A + s0 * (B - A), b = A + s1 * (B - A);
        const Vec2 oa0 = (oa + s0 * (ob - oa)).normalized(), ob0 = (oa + s1 * (ob - oa)).normalized();
        out.band(P(a + (h + 0.3 * px) * oa0), P(b + (h + 0.3 * px) * ob0), P(b + (h + band_w) * ob0),
                 P(a + (h + band_w) * oa0), kWet);
      }
    if (el.wet && run > 1 && (i / run) % 2 == 0)
      out.band(P(A + (h + 0.3 * px) * oa), P(B + (h + 0.3 * px) * ob), P(B + (h + band_w) * ob), P(A + (h + band_w) * oa),
               kWet);
    if (el.slipping)
      out.band(P(A - (h + band_w) * oa), P(B - (h + band_w) * ob), P(B - (h + 0.3 * px) * ob),
               P(A - (h + 0.3 * px) * oa), kSlip);
    out.elements.push_back(el);
  }

  // the direction of travel: an arrow beside the belt's outer side at the middle of each span
  // whose middle is in view, else beside the visible element nearest the view's centre
  const double arrow_len = 2.5 * font_px_, arrow_w = std::max(2.0, 0.16 * font_px_);
  const double gap = h + band_w + 0.6 * font_px_ * px;  // [m] from the belt's centre line
  // whether the arrow from tail to tip, with its head's half width, runs into a text box drawn so
  // far (the pulleys' names) or a spray zone's disc (one on a span's middle held its arrow)
  const double head_half = 0.4 * font_px_;
  auto over_text = [&](const Vec2& tail, const Vec2& tip) {
    const Vec2 lo = tail.cwiseMin(tip) - Vec2::Constant(head_half), hi = tail.cwiseMax(tip) + Vec2::Constant(head_half);
    for (const DrawList::TextBox& b : out.boxes)
      if (lo.x() < b.hi.x() && hi.x() > b.lo.x() && lo.y() < b.hi.y() && hi.y() > b.lo.y()) return true;
    for (const SprayZone& z : dr.spray.zones) {
      const Vec2 c = P(z.centre);
      if ((c.cwiseMax(lo).cwiseMin(hi) - c).norm() < z.radius * cam_.scale) return true;
    }
    return false;
  };
  // an arrow beside element i, on the belt's outer side or else its inner side, if it is in view
  // (and, when `clear`, crosses no pulley's name)
  auto travel_arrow = [&](int i, bool clear) {
    const Vec2 d = (Cd[after(i, n)] - Cd[before(i, n)]).normalized();
    const Vec2 u = (P(Cd[i] + d) - P(Cd[i])).normalized();
    for (double side : {1.0, -1.0}) {
      const Vec2 mid = P(Cd[i] + side * gap * O[i]);
      const Vec2 tail = mid - 0.5 * arrow_len * u, tip = mid + 0.5 * arrow_len * u;
      if (!in_view(tail) || !in_view(tip) || (clear && over_text(tail, tip))) continue;
      out.arrow(tail, tip, arrow_w, 0.8 * font_px_, kInk);
      out.travel.push_back({tail, tip});
      return true;
    }
    return false;
  };
  bool arrows = false;  // (any drawn: the legend shows one)
  for (const Route::Span& sp : sc_.route.spans) {
    if (sp.length * cam_.scale < 2 * arrow_len) continue;
    const Vec2 mid = 0.5 * (sp.from + sp.to);
    int best = 0;
    for (int i = 1; i < n; ++i)
      if ((Cd[i] - mid).squaredNorm() < (Cd[best] - mid).squaredNorm()) best = i;
    // at the span's middle, else the element nearest it (either way, within the middle half of
    // the span) whose arrow crosses no name, else at the middle whatever it crosses
    const int reach = static_cast<int>(0.25 * sp.length / sc_.model.belt.pitch);
    bool drawn = false;
    for (int k = 0; k <= reach && !drawn; ++k)
      for (int i : {best + k, best - k})
        if (!drawn) drawn = travel_arrow((i % n + n) % n, true);
    arrows = (drawn || travel_arrow(best, false)) || arrows;
  }
  if (!arrows) {
    std::vector<int> near(n);
    for (int i = 0; i < n; ++i) near[i] = i;
    std::sort(near.begin(), near.end(), [&](int a, int b) {
      return (P(Cd[a]) - cam_.area_centre).squaredNorm() < (P(Cd[b]) - cam_.area_centre).squaredNorm();
    });
    for (int i : near)
      if ((arrows = travel_arrow(i, false))) break;
  }

  draw_text_and_legend(t, seen, arrows, arrow_w, out);
}

bool FrameBuilder::in_view(const Vec2& p_px) const {
  return p_px.x() > font_px_ && p_px.x() < fs_.width - panel_ - font_px_ && p_px.y() > top_ + font_px_ &&
         p_px.y() < fs_.height - font_px_;
}

void FrameBuilder::draw_pulleys(const double* q, DrawList& out) const {
  const Model& m = sc_.model;
  auto P = [&](const Vec2& w) { return cam_.to_px(w); };
  // tensioner arms under their pulleys: a bar from the pivot to the pulley's centre, the pivot a
  // rimmed disc
  for (const Arm& a : m.arms) {
    const Vec2 pivot = P(a.pivot), c = P(m.centre(a.pulley, q));
    const double w = std::max(3.0, 0.25 * m.pulleys[a.pulley].radius * cam_.scale);
    out.line(pivot, c, w, kRim);
    out.disc(pivot, 0.8 * w, kRim, 32);
    out.disc(pivot, 0.4 * w, kPulley, 24);
  }
  // pulleys: disc up to the belt's inner edge, rim, spokes turning with θ, a red marker spoke
  const double h = 0.5 * thickness_;
  for (int j = 0; j < m.n_p(); ++j) {
    const Pulley& p = m.pulleys[j];
    const double R = std::max(p.radius - h - sc_.penetration[j], 0.2 * p.radius);
    const Vec2 c = P(m.centre(j, q));  // on a tensioner arm it moves
    const double Rp = R * cam_.scale;
    out.disc(c, Rp, kPulley);
    out.ring(c, Rp - std::max(1.5, 0.04 * Rp), Rp, kRim);
    const double theta = q[m.pulley_coord(j)];
    const double w = std::max(1.5, 0.035 * Rp);
    for (int k = 0; k < 6; ++k) {
      const double a = theta + k * M_PI / 3;
      const Vec2 u(std::cos(a), -std::sin(a));  // y down in pixels
      out.line(c + 0.18 * Rp * u, c + 0.9 * Rp * u, k == 0 ? 2.2 * w : w, k == 0 ? kMarker : kSpoke);
    }
    out.disc(c + 0.78 * Rp * Vec2(std::cos(theta), -std::sin(theta)), std::max(2.0, 0.07 * Rp), kMarker, 24);
    out.disc(c, 0.18 * Rp, kRim, 48);
    // its name where place_names put it (text is drawn over everything: only where it is in view)
    const NamePlace& np = names_[j];
    const double tw = font_ ? font_->width(p.name, font_px_) : 0;
    const Vec2 at = c + np.offset;
    const double x = at.x() - (np.align == DrawList::centre ? 0.5 : np.align == DrawList::right ? 1.0 : 0.0) * tw;
    // (on the disc: its middle in view; beside it: both ends)
    const bool seen = np.on_disc ? in_view(at) : in_view(Vec2(x, at.y())) && in_view(Vec2(x + tw, at.y()));
    Rgba box = np.on_disc ? kPulley : out.background;  // a patch of the disc's colour, or paper
    box.a = 0.85f;
    if (np.shown && seen) out.boxed_text(at, p.name, font_px_, kInk, box, np.align);
  }
}

std::string frame_size_problem(const Scene& scene, const FrameSettings& settings, double t, const double* y) {
  Font font;
  // the text of the state drawn (beltsim render's, whose header said t = 0.2 s while this quoted
  // t = 0.0000 s), else of the run's first frame
  if (!y) t = settings.t_start, y = scene.y0.data();
  auto cut = [&](int w, int h) {
    FrameSettings f = settings;
    f.width = w, f.height = h;
    return FrameBuilder(scene, f, &font).cut_text(t, y);
  };
  const std::string now = cut(settings.width, settings.height);
  if (now.empty()) return "";
  // the smallest of its shape in even numbers (a video's): up in steps of 2 %, then back down in
  // steps of 2 pixels of its width
  const double aspect = static_cast<double>(settings.height) / settings.width;
  auto height_of = [&](int w) { return 2 * static_cast<int>(std::ceil(0.5 * aspect * w)); };
  std::string fits = "no size up to 8192 of its shape shows it all";
  for (double k = 1.02; k * std::max(settings.width, settings.height) <= 8192; k *= 1.02) {
    int w = 2 * static_cast<int>(std::ceil(0.5 * k * settings.width));
    if (!cut(w, height_of(w)).empty()) continue;
    while (w - 2 > settings.width && cut(w - 2, height_of(w - 2)).empty()) w -= 2;
    fits = std::to_string(w) + "x" + std::to_string(height_of(w)) + " is the smallest of its shape that shows it all";
    break;
  }
  return std::to_string(settings.width) + "x" + std::to_string(settings.height) +
         " is too small for the frame's text with every line of its legend (" + now + "): " + fits +
         "; the frames are drawn as they are";
}

}  // namespace beltsim::render
