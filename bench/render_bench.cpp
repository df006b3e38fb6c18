// Frame throughput at 1280×720 on the paper's dry drive: the frames of a real run from 0.05 to
// 0.25 s at the paper_dry.lua frame rate (1/300 s apart), cycled, so that the encoder sees the
// motion it sees in a run (identical frames would encode for almost nothing):
//   BM_FrameRender      draw list + GL render (4× MSAA, llvmpipe) + read-back
//   BM_FrameRenderPng   the same + a PNG file (libpng, zlib level 3)
//   BM_FrameRenderH264  the same + one H.264 frame (libx264 superfast, crf 23, fragmented MP4)
//   BM_FrameRenderMsaa4 render only, with 4× MSAA on top of the analytic antialiasing (the
//                       alternative we did not take: 3× the cost on llvmpipe)
// The counter frames/s is what a run with frames spends per frame beside the integration.
//   build/bench/beltsim_bench --benchmark_filter=Frame
#include <benchmark/benchmark.h>

#include <cstdio>
#include <filesystem>

#include "integrate/belt_system.hpp"
#include "integrate/driver.hpp"
#include "integrate/stepper.hpp"
#include "media/png_writer.hpp"
#include "media/video_writer.hpp"
#include "render/draw_list.hpp"
#include "render/gl_renderer.hpp"
#include "render/text.hpp"
#include "support/presets.hpp"

namespace beltsim {
namespace {

struct Setup {
  Scene sc = build_scene(presets::paper_dry());
  std::vector<double> t;
  std::vector<Eigen::VectorXd> y;
  FrameSettings fs;
  render::Font font;
  std::unique_ptr<render::GlContext> ctx = render::make_gl_context(render::default_gl_backend());
  std::unique_ptr<render::GlRenderer> gl, gl_msaa;
  Setup() {
    BeltSystem sys(sc.model, sc.drive);
    auto st = make_stepper("esdirk32");
    DriveOptions o;
    o.t_end = 0.25, o.sample_dt = 0.25, o.events = sc.drive.breakpoints();
    o.streams.push_back(
        {0.05, 1.0 / 300, [&](double tf, const Eigen::VectorXd& yf) { t.push_back(tf), y.push_back(yf); }});
    Eigen::VectorXd y0 = sc.y0;
    drive(sys, *st, Tolerances{1e-5, -1}, o, y0, [](double, const Eigen::VectorXd&) {});
    fs.width = 1280, fs.height = 720, fs.magnify = 10, fs.png_dir = std::string(1, 'x');  // not = "x": GCC 12 -O3 gives a false -Wrestrict there (GCC PR 105329)
    gl = std::make_unique<render::GlRenderer>(*ctx, fs.width, fs.height);
    gl_msaa = std::make_unique<render::GlRenderer>(*ctx, fs.width, fs.height, 4);
  }
};

Setup& setup() {
  static Setup s;
  return s;
}

enum Sink { none, png, h264, msaa };

void run(benchmark::State& state, Sink sink) {
  Setup& s = setup();
  render::FrameBuilder b(s.sc, s.fs, &s.font);
  render::DrawList dl;
  Image img;
  const std::string dir = std::filesystem::temp_directory_path().string();
  std::unique_ptr<VideoWriter> video;
  if (sink == h264) video = std::make_unique<VideoWriter>(dir + "/beltsim_bench.mp4", VideoOptions{});
  long k = 0;
  for (auto _ : state) {
    const size_t i = static_cast<size_t>(k) % s.y.size();
    b.build(s.t[i], s.y[i].data(), dl);
    (sink == msaa ? s.gl_msaa : s.gl)->render(dl, img);
    if (sink == png) write_png(dir + "/beltsim_bench.png", img);
    if (sink == h264) video->add(img);
    k++;
  }
  if (video) video->close();  // the encoder's look-ahead frames are flushed inside the timing
  state.counters["frames/s"] = benchmark::Counter(static_cast<double>(k), benchmark::Counter::kIsRate);
}

void BM_FrameRender(benchmark::State& st) { run(st, none); }
void BM_FrameRenderPng(benchmark::State& st) { run(st, png); }
void BM_FrameRenderH264(benchmark::State& st) { run(st, h264); }
void BM_FrameRenderMsaa4(benchmark::State& st) { run(st, msaa); }
BENCHMARK(BM_FrameRender)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FrameRenderPng)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FrameRenderH264)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_FrameRenderMsaa4)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
}  // namespace beltsim
