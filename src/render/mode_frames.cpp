#include "render/mode_frames.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <filesystem>
#include <regex>

#include "io/output_dir.hpp"
#include "media/png_writer.hpp"
#include "media/video_writer.hpp"
#include "render/recorder.hpp"

namespace beltsim::render {

namespace fs = std::filesystem;

namespace {

// a mode's files: mode_NN_<f>Hz.png and .mp4 (NN from 01, its number; f its frequency)
std::string mode_file_base(int k, double frequency) {
  char name[48];
  std::snprintf(name, sizeof name, "mode_%02d_%.1fHz", k + 1, frequency);
  return name;
}

bool is_mode_file(const std::string& name) {
  static const std::regex form(R"(mode_[0-9]{2,}_[0-9]+\.[0-9]Hz\.(png|mp4))");
  return std::regex_match(name, form);
}

// each element's change of tension at phase φ of the mode's cycle, between −1 and 1
std::vector<double> tension_at(const std::vector<std::complex<double>>& change, double phase) {
  std::vector<double> v(change.size());
  for (size_t k = 0; k < v.size(); ++k) v[k] = (change[k] * std::polar(1.0, phase)).real();
  return v;
}

}  // namespace

std::string still_reach_text(const std::vector<double>& at_still) {
  double reach = 0;
  for (double v : at_still) reach = std::max(reach, std::abs(v));
  if (!(reach < 0.95)) return "";
  char b[80];
  std::snprintf(b, sizeof b, "colours here within \u00b1%.2f", reach);
  return b;
}

// each pulley's line of a mode picture's text band: how the mode moves its rim (R·|shape| of its
// angle) and, on a tensioner arm, its centre (arm length·|shape| of the arm's angle), as shares of
// the mode's largest point displacement (the shape's scale: 1 m) and phases from that point's
// ("driver: rim 0.42 at +180°"). A speed and a slip there read the analysed state pushed by the
// mode's amplitude, no running drive's: the rigid rotation's picture said "off the belt" of
// pulleys the belt wraps (a user's trial)
std::vector<std::string> mode_pulley_lines(const Model& model, const Mode& m) {
  const auto share = [](std::complex<double> z, double arm) {
    char b[64];
    const double a = std::abs(z) * arm;
    if (a < 5e-4) return std::string("0.000");
    // the phase's sign as the frame's other numbers write it: U+2212 for a minus
    const double deg = std::round(std::arg(z) * 180 / M_PI);
    std::snprintf(b, sizeof b, "%.3f at %s%.0f\u00b0", a, deg < 0 ? "\u2212" : "+", std::abs(deg));
    return std::string(b);
  };
  std::vector<std::string> lines;
  for (int j = 0; j < model.n_p(); ++j) {
    const Pulley& p = model.pulleys[j];
    std::string line = p.name + ": rim " + share(m.shape[model.pulley_coord(j)], p.radius);
    if (p.arm >= 0) line += ", centre " + share(m.shape[model.arm_coord(p.arm)], model.arms[p.arm].length);
    lines.push_back(line);
  }
  return lines;
}

std::vector<std::string> draw_modes(const Scene& sc, const Drive& d, const Eigen::VectorXd& y, const ModeAnalysis& a,
                                    const ModePictures& p) {
  std::vector<std::string> written;
  const int count = std::min<int>(p.count, static_cast<int>(a.modes.size()));
  // an earlier analysis's pictures and videos go (of another time, or more modes): the folder holds
  // this one's, none when it draws none (the folder is then not made)
  std::error_code ec;
  if (count > 0 || fs::is_directory(fs::symlink_status(p.dir, ec))) remove_numbered(OutputDir(p.dir), is_mode_file);
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
  fs.given = FrameSettings::Given{"tension change", "\u00d7 its largest", "> 0: stretched"};
  fs.range_lo = -1, fs.range_hi = 1;
  FrameDrawer drawer(sc, fs);  // one GL context for every mode
  for (int k = 0; k < count; ++k) {
    const Mode& m = a.modes[k];
    const std::string base = (fs::path(p.dir) / mode_file_base(k, m.frequency)).string();
    char caption[96];
    std::snprintf(caption, sizeof caption, "mode %d: %.2f Hz, \u03b6 %.4f", k + 1, m.frequency, m.damping);
    drawer.set_pulley_lines(mode_pulley_lines(sc.model, m));
    const std::vector<std::complex<double>> change = mode_tension_change(sc, d, a.t, y, m);
    const Eigen::VectorXd peak = mode_state(y, m, amplitude, 0.0);
    const std::vector<double> at_peak = tension_at(change, 0.0);
    // the still is the largest deflection, where the tension change need not be at its largest
    // (a span's sideways swing and its pulleys' turning apart, a quarter cycle off): its caption
    // says how far the colours reach there, so that pale spans are not read as spans that do not
    // stretch (a user's trial: ±0.4 in the still, ±1 in the video)
    const std::string reach = still_reach_text(at_peak);
    drawer.set_caption(reach.empty() ? std::string(caption) : std::string(caption) + ", " + reach);
    write_png(base + ".png", drawer.draw(a.t, peak.data(), d, nullptr, &at_peak));
    drawer.set_caption(caption);
    written.push_back(base + ".png");
    if (!p.video) continue;
    constexpr int kPerCycle = 24, kCycles = 3;
    VideoOptions vo;
    vo.width = p.width;
    vo.height = p.height;
    vo.fps = kPerCycle;
    VideoWriter video(base + ".mp4", vo);
    for (int f = 0; f < kPerCycle * kCycles; ++f) {
      const double phase = 2 * M_PI * f / kPerCycle;
      const Eigen::VectorXd at = mode_state(y, m, amplitude, phase);
      const std::vector<double> values = tension_at(change, phase);
      video.add(drawer.draw(a.t, at.data(), d, nullptr, &values));
    }
    video.close();
    written.push_back(base + ".mp4");
  }
  return written;
}

}  // namespace beltsim::render
