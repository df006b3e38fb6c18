// FrameBuilder::place_names: where each pulley's name goes in the frames (draw_list.hpp), chosen
// once per builder.
#include "render/draw_list.hpp"

#include <algorithm>
#include <cmath>

#include "render/text.hpp"
#include "scene/scene.hpp"

namespace beltsim::render {

void FrameBuilder::place_names() {
  const Model& m = sc_.model;
  auto P = [&](const Vec2& w) { return cam_.to_px(w); };
  const double h = 0.5 * thickness_;
  const double* q = sc_.y0.size() ? sc_.y0.data() : nullptr;
  auto centre = [&](int j) { return P(q ? m.centre(j, q) : m.pulleys[j].centre); };
  const DrawList::BoxMargins bm = DrawList::box_margins(font_px_);
  auto width = [&](int j) { return font_ ? font_->width(m.pulleys[j].name, font_px_) : 0.0; };
  // the box [px] of a name at `at` with that alignment
  struct Box {
    Vec2 lo, hi;
  };
  auto box = [&](int j, const Vec2& at, DrawList::Align a) {
    const double x = at.x() - (a == DrawList::centre ? 0.5 : a == DrawList::right ? 1.0 : 0.0) * width(j);
    return Box{Vec2(x - bm.pad, at.y() - bm.above), Vec2(x + width(j) + bm.pad, at.y() + bm.below)};
  };
  // on the disc below the hub, so the spokes do not cross it, where it fits there
  names_.assign(m.n_p(), NamePlace{});
  std::vector<Box> placed;
  for (int j = 0; j < m.n_p(); ++j) {
    const double R = std::max(m.pulleys[j].radius - h - sc_.penetration[j], 0.2 * m.pulleys[j].radius);
    const double Rp = R * cam_.scale, below = 0.18 * Rp + 1.1 * font_px_;
    if (std::hypot(0.5 * width(j) + bm.pad, below + bm.below) > 0.95 * Rp) continue;
    names_[j] = {true, true, Vec2(0, below), DrawList::centre};
    placed.push_back(box(j, centre(j) + names_[j].offset, DrawList::centre));
  }
  // what a name beside its pulley keeps clear of: points along the belt's path and the tensioner
  // arms with their half widths [px]
  std::vector<std::pair<Vec2, double>> marks;
  const double step = std::max(2.0 / cam_.scale, sc_.route.length / 5000);
  for (double s = 0; s < sc_.route.length; s += step) {
    Vec2 p, t;
    sc_.route.eval(s, p, t);
    marks.push_back({P(p), h * cam_.scale});
  }
  for (const Arm& a : m.arms) {
    const Vec2 pivot = P(a.pivot), c = centre(a.pulley);
    const double w = std::max(3.0, 0.25 * m.pulleys[a.pulley].radius * cam_.scale);
    for (int k = 0; k <= 20; ++k) marks.push_back({pivot + (c - pivot) * (k / 20.0), 0.8 * w});
  }
  // the distance between two boxes [px] (a point is a box of no size)
  auto apart = [](const Box& a, const Box& b) {
    return Vec2(std::max({a.lo.x() - b.hi.x(), b.lo.x() - a.hi.x(), 0.0}),
                std::max({a.lo.y() - b.hi.y(), b.lo.y() - a.hi.y(), 0.0}))
        .norm();
  };
  // a name's room [px]: its box's distance from the nearest mark, other pulley or name placed so far
  auto room = [&](int j, const Box& b) {
    double r = 1e300;
    for (const auto& [p, w] : marks) r = std::min(r, apart(b, {p, p}) - w);
    for (int k = 0; k < m.n_p(); ++k)
      if (k != j) r = std::min(r, apart(b, {centre(k), centre(k)}) - m.pulleys[k].radius * cam_.scale);
    for (const Box& o : placed) r = std::min(r, apart(b, o));
    return r;
  };
  Vec2 middle = Vec2::Zero();  // of the pulleys' centres
  for (int j = 0; j < m.n_p(); ++j) middle += centre(j) / m.n_p();
  // else beside the pulley, outside the belt: level with the hub on the side away from the drive's
  // middle where that is clear by a quarter of the font size, else where it has the most room (up
  // to a font size; among equals the nearest the side away from the middle) of sixteen places
  // round the pulley
  for (int j = 0; j < m.n_p(); ++j) {
    if (names_[j].on_disc) continue;
    const Vec2 c = centre(j);
    const double out_px = (m.pulleys[j].radius + 2 * h) * cam_.scale + 0.5 * font_px_;
    const bool right = c.x() >= middle.x();
    std::vector<NamePlace> tries{
        {true, false, Vec2(right ? out_px : -out_px, 0.35 * font_px_), right ? DrawList::left : DrawList::right}};
    const Vec2 away = (c - middle).norm() > 0 ? (c - middle).normalized() : Vec2(1, 0);
    std::vector<Vec2> dirs;
    for (int k = 0; k < 16; ++k) dirs.push_back(Vec2(std::cos(k * M_PI / 8), std::sin(k * M_PI / 8)));
    std::stable_sort(dirs.begin(), dirs.end(), [&](const Vec2& a, const Vec2& b) { return a.dot(away) > b.dot(away); });
    const Vec2 half(0.5 * width(j) + bm.pad, 0.5 * (bm.above + bm.below));
    for (const Vec2& u : dirs) {
      // the box's centre along u, the nearest where the box keeps out_px from the hub
      double t0 = 0, t1 = out_px + half.x() + half.y();
      for (int it = 0; it < 30; ++it) {
        const double t = 0.5 * (t0 + t1);
        ((t * u).cwiseAbs() - half).cwiseMax(0).norm() < out_px ? t0 = t : t1 = t;
      }
      tries.push_back({true, false, t1 * u + Vec2(0, 0.5 * (bm.above - bm.below)), DrawList::centre});
    }
    double best = -1e300;
    for (size_t k = 0; k < tries.size(); ++k) {
      const Box b = box(j, c + tries[k].offset, tries[k].align);
      if (!in_view(b.lo) || !in_view(b.hi)) continue;
      const double r = std::min(room(j, b), 1.0 * font_px_);
      if (k == 0 && r >= 0.25 * font_px_) {
        names_[j] = tries[k];
        break;
      }
      if (r > best) best = r, names_[j] = tries[k];
    }
    if (names_[j].shown) placed.push_back(box(j, c + names_[j].offset, names_[j].align));
  }
}

}  // namespace beltsim::render
