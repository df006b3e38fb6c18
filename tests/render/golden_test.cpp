// Golden images: small deterministic frames rendered with OSMesa (llvmpipe, pinned by the test's
// GALLIUM_DRIVER=llvmpipe) compared with tests/golden/*.png by the goldens' metric (media/image_compare.hpp,
// also `beltsim compare`): a pixel differs when any channel differs by more than 16 of 255 levels;
// an image fails when more than 12 pixels differ. The tests below check that the metric catches a
// colour map one band off and an element shifted by half its thickness. A FreeType or font upgrade
// that moves glyphs is a real change of the picture: update the goldens (below), or add an
// alternate NAME_1.png beside NAME.png (accepted as well, as VTK does).
// On failure the actual image and a difference image (differing pixels red on grey) are
// written to the build tree (tests/golden_out/). To update the goldens on purpose:
//   ninja -C build update_golden    (this program with BELTSIM_UPDATE_GOLDEN=1; ctest unsets it)
// (only the goldens the new images fail, or missing ones, are rewritten), then look at the new
// tests/golden/*.png before committing them.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include <cmath>

#include "media/image_compare.hpp"
#include "media/png_writer.hpp"
#include "plot/plot.hpp"
#include "render/recorder.hpp"
#include "sim/simulation.hpp"
#include "render/draw_list.hpp"
#include "render/gl_context.hpp"
#include "render/gl_renderer.hpp"
#include "render/render_scenes.hpp"
#include "render/text.hpp"

namespace beltsim::render {
namespace {

namespace fs = std::filesystem;

constexpr int kLevelTol = ImageTolerance{}.level_tol;
constexpr long kMaxBadPixels = ImageTolerance{}.max_bad_pixels;

ImageComparison compare(const Image& a, const Image& b) { return compare_images(a, b, kLevelTol); }

// one context and renderer per size for the whole test program
class Golden : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ctx_ = make_gl_context(GlBackend::osmesa).release();
    gl_ = new GlRenderer(*ctx_, kW, kH);
    std::printf("GL_RENDERER = %s\nGL_VERSION = %s\nfont = %s\n", gl_->gl_renderer().c_str(),
                gl_->gl_version().c_str(), Font::default_path().c_str());
    font_ = new Font();
  }
  static void TearDownTestSuite() {
    delete gl_;
    delete ctx_;
    delete font_;
  }
  static Image render(const Scene& sc, const FrameSettings& fs, const Eigen::VectorXd& y,
                      void (*mutate)(DrawList&) = nullptr) {
    FrameBuilder b(sc, fs, font_);
    DrawList dl;
    b.build(0.25, y.data(), dl);
    if (mutate) mutate(dl);
    Image img;
    gl_->render(dl, img);
    return img;
  }
  static FrameSettings settings(FrameQuantity q) {
    FrameSettings fs;
    fs.width = kW, fs.height = kH, fs.quantity = q;
    fs.png_dir = "unused";
    return fs;
  }
  // compares with tests/golden/NAME.png (or its alternate NAME_1.png). With BELTSIM_UPDATE_GOLDEN=1
  // a golden the image fails (or a missing one) is rewritten; one it passes is left as it is, so
  // that an update changes only the pictures that changed (llvmpipe's level or two of noise
  // would otherwise give every golden new bytes)
  static void expect_golden(const std::string& name, const Image& img) {
    const fs::path golden = fs::path(BELTSIM_SOURCE_DIR) / "tests" / "golden" / (name + ".png");
    const fs::path out = fs::path(BELTSIM_BINARY_DIR) / "tests" / "golden_out";
    const char* u = std::getenv("BELTSIM_UPDATE_GOLDEN");
    const bool update = u && std::string(u) == "1";
    if (update && !fs::exists(golden)) {
      write_png(golden.string(), img);
      GTEST_SKIP() << "created " << golden.string() << ": nothing compared";
    }
    ASSERT_TRUE(fs::exists(golden)) << golden << " missing: ninja -C build update_golden creates it";
    ImageComparison best = compare(img, read_png(golden.string()));
    const fs::path alt = golden.parent_path() / (name + "_1.png");
    if (best.bad > kMaxBadPixels && fs::exists(alt)) {
      ImageComparison c = compare(img, read_png(alt.string()));
      if (c.bad < best.bad) best = std::move(c);
    }
    if (update) {
      if (best.bad <= kMaxBadPixels) GTEST_SKIP() << "kept " << golden.string() << ": " << best.bad << " pixels differ";
      write_png(golden.string(), img);
      GTEST_SKIP() << "updated " << golden.string() << ": " << best.bad << " pixels differed";
    }
    if (best.bad > kMaxBadPixels) {
      fs::create_directories(out);
      write_png((out / (name + "_actual.png")).string(), img);
      if (best.diff.width) write_png((out / (name + "_diff.png")).string(), best.diff);
    }
    EXPECT_LE(best.bad, kMaxBadPixels) << name << ": " << best.bad << " pixels differ by more than " << kLevelTol
                                       << " levels (largest difference " << best.worst << "); actual and difference"
                                       << " images in " << out;
  }

  static constexpr int kW = 640, kH = 360;
  static GlContext* ctx_;
  static GlRenderer* gl_;
  static Font* font_;
};
GlContext* Golden::ctx_ = nullptr;
GlRenderer* Golden::gl_ = nullptr;
Font* Golden::font_ = nullptr;

const Scene& dry() {
  static const Scene sc = test::moving_scene(presets::paper_dry());
  return sc;
}
const Scene& live_scene() {
  static const Scene sc = build_scene(presets::paper_dry());
  return sc;
}
const Scene& wet() {
  static const Scene sc = test::moving_scene(presets::paper_wet());
  return sc;
}

TEST_F(Golden, DryTensionMagnified) {
  FrameSettings fs = settings(FrameQuantity::tension);
  fs.magnify = 20;
  expect_golden("dry_tension", render(dry(), fs, test::moving_state(dry())));
}

TEST_F(Golden, WetSlip) {
  FrameSettings fs = settings(FrameQuantity::slip);
  fs.range_lo = -0.08, fs.range_hi = 0.08;
  expect_golden("wet_slip", render(wet(), fs, test::moving_state(wet())));
}

// zoomed on the driven pulley's slip arc: the belt runs under the text band and the colour-bar
// panel, whose text stands on boxes; the arrow of travel sits beside the visible belt
TEST_F(Golden, WetSlipZoomed) {
  FrameSettings fs = settings(FrameQuantity::slip);
  fs.range_lo = -0.08, fs.range_hi = 0.08;
  fs.view_centre = Vec2(0.33, 0.05), fs.view_width = 0.15;
  expect_golden("wet_slip_zoomed", render(wet(), fs, test::moving_state(wet())));
}

TEST_F(Golden, WetFriction) {
  FrameSettings fs = settings(FrameQuantity::friction);
  expect_golden("wet_friction", render(wet(), fs, test::moving_state(wet())));
}

// sim:show and sim:plot: a live simulation of the dry drive paused at 0.02 s with a wet stretch,
// drawn by render_snapshot (what sim:show calls) and its time histories so far by plot_csv (what
// sim:plot and `beltsim plot` call, through gnuplot's pngcairo)
TEST_F(Golden, LiveShowAndPlot) {
  const fs::path out = fs::path(BELTSIM_BINARY_DIR) / "tests" / "golden_live";
  fs::remove_all(out);
  RunSettings rs;
  rs.out_dir = out.string();
  Simulation sim(live_scene(), rs);
  sim.run_to(0.01);
  std::vector<double> mu(sim.model().n_el(), std::nan(""));
  for (int i = 0; i < 12; ++i) mu[i] = 0.2;
  sim.set_mu(mu, "wet", "golden");
  sim.run_to(0.02);
  FrameSettings fs = settings(FrameQuantity::mu);
  render_snapshot(sim.scene(), fs, sim.now(), sim.state().data(), sim.drive(), (out / "show.png").string(),
                  &sim.observation());
  ctx_->make_current();  // the snapshot made a context of its own
  expect_golden("live_show", read_png((out / "show.png").string()));
  sim.close();
  plot::plot_csv(sim.csv_path(), {"driver.omega", "driven.omega", "probe.sde_force"}, 0.0, (out / "plot.png").string());
  expect_golden("live_plot", read_png((out / "plot.png").string()));
}

// The comparison must catch a deliberately wrong picture. These compare renderings against the
// correct rendering of the same frame (not against the files, so they hold whatever the goldens).
TEST_F(Golden, ColourMapOneBandOffFails) {
  FrameSettings fs = settings(FrameQuantity::tension);
  fs.magnify = 20;
  fs.range_lo = 0, fs.range_hi = 1000;
  const Eigen::VectorXd y = test::moving_state(dry());
  const Image good = render(dry(), fs, y);
  // the same frame with every element coloured one band higher
  fs.range_lo = 0 - 1000.0 / fs.levels, fs.range_hi = 1000 - 1000.0 / fs.levels;
  const Image shifted = render(dry(), fs, y);
  const ImageComparison c = compare(good, shifted);
  EXPECT_GT(c.bad, 50 * kMaxBadPixels) << "a colour map one band off must fail (" << c.bad << " pixels)";
  std::printf("colour map one band off: %ld pixels differ\n", c.bad);
}

TEST_F(Golden, ShiftedElementFails) {
  FrameSettings fs = settings(FrameQuantity::tension);
  fs.magnify = 20;
  const Eigen::VectorXd y = test::moving_state(dry());
  const Image good = render(dry(), fs, y);
  // element 10 moved outwards by half the belt's drawn thickness
  Eigen::VectorXd y2 = y;
  const Vec2 e = axis(y[3 * 10 + 2]);
  const Vec2 shift = 2.25e-3 / fs.magnify * perp(e);  // magnified to half the drawn thickness
  y2[30] += shift.x(), y2[31] += shift.y();
  const ImageComparison c = compare(good, render(dry(), fs, y2));
  EXPECT_GT(c.bad, kMaxBadPixels) << "an element shifted by half its thickness must fail (" << c.bad << " pixels)";
  std::printf("shifted element: %ld pixels differ\n", c.bad);
}

// A belt of 2 400 elements, a quarter of a pixel each at this size: the colour the elements carry
// is what the belt shows, not the dark joints between them (drawn at every element they covered
// the belt with a moiré of dashes: the pixels at the elements' centres were the joints' colour
// almost everywhere). Each element's centre pixel is within 40 levels of its colour.
TEST_F(Golden, FineBeltShowsItsColours) {
  SceneDef def = presets::paper_dry();
  def.belt.elements = 2400;
  const Scene sc = test::moving_scene(def);
  const FrameSettings fs = settings(FrameQuantity::tension);
  FrameBuilder b(sc, fs, font_);
  DrawList dl;
  const Eigen::VectorXd y = test::moving_state(sc);
  b.build(0.25, y.data(), dl);
  Image img;
  gl_->render(dl, img);
  int near = 0;
  for (const ElementDraw& el : dl.elements) {
    const std::uint8_t* p = img.pixel(static_cast<int>(el.centre.x()), static_cast<int>(el.centre.y()));
    const float c[3] = {el.colour.r, el.colour.g, el.colour.b};
    bool close = true;
    for (int k = 0; k < 3; ++k) close = close && std::abs(p[k] - 255.0 * c[k]) <= 40;
    near += close;
  }
  EXPECT_GE(near, 0.9 * static_cast<double>(dl.elements.size())) << near << " of " << dl.elements.size();
}

// The second backend (EGL on Mesa's surfaceless platform, for Mesa >= 25.1 without OSMesa) draws
// the same pixels as OSMesa (both are llvmpipe here: measured identical). Skipped, saying why,
// where no EGL context can be made.
TEST_F(Golden, EglDrawsWhatOsMesaDraws) {
  FrameSettings fs = settings(FrameQuantity::friction);
  const Eigen::VectorXd y = test::moving_state(wet());
  const Image osmesa = render(wet(), fs, y);
  std::unique_ptr<GlContext> egl;
  try {
    egl = make_gl_context(GlBackend::egl);
  } catch (const std::exception& e) {
    GTEST_SKIP() << e.what();
  }
  Image img;
  {
    GlRenderer r(*egl, kW, kH);
    std::printf("EGL: GL_RENDERER = %s\n", r.gl_renderer().c_str());
    FrameBuilder b(wet(), fs, font_);
    DrawList dl;
    b.build(0.25, y.data(), dl);
    r.render(dl, img);
  }
  egl.reset();
  ctx_->make_current();  // back to the suite's OSMesa context
  const ImageComparison c = compare(osmesa, img);
  EXPECT_LE(c.bad, kMaxBadPixels) << c.bad << " pixels differ (largest difference " << c.worst << ")";
}

// A context that cannot be made gives a message naming the backend, the version and what to do
// (OSMesa of Mesa 22.3 makes no 4.6 core context).
TEST_F(Golden, FailedContextSaysWhy) {
  try {
    make_gl_context(GlBackend::osmesa, 4, 6);
    GTEST_SKIP() << "this OSMesa makes 4.6 core contexts: nothing to fail";
  } catch (const std::runtime_error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("cannot create an OpenGL 4.6 core context with OSMesa"), std::string::npos) << m;
    EXPECT_NE(m.find("libosmesa6"), std::string::npos) << m;
    EXPECT_NE(m.find("BELTSIM_GL=egl"), std::string::npos) << m;
  }
  ctx_->make_current();
}

}  // namespace
}  // namespace beltsim::render
