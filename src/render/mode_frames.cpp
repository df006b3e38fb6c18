#include "render/mode_frames.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "media/png_writer.hpp"
#include "media/video_writer.hpp"
#include "render/recorder.hpp"

namespace beltsim::render {

namespace fs = std::filesystem;

std::vector<std::string> draw_modes(const Scene& sc, const Drive& d, const Eigen::VectorXd& y, const ModeAnalysis& a,
                                    const ModePictures& p) {
  std::vector<std::string> written;
  const int count = std::min<int>(p.count, static_cast<int>(a.modes.size()));
  if (count <= 0) return written;
  // the layout's size: the extent of the pulleys' rims
  Vec2 lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
  for (const Pulley& pl : sc.model.pulleys) {
    lo = lo.cwiseMin(pl.centre - Vec2::Constant(pl.radius));
    hi = hi.cwiseMax(pl.centre + Vec2::Constant(pl.radius));
  }
  const double amplitude = p.amplitude * (hi - lo).maxCoeff();
  FrameSettings fs;
  fs.width = p.width;
  fs.height = p.height;
  fs.png_dir = p.dir;  // (draws() only: the files are written here)
  FrameDrawer drawer(sc, fs);  // one GL context for every mode
  // (the folder is made by the first picture's writer, never through a link: io/output_dir.hpp)
  for (int k = 0; k < count; ++k) {
    const Mode& m = a.modes[k];
    char name[48];
    std::snprintf(name, sizeof name, "mode_%02d_%.1fHz", k + 1, m.frequency);
    const std::string base = (fs::path(p.dir) / name).string();
    char caption[96];
    std::snprintf(caption, sizeof caption, "mode %d: %.2f Hz, \u03b6 %.4f", k + 1, m.frequency, m.damping);
    drawer.set_caption(caption);
    const Eigen::VectorXd peak = mode_state(y, m, amplitude, 0.0);
    write_png(base + ".png", drawer.draw(a.t, peak.data(), d, nullptr));
    written.push_back(base + ".png");
    if (!p.video) continue;
    constexpr int kPerCycle = 24, kCycles = 3;
    VideoOptions vo;
    vo.width = p.width;
    vo.height = p.height;
    vo.fps = kPerCycle;
    VideoWriter video(base + ".mp4", vo);
    for (int f = 0; f < kPerCycle * kCycles; ++f) {
      const Eigen::VectorXd at = mode_state(y, m, amplitude, 2 * M_PI * f / kPerCycle);
      video.add(drawer.draw(a.t, at.data(), d, nullptr));
    }
    video.close();
    written.push_back(base + ".mp4");
  }
  return written;
}

}  // namespace beltsim::render
