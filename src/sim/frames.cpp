#include "sim/frames.hpp"

#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "io/number_text.hpp"
#include "io/output_dir.hpp"
#include "scene/validate.hpp"

namespace beltsim {

const std::vector<FrameQuantityInfo>& frame_quantities() {
  static const std::vector<FrameQuantityInfo> q{
      {FrameQuantity::tension, "tension", "belt tension", "N", false},
      {FrameQuantity::normal, "normal", "normal force", "N", false},
      {FrameQuantity::friction, "friction", "friction force", "N", true},
      {FrameQuantity::slip, "slip", "slip velocity", "m/s", true},
      {FrameQuantity::mu, "mu", "friction coeff. \u03bc", "", false},
  };
  return q;
}

const FrameQuantityInfo& frame_quantity_info(FrameQuantity q) {
  for (const auto& i : frame_quantities())
    if (i.q == q) return i;
  return frame_quantities().front();
}

namespace {
template <class T>
[[noreturn]] void bad(const std::string& key, const std::string& reason, const T& value, const char* unit = "") {
  std::string got;
  if constexpr (std::is_floating_point_v<T>)
    got = rounded_text(value);
  else if constexpr (std::is_integral_v<T>)
    got = std::to_string(value);
  else
    got = value;
  throw ParameterError("frames." + key, reason + " (got " + got + unit + ")");
}
// a and b name one place, as text ("frames" and "./frames/")
bool same_path(const std::string& a, const std::string& b) {
  auto normal = [](const std::string& p) {
    std::string n = std::filesystem::path(p).lexically_normal().string();
    while (n.size() > 1 && n.back() == '/') n.pop_back();
    return n;
  };
  return normal(a) == normal(b);
}
}  // namespace

std::string range_problem(double lo, double hi) {
  if (!std::isfinite(lo) || !std::isfinite(hi)) return "must be finite";
  return lo < hi ? "" : "needs lo < hi";
}

std::string magnify_problem(double magnify) {
  return magnify > 0 && magnify <= 1e4 ? "" : "must be in (0, 1e4]";
}

// a view narrower than a micrometre shows nothing one could read; wider than 100 km, likewise
std::string view_width_problem(double width) {
  return width >= 1e-6 && width <= 1e5 ? "" : "must be in [1e-6, 1e5] m";
}

void validate(const FrameSettings& f, bool times_only) {
  if (!(f.fps > 0 && f.fps <= 240)) bad("fps", "must be in (0, 240]", f.fps);
  if (f.fps != std::floor(f.fps)) bad("fps", "must be a whole number of frames per second", f.fps);
  if (!(f.slowdown > 0 && f.slowdown < 1e9)) bad("slowdown", "must be > 0 video seconds per simulated second", f.slowdown);
  // odd sizes are a video's problem only (H.264 in yuv420p halves each chroma plane); a PNG takes any
  const bool video = !f.video_path.empty();
  for (int v : {f.width, f.height})
    if (v < 16 || v > 8192 || (video && v % 2)) {
      bad("size",
          video ? "width and height must be even and in 16..8192 px (H.264 in yuv420p)"
                : "width and height must be in 16..8192 px",
          std::to_string(f.width) + "x" + std::to_string(f.height));
    }
  if (f.range_lo && f.range_hi)
    if (const std::string why = range_problem(*f.range_lo, *f.range_hi); !why.empty())
      bad("range", why, "{" + rounded_text(*f.range_lo) + ", " + rounded_text(*f.range_hi) + "}");
  if (!(f.levels == 0 || (f.levels >= 2 && f.levels <= 64))) bad("levels", "must be 0 (continuous) or 2..64", f.levels);
  if (const std::string why = magnify_problem(f.magnify); !why.empty()) bad("magnify", why, f.magnify);
  if (f.view_width)
    if (const std::string why = view_width_problem(*f.view_width); !why.empty())
      bad("view.width", why, *f.view_width, " m");
  if (f.range_lo && !std::isfinite(*f.range_lo)) bad("range", "must be finite", *f.range_lo);
  if (f.range_hi && !std::isfinite(*f.range_hi)) bad("range", "must be finite", *f.range_hi);
  if (f.png_every < 1) bad("png_every", "must be >= 1", f.png_every);
  if (!(f.t_start >= 0 && std::isfinite(f.t_start))) bad("t_start", "must be >= 0 and finite", f.t_start, " s");
  if (video && !f.png_dir.empty() && same_path(f.video_path, f.png_dir))
    bad("video", "the same name as png's folder of PNGs: the two names collide (give the video a name of its own)",
        f.video_path);
  if (const std::string why = video ? video_name_problem(f.video_path) : ""; !why.empty())
    bad("video", why, f.video_path);
  if (!times_only && !f.draws())
    bad("png", "neither png nor video asked for: nothing to write (keep_states = true keeps the states at these times)",
        std::string("none"));
}

}  // namespace beltsim
