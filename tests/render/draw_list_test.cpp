// The draw list without GL: element quads where the state puts the elements, colours from the
// colour map, magnification about the nominal path, wet and slip marks, the text band and the
// colour bar, colour-map properties (where things go in the frame: frame_layout_test.cpp).
#include "render/draw_list.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>

#include "model/contacts.hpp"
#include "model/forces.hpp"
#include "model/observables.hpp"
#include "render/colormap.hpp"
#include "render/frame_fixture.hpp"
#include "render/mode_frames.hpp"
#include "render/render_scenes.hpp"
#include "render/text.hpp"

namespace beltsim::render {
namespace {

using test_frames::Fixture;

// CIE L* (perceived lightness, 0..100) of an sRGB colour
double luminance(Rgba c) {
  auto lin = [](double u) { return u <= 0.04045 ? u / 12.92 : std::pow((u + 0.055) / 1.055, 2.4); };
  const double Y = 0.2126 * lin(c.r) + 0.7152 * lin(c.g) + 0.0722 * lin(c.b);
  return 116 * (Y > 0.008856 ? std::cbrt(Y) : 7.787 * Y + 16.0 / 116) - 16;
}

TEST(ColourMap, ViridisLightnessRisesDivergingIsSymmetric) {
  for (int k = 1; k <= 64; ++k)
    EXPECT_GT(luminance(colour_at(ColourMap::viridis, k / 64.0)),
              luminance(colour_at(ColourMap::viridis, (k - 1) / 64.0)));
  for (int k = 0; k < 32; ++k) {
    // lightness rises to the grey middle and falls after it, equally on both sides (within 2 L*
    // units: the anchors are symmetric in L*, the interpolation between them in sRGB nearly so)
    const double a = luminance(colour_at(ColourMap::diverging, k / 64.0));
    const double b = luminance(colour_at(ColourMap::diverging, 1 - k / 64.0));
    EXPECT_LT(a, luminance(colour_at(ColourMap::diverging, 0.5)));
    EXPECT_NEAR(a, b, 2.0);
  }
}

// CIE L*a*b* (D65) of an sRGB colour
Eigen::Vector3d lab(Rgba c) {
  auto lin = [](double u) { return u <= 0.04045 ? u / 12.92 : std::pow((u + 0.055) / 1.055, 2.4); };
  const double r = lin(c.r), g = lin(c.g), b = lin(c.b);
  const double X = (0.4124 * r + 0.3576 * g + 0.1805 * b) / 0.95047, Y = 0.2126 * r + 0.7152 * g + 0.0722 * b,
               Z = (0.0193 * r + 0.1192 * g + 0.9505 * b) / 1.08883;
  auto f = [](double t) { return t > 0.008856 ? std::cbrt(t) : 7.787 * t + 16.0 / 116; };
  return {116 * f(Y) - 16, 500 * (f(X) - f(Y)), 200 * (f(Y) - f(Z))};
}

// the slipping mark cannot be read as a value: every colour of both maps is farther from it (CIE76
// ΔE) than half the diverging map's distance from its grey middle to either end (ΔE 87, so 43;
// the orange used before came within 40 of the map's warm side, magenta stays 61 away)
TEST(ColourMap, SlipMarkIsNoColourOfEitherMap) {
  const double half =
      0.5 * (lab(colour_at(ColourMap::diverging, 0)) - lab(colour_at(ColourMap::diverging, 0.5))).norm();
  EXPECT_NEAR(half, 43.4, 0.5);
  for (ColourMap map : {ColourMap::viridis, ColourMap::diverging})
    for (int k = 0; k <= 256; ++k) EXPECT_GT((lab(kSlipColour) - lab(colour_at(map, k / 256.0))).norm(), half) << k;
}

TEST(ColourMap, BandsAndNaN) {
  ColourScale s;
  s.lo = 0, s.hi = 160, s.levels = 16;
  EXPECT_EQ(s.band(0), 0);
  EXPECT_EQ(s.band(9.99), 0);
  EXPECT_EQ(s.band(10.01), 1);
  EXPECT_EQ(s.band(159.9), 15);
  EXPECT_EQ(s.band(1e9), 15);
  EXPECT_EQ(s.band(-5), 0);
  EXPECT_EQ(s.band(std::nan("")), -1);
  const Rgba none = s.colour(std::nan(""));
  EXPECT_EQ(none.r, s.none.r);
  // one flat colour per band, different between neighbouring bands
  const Rgba a = s.colour(11), b = s.colour(19), c = s.colour(21);
  EXPECT_EQ(a.r, b.r);
  EXPECT_NE(b.g, c.g);
}

TEST_F(Fixture, ElementQuadsSitWhereTheStateSays) {
  const Scene& sc = wet();
  const Eigen::VectorXd y = sc.y0;  // smooth: the checks of the shape below hold to 1 %
  FrameBuilder b(sc, fs(), &font);
  DrawList dl;
  b.build(0.1, y.data(), dl);
  ASSERT_EQ(static_cast<int>(dl.elements.size()), sc.model.n_el());
  const int n = sc.model.n_el();
  const double pitch = sc.model.belt.pitch * b.camera().scale;
  for (int i = 0; i < n; ++i) {
    const ElementDraw& el = dl.elements[i];
    const Vec2 want = b.camera().to_px(Vec2(y[3 * i], y[3 * i + 1]));
    EXPECT_NEAR((el.centre - want).norm(), 0, 1e-9) << "element " << i;
    // the quad runs between the joints with its neighbours, which it shares with them
    const ElementDraw& next = dl.elements[(i + 1) % n];
    EXPECT_NEAR((el.corners[1] - next.corners[0]).norm(), 0, 1e-9);
    EXPECT_NEAR((el.corners[2] - next.corners[3]).norm(), 0, 1e-9);
    // its mid-line passes the centre within twice a chord's sagitta on a pulley (the joints sit
    // l²/8r inside the circle through the centres: l²/4r = 1 mm here)
    const double l = sc.model.belt.pitch;
    const Vec2 mid = 0.25 * (el.corners[0] + el.corners[1] + el.corners[2] + el.corners[3]);
    EXPECT_LT((mid - want).norm(), 1.1 * l * l / (4 * 0.1) * b.camera().scale) << "element " << i;
    // one pitch long, along the element's axis within the bend between neighbours (one pitch
    // turns the belt by l/r = 0.2 rad on the pulleys; measured up to 0.031 where an arc meets a
    // span; y points down in pixels)
    const Vec2 d = 0.5 * (el.corners[1] + el.corners[2] - el.corners[0] - el.corners[3]);
    EXPECT_NEAR(d.norm(), pitch, 0.02 * pitch);
    EXPECT_NEAR(std::remainder(std::atan2(-d.y(), d.x()) - y[3 * i + 2], 2 * M_PI), 0, 0.05) << "element " << i;
  }
}

TEST_F(Fixture, ColoursComeFromTheColourMap) {
  const Scene& sc = wet();
  const Eigen::VectorXd y = test::moving_state(sc);
  FrameSettings f = fs();
  f.range_lo = 0, f.range_hi = 1000;
  f.levels = 16;
  FrameBuilder b(sc, f, &font);
  DrawList dl;
  b.build(0.1, y.data(), dl);
  const Model& m = sc.model;
  const double* v = y.data() + m.n_coord();
  int bands_seen = 0;
  std::vector<bool> seen(16, false);
  for (int i = 0; i < m.n_el(); ++i) {
    const double T = 0.5 * (sde_axial_force(m, y.data(), v, i) + sde_axial_force(m, y.data(), v, (i + 1) % m.n_el()));
    const ElementDraw& el = dl.elements[i];
    EXPECT_NEAR(el.value, T, 1e-9);
    EXPECT_EQ(el.band, std::clamp(static_cast<int>(std::floor(T / 1000 * 16)), 0, 15));
    const Rgba want = colour_at(ColourMap::viridis, (el.band + 0.5) / 16);
    EXPECT_FLOAT_EQ(el.colour.g, want.g);
    // a triangle of that colour is in the list
    bool found = false;
    for (const SolidVertex& sv : dl.triangles)
      found = found || (sv.c.r == want.r && sv.c.g == want.g && sv.c.b == want.b);
    EXPECT_TRUE(found);
    if (!seen[el.band]) seen[el.band] = true, bands_seen++;
  }
  EXPECT_GE(bands_seen, 4);  // the state's ±300 N wave spans several bands
  EXPECT_FALSE(dl.glyphs.empty());
}

TEST_F(Fixture, MagnifiesTheDeviationFromTheNominalPath) {
  const Scene& sc = test::moving_scene(presets::paper_dry());
  Eigen::VectorXd y = sc.y0;
  // element in the middle of the upper span: move it up by 0.2 mm
  const int i = sc.element_nearest(Vec2(0.145, 0.1));
  y[3 * i + 1] += 2e-4;
  FrameSettings f = fs();
  f.magnify = 50;
  FrameBuilder b(sc, f, &font);
  const Vec2 C(y[3 * i], y[3 * i + 1]);
  const Route path = b.nominal(y.data());
  const Vec2 shown = b.displayed(path, C);
  const Vec2 rest = b.displayed(path, Vec2(sc.y0[3 * i], sc.y0[3 * i + 1]));
  EXPECT_NEAR((shown - rest).y(), 50 * 2e-4, 1e-6);
  EXPECT_NEAR((shown - rest).x(), 0, 1e-9);
  // on a pulley the static penetration is not deformation: the state at rest is drawn on the path
  const int k = sc.element_nearest(Vec2(-0.1, 0));
  const Vec2 Ck(sc.y0[3 * k], sc.y0[3 * k + 1]);
  EXPECT_NEAR((b.displayed(path, Ck) - Ck).norm(), 0, 50 * 2e-5);
}

// A pulley on a tensioner arm moves: the nominal path goes round it where it is, so a belt that
// moves with it is not drawn lifted off it (a user read a magnified frame as the belt leaving the
// tensioner while it pressed on it: the path had stayed where the arm was at rest)
TEST_F(Fixture, TheNominalPathFollowsATensionerArm) {
  const Scene sc = test::moving_scene(presets::automotive_tensioner());
  const Model& m = sc.model;
  ASSERT_EQ(m.arms.size(), 1u);
  int j = 0;
  while (m.pulleys[j].arm < 0) ++j;
  // the elements on the pulley's wrap, which the frame of the state at rest draws where they are
  FrameSettings f = fs();
  f.magnify = 5;
  FrameBuilder b(sc, f, &font);
  Eigen::VectorXd y = sc.y0;
  const Vec2 c0 = m.centre(j, y.data());
  const Route rest = b.nominal(y.data());
  std::vector<int> wrap;
  std::vector<double> drawn_off;  // how far from itself each is drawn at rest (chords, magnified)
  for (int i = 0; i < m.n_el(); ++i) {
    const Vec2 P(y[3 * i], y[3 * i + 1]);
    if (std::abs((P - c0).norm() - m.pulleys[j].radius) < 1e-3)
      wrap.push_back(i), drawn_off.push_back((b.displayed(rest, P) - P).norm());
  }
  ASSERT_GE(wrap.size(), 3u);
  // the arm turned by 0.03 rad (some 2 mm at its 63 mm), the wrap carried along with the pulley
  y[m.arm_coord(m.pulleys[j].arm)] += 0.03;
  const Vec2 shift = m.centre(j, y.data()) - c0;
  ASSERT_GT(shift.norm(), 1e-3);
  for (int i : wrap) y[3 * i] += shift.x(), y[3 * i + 1] += shift.y();
  const Route path = b.nominal(y.data());
  double worst_at_rest_path = 0;
  for (size_t k = 0; k < wrap.size(); ++k) {
    // drawn as at rest, within a tenth of the shift
    const int i = wrap[k];
    const Vec2 P(y[3 * i], y[3 * i + 1]);
    EXPECT_NEAR((b.displayed(path, P) - P).norm(), drawn_off[k], 0.1 * shift.norm()) << "element " << i;
    worst_at_rest_path = std::max(worst_at_rest_path, (b.displayed(rest, P) - P).norm() - drawn_off[k]);
  }
  // against the path at rest (what frames drew) the wrap stood off the rim by some magnify - 1 shifts
  EXPECT_GT(worst_at_rest_path, 2 * shift.norm());
}

TEST_F(Fixture, WetAndSlippingElementsAreMarked) {
  const Scene& sc = wet();
  const Eigen::VectorXd y = test::moving_state(sc);
  FrameSettings f = fs();
  f.quantity = FrameQuantity::slip;
  FrameBuilder b(sc, f, &font);
  DrawList dl;
  b.build(0.1, y.data(), dl);
  const Model& m = sc.model;
  // the marks are the gross-slip arcs of the one criterion (model/observables.hpp)
  Observation o;
  observe(m, sc.drive, sc.senses(), 0.1, y.data(), o);
  int wet = 0, slipping = 0, off = 0;
  for (int i = 0; i < m.n_el(); ++i) {
    const ElementDraw& el = dl.elements[i];
    EXPECT_EQ(el.wet, sc.drive.mu[i] < 0.5);
    wet += el.wet;
    const ElementContact c = element_contact(o.contacts, i);
    EXPECT_EQ(el.slipping, o.elements[i].state == ContactState::slip) << i;
    slipping += el.slipping;
    if (c.pulley < 0) {
      EXPECT_TRUE(std::isnan(el.value));
      EXPECT_EQ(el.colour.r, dl.scale.none.r);
      off++;
    }
  }
  EXPECT_EQ(wet, 30);
  EXPECT_GT(slipping, 5);
  EXPECT_LT(slipping, 55);
  EXPECT_GT(off, 10);
}

// a spray zone's disc is in the legend (filled: spraying, outline: off) where the scene has one
// and only there, the legend inside the frame; the arrows of travel keep off the disc where the
// span's middle half leaves room (the one at the upper span's middle was drawn inside
// scripts/spray_zone.lua's zone: a user trial)
TEST_F(Fixture, ASprayZoneIsInTheLegendAndOffTheArrows) {
  SceneDef d = presets::paper_dry();
  SprayZone z;
  z.centre = {0.145, 0.1}, z.radius = 0.03, z.mu = 0.2, z.from = 0, z.to = 1, z.drying_length = 2;
  d.spray.push_back(z);
  const Scene sprayed = test::moving_scene(d), plain = test::moving_scene(presets::paper_dry());
  for (const auto& [w, h] : {std::pair{640, 360}, std::pair{1280, 720}, std::pair{320, 180}})
    for (const Scene* sc : {&plain, &sprayed}) {
      FrameSettings f = fs();
      f.width = w, f.height = h;
      f.quantity = FrameQuantity::slip;
      FrameBuilder b(*sc, f, &font);
      DrawList dl;
      b.build(0.1, test::moving_state(*sc).data(), dl);
      bool legend = false;
      for (const DrawList::TextBox& t : dl.boxes) {
        EXPECT_LE(t.hi.x(), w) << w << "x" << h << ": " << t.text;
        EXPECT_LE(t.hi.y(), h) << w << "x" << h << ": " << t.text;
        legend = legend || t.text == "spray: on, off";
      }
      EXPECT_EQ(legend, sc == &sprayed) << w << "x" << h;
      // (at 320x180 the disc covers the span's middle half for an arrow: drawn over it there)
      if (sc == &plain || w == 320) continue;
      const Vec2 c = b.camera().to_px(z.centre);
      const double r = z.radius * b.camera().scale;
      EXPECT_FALSE(dl.travel.empty());
      for (const auto& [tail, tip] : dl.travel) {
        const double u = std::clamp((c - tail).dot(tip - tail) / (tip - tail).squaredNorm(), 0.0, 1.0);
        EXPECT_GT((tail + u * (tip - tail) - c).norm(), r) << w << "x" << h;
      }
    }
}

// run events change μ while running: the frame shows the drive it is given, not the scene's
TEST_F(Fixture, WetMarksFollowTheDriveAsItIsNow) {
  const Scene& sc = test::moving_scene(presets::paper_dry());
  const Eigen::VectorXd y = sc.y0;
  Drive now = sc.drive;
  for (int i = 0; i < 10; ++i) now.mu[i] = 0.2;
  FrameSettings f = fs();
  f.quantity = FrameQuantity::mu;
  FrameBuilder b(sc, f, &font);
  DrawList before, after;
  b.build(0, y.data(), before);
  b.build(0, y.data(), after, &now);
  for (int i = 0; i < sc.model.n_el(); ++i) {
    EXPECT_FALSE(before.elements[i].wet);
    EXPECT_EQ(after.elements[i].wet, i < 10);
    EXPECT_DOUBLE_EQ(after.elements[i].value, now.mu[i]);
  }
  // a stretch raised above the scene's μ is not wet, nor is the rest of the belt (both were marked
  // wet, μ below the raised 1.5: a user trial)
  for (int i = 0; i < 10; ++i) now.mu[i] = 1.5;
  DrawList raised;
  b.build(0, y.data(), raised, &now);
  for (int i = 0; i < sc.model.n_el(); ++i) EXPECT_FALSE(raised.elements[i].wet) << i;
}

TEST_F(Fixture, SignedQuantitiesUseTheDivergingMapWithTheSignAlongTravel) {
  const Scene& sc = wet();
  const Eigen::VectorXd y = test::moving_state(sc);
  const std::vector<double> slip = element_values(sc, FrameQuantity::slip, 0, y.data());
  // the driver's rim runs 1 % ahead of the belt (belt slips backwards: negative), the driven's
  // 1 % behind (positive), apart from the ±3 % ripple of the belt's speed
  const Model& m = sc.model;
  double on_driver = 0, on_driven = 0;
  ContactRecords contacts;
  fill_contacts(m, sc.drive, 0, y.data(), contacts);
  for (int i = 0; i < m.n_el(); ++i) {
    const ElementContact c = element_contact(contacts, i);
    if (c.pulley == 0) on_driver += slip[i];
    if (c.pulley == 1) on_driven += slip[i];
  }
  EXPECT_LT(on_driver, 0);
  EXPECT_GT(on_driven, 0);
  FrameSettings f = fs();
  f.quantity = FrameQuantity::friction;
  FrameBuilder b(sc, f, &font);
  EXPECT_EQ(b.scale().map, ColourMap::diverging);
  EXPECT_LT(b.scale().lo, 0);
  EXPECT_DOUBLE_EQ(b.scale().lo, -b.scale().hi);
}

// the time has 4 decimals, or as many more as tell consecutive frames apart (fps = 30 with
// slowdown = 1000 read 0.3000, 0.3000, 0.3001: a user trial)
TEST_F(Fixture, TheTimeTellsConsecutiveFramesApart) {
  const Scene& sc = wet();
  const Eigen::VectorXd y = test::moving_state(sc);
  auto head = [&](double fps, double slowdown, double t) {
    FrameSettings f = fs();
    f.fps = fps, f.slowdown = slowdown;
    FrameBuilder b(sc, f, &font);
    DrawList dl;
    b.build(t, y.data(), dl);
    for (const std::string& text : dl.texts)
      if (text.rfind("t = ", 0) == 0) return text.substr(0, text.find(" s "));
    return std::string("no time");
  };
  EXPECT_EQ(head(30, 10, 0.3), "t = 0.3000");
  EXPECT_EQ(head(240, 10, 0.3), "t = 0.3000");
  EXPECT_EQ(head(240, 40, 0.3), "t = 0.3000");  // frames 1.04e-4 s apart
  EXPECT_EQ(head(30, 1000, 0.3 + 1 / 30000.0), "t = 0.30003");
  EXPECT_EQ(head(30, 1000, 0.3 + 2 / 30000.0), "t = 0.30007");
  EXPECT_EQ(head(240, 1000, 0.3 + 1 / 240000.0), "t = 0.300004");
  EXPECT_EQ(head(240, 1000, 0.3 + 2 / 240000.0), "t = 0.300008");
  EXPECT_EQ(head(100, 100, 0.3), "t = 0.3000");  // 1e-4 apart: 4 are enough
}

// every glyph drawn lies in a recorded text rectangle (what `beltsim compare --ignore-text` leaves
// out), a boxed text's rectangle covering its box; a plain text's its extent from the font
TEST_F(Fixture, EveryGlyphLiesInATextRectangle) {
  const Scene& sc = wet();
  const Eigen::VectorXd y = test::moving_state(sc);
  FrameBuilder b(sc, fs(), &font);
  DrawList dl;
  b.build(0.3, y.data(), dl);
  dl.text(Vec2(20.3, 40.6), "plain \u03c9 = 1.25 rad/s", 17, Rgba{0, 0, 0, 1}, DrawList::centre);
  ASSERT_EQ(dl.text_rects.size(), dl.boxes.size() + 1);  // the frame's text is all boxed
  auto inside = [](const PixelRect& r, double x0, double y0, double x1, double y1) {
    return r.x <= x0 && r.y <= y0 && x1 <= r.x + r.w && y1 <= r.y + r.h;
  };
  for (size_t k = 0; k < dl.boxes.size(); ++k)
    EXPECT_TRUE(
        inside(dl.text_rects[k], dl.boxes[k].lo.x(), dl.boxes[k].lo.y(), dl.boxes[k].hi.x(), dl.boxes[k].hi.y()))
        << dl.boxes[k].text;
  ASSERT_EQ(dl.glyphs.size() % 6, 0u);
  for (size_t g = 0; g < dl.glyphs.size(); g += 6) {
    double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
    for (size_t v = g; v < g + 6; ++v)
      x0 = std::min<double>(x0, dl.glyphs[v].x), y0 = std::min<double>(y0, dl.glyphs[v].y),
      x1 = std::max<double>(x1, dl.glyphs[v].x), y1 = std::max<double>(y1, dl.glyphs[v].y);
    EXPECT_TRUE(std::any_of(dl.text_rects.begin(), dl.text_rects.end(),
                            [&](const PixelRect& r) { return inside(r, x0, y0, x1, y1); }))
        << "a glyph at " << x0 << ", " << y0 << " to " << x1 << ", " << y1;
  }
  // the plain text's: its width and the font's extent, 1 px around, not the whole frame
  const PixelRect& r = dl.text_rects.back();
  EXPECT_NEAR(r.w, font.width("plain \u03c9 = 1.25 rad/s", 17) + 2, 2.01);
  EXPECT_NEAR(r.h, font.ascent(17) + font.descent(17) + 2, 2.01);
  // a new frame starts a new list
  b.build(0.3, y.data(), dl);
  EXPECT_EQ(dl.text_rects.size(), dl.boxes.size());
}

// the text states the time, each pulley's speed and slip, the quantity, its unit and range
TEST_F(Fixture, TextAndColourBarSayWhatIsShown) {
  const Scene& sc = wet();
  const Eigen::VectorXd y = test::moving_state(sc);
  FrameSettings f = fs();
  f.magnify = 20;
  FrameBuilder b(sc, f, &font);
  DrawList dl;
  b.build(0.125, y.data(), dl);
  auto has = [&](const std::string& part) {
    for (const std::string& t : dl.texts)
      if (t.find(part) != std::string::npos) return true;
    return false;
  };
  EXPECT_TRUE(has("t = 0.1250 s"));
  EXPECT_TRUE(has("colour: belt tension [N]"));
  EXPECT_TRUE(has("deformation \u00d720"));
  // the driver's rim runs 1 % ahead of the belt's 6 m/s mean speed (moving_state): ω = −60.6 rad/s;
  // slip is the pulley's slip_pitch, the belt on its wrap minus the rim's pitch line
  // (model/observables.hpp): here, every element slipping one way or the other (±3 % about
  // 6 m/s), what the run slipping backwards before the driver's exit and forwards before the
  // driven pulley's gives
  Observation o;
  observe(sc.model, sc.drive, sc.senses(), 0.125, y.data(), o);
  EXPECT_NEAR(o.pulleys[0].slip_pitch, -0.112, 5e-4);
  EXPECT_NEAR(o.pulleys[1].slip_pitch, 0.121, 5e-4);
  EXPECT_TRUE(has("driver: \u03c9 = \u221260.60 rad/s, slip_pitch \u22120.112 m/s"));
  EXPECT_TRUE(has("driven: \u03c9 = \u221259.40 rad/s, slip_pitch +0.121 m/s"));
  for (const char* s : {"belt tension", "[N]", "0", "1000", "wet (\u03bc < 1)", "slipping"}) EXPECT_TRUE(has(s)) << s;
}

// the default bar's end is a round number (its quarters, the ticks, round too) at most a third
// above twice the pretension, so the spans fill at least 3/4 of the bar: a 300 N pretension's
// 600 N ends at 600 N, not at 1000 N where every span took the bar's lowest colours
TEST_F(Fixture, DefaultTensionRangeEndsRoundJustAboveTwiceThePretension) {
  Scene sc = wet();
  double lo = 0, hi = 0;
  for (double T0 : {300.0, 500.4, 37.0, 1234.0, 7.9, 2600.0}) {
    sc.static_tension = T0;
    default_range(sc, FrameQuantity::tension, lo, hi);
    EXPECT_EQ(lo, 0);
    EXPECT_GE(hi, 0.97 * 2 * T0) << T0;
    EXPECT_LE(hi, 1.34 * 2 * T0) << T0;
    const double mant = hi / std::pow(10.0, std::floor(std::log10(hi)));
    bool round = false;
    for (double m : {1.0, 1.2, 1.6, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0}) round = round || std::abs(mant - m) < 1e-9;
    EXPECT_TRUE(round) << hi;
  }
  sc.static_tension = 300;
  default_range(sc, FrameQuantity::tension, lo, hi);
  EXPECT_DOUBLE_EQ(hi, 600);
  sc.static_tension = 500.4;  // the paper's drive: 2·500.4 N within 3 % of 1000 N
  default_range(sc, FrameQuantity::tension, lo, hi);
  EXPECT_DOUBLE_EQ(hi, 1000);
}

// values beyond the colour bar's ends are marked by a triangle at that end (the bar's bands and the elements' quads are
// the same in number whatever the range, so the marks are the only triangles a narrower range adds)
TEST_F(Fixture, ColourBarMarksValuesBeyondItsEnds) {
  const Scene& sc = wet();
  const Eigen::VectorXd y = test::moving_state(sc);
  auto build = [&](double lo, double hi, DrawList& dl) {
    FrameSettings f = fs();
    f.range_lo = lo, f.range_hi = hi;
    FrameBuilder(sc, f, &font).build(0.1, y.data(), dl);
  };
  DrawList all, above, both;
  build(-1e4, 1e4, all);
  double v_lo = INFINITY, v_hi = -INFINITY;
  for (const ElementDraw& el : all.elements) v_lo = std::min(v_lo, el.value), v_hi = std::max(v_hi, el.value);
  ASSERT_LT(v_lo + 10, v_hi);
  build(v_lo - 1, v_hi - 1, above);
  build(v_lo + 1, v_hi - 1, both);
  EXPECT_EQ(above.triangles.size(), all.triangles.size() + 3);
  EXPECT_EQ(both.triangles.size(), all.triangles.size() + 6);
}

// a pulley on a tensioner arm shows the arm's angle, one with a coupled rotor the rotor's speed;
// expected from the layout (the arm's angle is that of the pulley's centre seen from the pivot)
// and from the speed written into the state, not from the observables
// the driven pulley of d coupled to a rotor (2e-3 kg·m², 15 N·m/rad)
void add_rotor(SceneDef& d) {
  CouplingDef c;
  c.inertia = 2e-3;
  c.stiffness = 15;
  d.pulleys[1].coupling = c;
}

// the header's line of the pulley whose name starts it ("driven: ...")
std::string header_line(const DrawList& dl, const std::string& pulley) {
  for (const std::string& t : dl.texts)
    if (t.rfind(pulley + ": ", 0) == 0) return t;
  return std::string();
}

TEST_F(Fixture, HeaderShowsTheArmAngleAndTheRotorSpeed) {
  SceneDef d = presets::paper_dry();
  TensionerDef arm;
  arm.pivot = d.pulleys[1].centre + Vec2(0.06, 0.08);  // the arm at atan2(-0.08, -0.06) = -2.214 rad
  arm.inertia = 1e-3;
  arm.stiffness = 30;
  d.pulleys[1].tensioner = arm;
  add_rotor(d);
  const Scene sc = test::moving_scene(d);
  Eigen::VectorXd y = test::moving_state(sc);
  y[sc.model.n_coord() + sc.model.rotor_coord(0)] = -123.45;
  FrameBuilder b(sc, fs(), &font);
  DrawList dl;
  b.build(0.125, y.data(), dl);
  const std::string line = header_line(dl, "driven");
  const std::string arm_text = ", arm \u2212" + std::to_string(std::atan2(0.08, 0.06) - M_PI).substr(1, 5) + " rad";
  EXPECT_NE(line.find(arm_text), std::string::npos) << line << " lacks " << arm_text;
  EXPECT_NE(line.find(", rotor \u2212123.45 rad/s"), std::string::npos) << line;
  EXPECT_EQ(header_line(dl, "driver").find("arm"), std::string::npos) << header_line(dl, "driver");
}

// a caption (a mode's picture: render/mode_frames.cpp) heads the text band, before the time
TEST_F(Fixture, CaptionHeadsTheText) {
  const Scene& sc = wet();
  const Eigen::VectorXd y = test::moving_state(sc);
  FrameSettings f = fs();
  DrawList plain, captioned;
  FrameBuilder(sc, f, &font).build(0.125, y.data(), plain);
  f.caption = "mode 3: 134.01 Hz, \u03b6 0.0914";
  FrameBuilder(sc, f, &font).build(0.125, y.data(), captioned);
  auto head = [](const DrawList& dl) {
    for (const std::string& t : dl.texts)
      if (t.find("t = 0.1250 s") != std::string::npos) return t;
    return std::string();
  };
  EXPECT_EQ(head(plain).rfind("t = 0.1250 s", 0), 0u) << head(plain);
  EXPECT_EQ(head(captioned).rfind("mode 3: 134.01 Hz, \u03b6 0.0914      t = 0.1250 s", 0), 0u) << head(captioned);
}

// a mode's picture says how the mode moves each pulley (render/mode_frames.cpp), not a speed and a
// slip of the analysed state pushed by the mode's amplitude: the rigid rotation's picture said "off
// the belt" of pulleys the belt wraps (a user's trial). The rim's share of the mode's largest point
// displacement (the shape's 1 m) and its phase; the lines given take the speeds' and slips' place
TEST_F(Fixture, AModesPictureSaysHowTheModeMovesEachPulley) {
  const Scene& sc = wet();
  Mode m;
  m.shape = Eigen::VectorXcd::Zero(sc.model.n_coord());
  const Pulley &p0 = sc.model.pulleys[0], &p1 = sc.model.pulleys[1];
  m.shape[sc.model.pulley_coord(0)] = 1.0 / p0.radius;   // its rim moves by the largest point's 1 m
  m.shape[sc.model.pulley_coord(1)] = std::polar(0.5 / p1.radius, -M_PI / 2);  // half as far, a quarter turn behind
  const std::vector<std::string> lines = mode_pulley_lines(sc.model, m);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0], p0.name + ": rim 1.000 at +0\u00b0");
  EXPECT_EQ(lines[1], p1.name + ": rim 0.500 at \u221290\u00b0");
  const Eigen::VectorXd y = test::moving_state(sc);
  FrameSettings f = fs();
  f.pulley_lines = lines;
  DrawList dl;
  FrameBuilder(sc, f, &font).build(0.125, y.data(), dl);
  EXPECT_EQ(header_line(dl, p0.name), lines[0]);
  EXPECT_EQ(header_line(dl, p1.name), lines[1]);
}

// a mode's still is its largest deflection, where the tension change may reach a part of its
// cycle's largest: the caption then says how far (a user's trial read pale spans in the still as
// spans that do not stretch, where the video showed them at ±1); none where the colours reach the
// bar's ends
TEST(ModePictures, TheStillSaysHowFarItsColoursReach) {
  EXPECT_EQ(still_reach_text({0.1, -0.4, 0.25}), "colours here within \u00b10.40");
  EXPECT_EQ(still_reach_text({0.3, -0.97}), "");
  EXPECT_EQ(still_reach_text({1.0}), "");
}

// values the caller gives (a mode's change of tension: render/mode_frames.cpp) colour the belt in
// place of the quantity, on the diverging map over the range given, their name, unit and sign said
// in the text band, on the bar and in the legend; no element is past the bar's ends
TEST_F(Fixture, GivenValuesColourTheBeltWithTheirOwnBar) {
  const Scene& sc = wet();
  const Eigen::VectorXd y = test::moving_state(sc);
  const int n = sc.model.n_el();
  std::vector<double> values(n);
  for (int i = 0; i < n; ++i) values[i] = std::sin(2 * M_PI * i / n);
  FrameSettings f = fs();
  DrawList plain, given;
  FrameBuilder(sc, f, &font).build(0.125, y.data(), plain, nullptr, nullptr, &values);
  f.given = FrameSettings::Given{"tension change", "\u00d7 its largest", "+ : stretches"};
  f.range_lo = -1, f.range_hi = 1;
  const FrameBuilder b(sc, f, &font);
  b.build(0.125, y.data(), given, nullptr, nullptr, &values);
  EXPECT_EQ(b.scale().map, ColourMap::diverging);
  ASSERT_EQ(given.elements.size(), static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    EXPECT_EQ(given.elements[i].value, values[i]);
    EXPECT_NE(plain.elements[i].value, values[i]);  // (without their own bar, the quantity's)
  }
  auto has = [](const DrawList& dl, const std::string& part) {
    for (const std::string& t : dl.texts)
      if (t.find(part) != std::string::npos) return true;
    return false;
  };
  for (const char* t :
       {"colour: tension change [\u00d7 its largest]", "[\u00d7 its largest]", "+ : stretches", "\u22121.00", "1.00"})
    EXPECT_TRUE(has(given, t)) << t;
  EXPECT_FALSE(has(given, "belt tension"));
  EXPECT_FALSE(has(given, "+ : along travel"));
  // no mark of values past the bar's ends: values past both ends add one at each (3 triangles)
  std::vector<double> past = values;
  for (double& v : past) v *= 1.5;
  DrawList over;
  b.build(0.125, y.data(), over, nullptr, nullptr, &past);
  EXPECT_EQ(over.triangles.size(), given.triangles.size() + 6);
}

// a value that rounds to zero is written without a minus (issue 44: a frame's header read "slip
// -0.000 m/s" on an alternator whose belt and rim ran within 0.5 mm/s): a rotor at -1e-4 rad/s
// reads 0.00, one at -0.006 rad/s -0.01
TEST_F(Fixture, HeaderWritesNoMinusOnAZero) {
  SceneDef d = presets::paper_dry();
  add_rotor(d);
  const Scene sc = test::moving_scene(d);
  Eigen::VectorXd y = test::moving_state(sc);
  FrameBuilder b(sc, fs(), &font);
  auto driven_line = [&](double rotor_speed) {
    y[sc.model.n_coord() + sc.model.rotor_coord(0)] = rotor_speed;
    DrawList dl;
    b.build(0.125, y.data(), dl);
    return header_line(dl, "driven");
  };
  const std::string zero = driven_line(-1e-4), small = driven_line(-0.006);
  EXPECT_NE(zero.find(", rotor 0.00 rad/s"), std::string::npos) << zero;
  EXPECT_NE(small.find(", rotor \u22120.01 rad/s"), std::string::npos) << small;
}

TEST(Text, Utf8AndGlyphs) {
  EXPECT_EQ(decode_utf8("t = \u03c9 \u00d7"), std::u32string(U"t = \u03c9 \u00d7"));
  Font f;
  EXPECT_GT(f.width("t = 0.35 s", 18), 40);
  EXPECT_LT(f.width("t = 0.35 s", 18), 140);
  const Glyph& g = f.glyph(U'\u03c9', 18);
  EXPECT_GT(g.w, 4);
  EXPECT_GT(g.advance, 5);
}

}  // namespace
}  // namespace beltsim::render
