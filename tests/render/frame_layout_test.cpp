// Where things go in a frame: the arrows of travel beside the belt and off the names, the camera
// on the layout or the view, the pulleys' names off the belt and by their own pulley, the pulleys'
// lines of the text band clear of each other and of the colour bar.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "render/draw_list.hpp"
#include "render/frame_fixture.hpp"
#include "render/render_scenes.hpp"

namespace beltsim::render {
namespace {

using test_frames::Fixture;
using test_frames::pulley;
using test_frames::serpentine_layout;
using test_frames::serpentine_with_arm;

// arrows beside the belt point along the route's direction of travel: one at each span's middle,
// outside the loop; in a view of one pulley's rim, one beside the visible belt
TEST_F(Fixture, ArrowsShowTheDirectionOfTravel) {
  const Scene& sc = wet();
  const Eigen::VectorXd y = test::moving_state(sc);
  // the route's tangent (direction of travel) at the point nearest w
  auto travel_at = [&](const Vec2& w) {
    Vec2 best_t(0, 0), p, t;
    double best = 1e300;
    for (int k = 0; k < 4000; ++k) {
      sc.route.eval(sc.route.length * k / 4000, p, t);
      if ((p - w).squaredNorm() < best) best = (p - w).squaredNorm(), best_t = t;
    }
    return best_t;
  };
  auto check = [&](const FrameBuilder& b, const DrawList& dl) {
    const Camera& cam = b.camera();
    for (const auto& [tail, tip] : dl.travel) {
      const Vec2 mid = 0.5 * (tail + tip);
      const Vec2 w = cam.centre + Vec2(mid.x() - cam.area_centre.x(), cam.area_centre.y() - mid.y()) / cam.scale;
      const Vec2 t = travel_at(w), u = (tip - tail).normalized();
      EXPECT_GT(u.x() * t.x() - u.y() * t.y(), 0.95) << "arrow at " << w.transpose();  // y down in pixels
      for (const Vec2& e : {tail, tip}) {
        EXPECT_GT(e.x(), 0);
        EXPECT_LT(e.x(), 0.83 * dl.width);
        EXPECT_GT(e.y(), 0);
        EXPECT_LT(e.y(), dl.height);
      }
    }
  };
  FrameSettings f = fs();
  FrameBuilder fit(sc, f, &font);
  DrawList dl;
  fit.build(0.25, y.data(), dl);
  ASSERT_EQ(dl.travel.size(), sc.route.spans.size());
  check(fit, dl);
  for (size_t k = 0; k < dl.travel.size(); ++k) {
    // outside the loop: farther from the pulleys' centre line (y = 0) than the span (|y| = r)
    const Vec2 mid = 0.5 * (dl.travel[k].first + dl.travel[k].second);
    EXPECT_GT(std::abs(mid.y() - fit.camera().area_centre.y()), 0.1 * fit.camera().scale);
  }
  bool legend = false;
  for (const std::string& t : dl.texts) legend = legend || t == "belt travel";
  EXPECT_TRUE(legend);
  f.view_centre = Vec2(0.39, 0.0), f.view_width = 0.05;  // the driven pulley's rim, no span in view
  FrameBuilder zoom(sc, f, &font);
  zoom.build(0.25, y.data(), dl);
  ASSERT_EQ(dl.travel.size(), 1u);
  check(zoom, dl);
}

// an arrow of travel never crosses a pulley's name: on a serpentine drive whose back-side idler has
// its name beside it, where the span leaving it has its middle, the arrow goes to the belt's other
// side (it was drawn through the name "idler")
TEST_F(Fixture, TravelArrowsStayOffThePulleyNames) {
  SceneDef d;
  d.pulleys = {
      pulley("crank", {0, 0}, 0.08, WrapSide::inside), pulley("tensioner", {-0.108, 0.07}, 0.032, WrapSide::back),
      pulley("pump", {-0.1, 0.18}, 0.05, WrapSide::inside), pulley("idler", {0.01, 0.235}, 0.03, WrapSide::back),
      pulley("alternator", {0.12, 0.22}, 0.028, WrapSide::inside)};
  d.belt.elements = 240;
  d.belt.pretension = 320;
  d.belt.loop_sense = -1;
  const Scene sc = test::moving_scene(d);
  FrameSettings f = fs();
  f.width = 1280, f.height = 720;
  FrameBuilder b(sc, f, &font);
  DrawList dl;
  b.build(0, sc.y0.data(), dl);
  ASSERT_EQ(dl.travel.size(), sc.route.spans.size());
  int names = 0;
  for (const DrawList::TextBox& box : dl.boxes) {
    if (std::none_of(sc.model.pulleys.begin(), sc.model.pulleys.end(),
                     [&](const Pulley& p) { return p.name == box.text; }))
      continue;
    ++names;
    for (const auto& [tail, tip] : dl.travel)
      for (int k = 0; k <= 20; ++k) {  // points along the arrow
        const Vec2 v = tail + (tip - tail) * (k / 20.0);
        EXPECT_FALSE(v.x() > box.lo.x() && v.x() < box.hi.x() && v.y() > box.lo.y() && v.y() < box.hi.y())
            << "the arrow from " << tail.transpose() << " to " << tip.transpose() << " crosses the name " << box.text;
      }
  }
  EXPECT_EQ(names, 5);
}

TEST_F(Fixture, CameraFitsTheLayoutOrFollowsTheView) {
  const Scene& sc = wet();
  FrameSettings f = fs();
  FrameBuilder fit(sc, f, &font);
  // both pulleys (x from -0.1 to 0.39 m) inside the drawing, left of the colour-bar panel
  const Vec2 l = fit.camera().to_px(Vec2(-0.1, 0)), r = fit.camera().to_px(Vec2(0.39, 0));
  EXPECT_GT(l.x(), 0);
  EXPECT_LT(r.x(), 0.83 * f.width);
  EXPECT_GT(r.x() - l.x(), 0.6 * f.width);  // and it fills most of the width
  f.view_centre = Vec2(0.29, 0.0), f.view_width = 0.25;
  FrameBuilder view(sc, f, &font);
  EXPECT_NEAR((view.camera().to_px(Vec2(0.29, 0)) - view.camera().area_centre).norm(), 0, 1e-9);
  const double width_px = (view.camera().to_px(Vec2(0.415, 0)) - view.camera().to_px(Vec2(0.165, 0))).x();
  EXPECT_NEAR(width_px, f.width - std::max(0.17 * f.width, 11.0 * std::max(10.0, std::round(f.height / 40.0))), 1e-6);
}

// a pulley's name sits inside its disc where it fits there and beside the pulley where it does not,
// never on the belt: no element's corner or centre inside the name's box
TEST_F(Fixture, PulleyNamesStayOffTheBelt) {
  const Scene automotive = test::moving_scene(presets::automotive_wet());
  for (const Scene* sc : {&wet(), &automotive}) {
    FrameBuilder b(*sc, fs(), &font);
    DrawList dl;
    b.build(0, sc->y0.data(), dl);
    int inside = 0, beside = 0;
    for (int j = 0; j < sc->model.n_p(); ++j) {
      const Pulley& p = sc->model.pulleys[j];
      const DrawList::TextBox* box = nullptr;
      for (const DrawList::TextBox& t : dl.boxes)
        if (t.text == p.name) box = &t;
      ASSERT_NE(box, nullptr) << p.name;
      auto in_box = [&](const Vec2& v) {
        return v.x() > box->lo.x() && v.x() < box->hi.x() && v.y() > box->lo.y() && v.y() < box->hi.y();
      };
      for (const ElementDraw& e : dl.elements) {
        EXPECT_FALSE(in_box(e.centre)) << p.name << " over an element";
        for (const Vec2& c : e.corners) EXPECT_FALSE(in_box(c)) << p.name << " over an element's corner";
      }
      const Vec2 mid = 0.5 * (box->lo + box->hi), c = b.camera().to_px(sc->model.centre(j, sc->y0.data()));
      ((mid - c).norm() < p.radius * b.camera().scale ? inside : beside) += 1;
    }
    if (sc == &wet())
      EXPECT_EQ(inside, 2);  // the paper's two large pulleys
    else
      EXPECT_GT(beside, 0);  // the automotive drive's small ones
  }
}

// on scripts/serpentine.lua's layout, where the small idler stands beside the alternator, each
// name is nearer its own pulley than any other, on no other pulley and on no other name (the
// idler's went beside it on the side away from the drive's middle, onto the alternator)
TEST_F(Fixture, PulleyNamesSitByTheirOwnPulley) {
  SceneDef d = serpentine_layout();
  const Scene sc = test::moving_scene(d);
  for (int width : {640, 1280}) {
    FrameSettings f = fs();
    f.width = width, f.height = width * 9 / 16;
    FrameBuilder b(sc, f, &font);
    DrawList dl;
    b.build(0, sc.y0.data(), dl);
    std::vector<const DrawList::TextBox*> names;
    for (const Pulley& p : sc.model.pulleys)
      for (const DrawList::TextBox& t : dl.boxes)
        if (t.text == p.name) names.push_back(&t);
    ASSERT_EQ(names.size(), sc.model.pulleys.size()) << width;
    // from a box to pulley k's rim [px], negative inside the disc
    auto to_rim = [&](const DrawList::TextBox& t, int k) {
      const Vec2 c = b.camera().to_px(sc.model.centre(k, sc.y0.data()));
      const Vec2 gap = (t.lo - c).cwiseMax(c - t.hi).cwiseMax(0);
      return gap.norm() - sc.model.pulleys[k].radius * b.camera().scale;
    };
    for (int j = 0; j < sc.model.n_p(); ++j)
      for (int k = 0; k < sc.model.n_p(); ++k) {
        if (k == j) continue;
        const DrawList::TextBox &t = *names[j], &o = *names[k];
        EXPECT_GT(to_rim(t, k), 0) << width << ": " << t.text << " on " << o.text;
        EXPECT_LT(to_rim(t, j), to_rim(t, k)) << width << ": " << t.text << " nearer " << o.text;
        EXPECT_TRUE(t.hi.x() < o.lo.x() || o.hi.x() < t.lo.x() || t.hi.y() < o.lo.y() || o.hi.y() < t.lo.y())
            << width << ": " << t.text << " over " << o.text;
      }
  }
}

// the pulleys' lines of the text band: inside the frame, none over another or over the colour
// bar's texts, in at most three rows at 1280×720 for the serpentine's six pulleys with a tensioner
// arm (one column of six took a quarter of the frame from the drawing)
TEST_F(Fixture, PulleyLinesShareTheTextBandWithoutOverlap) {
  const Scene sc = test::moving_scene(serpentine_with_arm());
  for (int width : {640, 960, 1280}) {
    FrameSettings f = fs();
    f.width = width, f.height = width * 9 / 16;
    FrameBuilder b(sc, f, &font);
    DrawList dl;
    b.build(0, sc.y0.data(), dl);
    std::vector<const DrawList::TextBox*> lines, others;
    for (const DrawList::TextBox& t : dl.boxes) {
      bool line = false;
      for (const Pulley& p : sc.model.pulleys) line = line || t.text.rfind(p.name + ": ", 0) == 0;
      (line ? lines : others).push_back(&t);
    }
    ASSERT_EQ(lines.size(), sc.model.pulleys.size()) << width;
    double bottom = 0;
    for (const DrawList::TextBox* t : lines) {
      EXPECT_GE(t->lo.x(), 0) << width << ": " << t->text;
      EXPECT_LE(t->hi.x(), width) << width << ": " << t->text;
      bottom = std::max(bottom, t->hi.y());
      auto apart = [](const DrawList::TextBox* a, const DrawList::TextBox* c) {
        return a->hi.x() <= c->lo.x() || c->hi.x() <= a->lo.x() || a->hi.y() <= c->lo.y() || c->hi.y() <= a->lo.y();
      };
      for (const DrawList::TextBox* o : lines) {
        if (o != t) {
          EXPECT_TRUE(apart(t, o)) << width << ": " << t->text << " over " << o->text;
        }
      }
      for (const DrawList::TextBox* o : others) {  // below the time line: the bar's, the names'
        if (o->lo.y() > 2 * f.height / 40.0 * 1.4) {
          EXPECT_TRUE(apart(t, o)) << width << ": " << t->text << " over " << o->text;
        }
      }
    }
    if (width == 1280) {
      EXPECT_LT(bottom, 5 * 1.4 * 18) << "more than three rows of pulley lines";
    }
  }
}

// a portrait frame: its text inside it (the font from the height ran the pulleys' lines off the
// right edge at 720x1280) and the tensioner arm's pivot in view (it was left out of the fit and
// drawn off the left edge): a user trial
TEST_F(Fixture, APortraitFrameKeepsItsTextAndTheArmInView) {
  const Scene sc = test::moving_scene(serpentine_with_arm());
  for (const auto& [w, h] : {std::pair{720, 1280}, std::pair{360, 640}, std::pair{1280, 720}}) {
    FrameSettings f = fs();
    f.width = w, f.height = h;
    FrameBuilder b(sc, f, &font);
    DrawList dl;
    b.build(0, sc.y0.data(), dl);
    for (const DrawList::TextBox& t : dl.boxes) {
      EXPECT_GE(t.lo.x(), 0) << w << "x" << h << ": " << t.text;
      EXPECT_LE(t.hi.x(), w) << w << "x" << h << ": " << t.text;
    }
    const Vec2 pivot = b.camera().to_px(sc.model.arms.at(0).pivot);
    EXPECT_GT(pivot.x(), 0) << w << "x" << h;
    EXPECT_LT(pivot.x(), w) << w << "x" << h;
  }
}

// a small frame's legend stays inside it, losing the lines a reader needs least (a 320x180 frame's
// ran off its bottom: a user trial), and its colour bar keeps both end labels and zero (it read
// 0.030 / -0.010 / -0.050 for -0.05..0.05); 640x360 keeps every line
TEST_F(Fixture, ASmallFramesLegendStaysInsideWithTheBarsEnds) {
  const Scene& sc = wet();
  const Eigen::VectorXd y = test::moving_state(sc);
  for (const auto& [w, h] : {std::pair{320, 180}, std::pair{640, 360}}) {
    FrameSettings f = fs();
    f.width = w, f.height = h;
    f.quantity = FrameQuantity::slip;
    FrameBuilder b(sc, f, &font);
    DrawList dl;
    b.build(0, y.data(), dl);
    bool wet = false, top = false, bottom = false, zero = false;
    for (const DrawList::TextBox& t : dl.boxes) {
      EXPECT_LE(t.hi.y(), h) << w << "x" << h << ": " << t.text;
      wet = wet || t.text.rfind("wet (", 0) == 0;
      top = top || t.text == "0.050";
      bottom = bottom || t.text == "\u22120.050" || t.text == "-0.050";
      zero = zero || t.text == "0.000";
    }
    EXPECT_TRUE(wet && top && bottom && zero)
        << w << "x" << h << ": wet " << wet << ", ends " << top << bottom << ", zero " << zero;
    bool sign = false;
    for (const std::string& t : dl.texts) sign = sign || t == "+ : along travel";
    EXPECT_EQ(sign, w == 640) << w << "x" << h;
  }
}

// a frame too small for its text says so, naming what it cuts and the smallest size of its shape
// that shows it all (a 161x91 frame cut its header and a 320x180 one left legend lines out without
// a word: a user trial)
TEST_F(Fixture, AFrameTooSmallForItsTextSaysSo) {
  const Scene& sc = wet();
  FrameSettings f = fs();
  f.quantity = FrameQuantity::slip;
  auto problem = [&](int w, int h) {
    f.width = w, f.height = h;
    return frame_size_problem(sc, f);
  };
  EXPECT_EQ(problem(640, 360), "");
  const std::string small = problem(320, 180);
  EXPECT_EQ(small.rfind("320x180 is too small for the frame's text with every line of its legend (its legend leaves "
                        "out '+ : along travel', 'belt travel'): ",
                        0),
            0u)
      << small;
  int w = 0, h = 0;
  ASSERT_EQ(std::sscanf(small.c_str() + small.find("): ") + 3, "%dx%d is the smallest", &w, &h), 2) << small;
  EXPECT_EQ(problem(w, h), "") << w << "x" << h;
  EXPECT_NE(problem(w - 2, h - 2), "") << w << "x" << h;
  EXPECT_NE(problem(161, 91).find("(the pulleys' lines run off its right edge; its legend leaves out "),
            std::string::npos)
      << problem(161, 91);
}

}  // namespace
}  // namespace beltsim::render
