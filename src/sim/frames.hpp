// What a run is asked to draw (plain data, no GL): frames at fixed simulated times rendered by an
// observer that the engine knows only through FrameSink. The renderer (src/render, its own
// library) provides the sink; a run that asks for no frames never calls the factory, so it opens
// no GL context and no encoder (a scene pays only for what it uses).
#pragma once

#include <cmath>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "model/drive.hpp"
#include "model/model.hpp"
#include "model/observables.hpp"

namespace beltsim {

struct Scene;

// the quantity a frame colours the belt by
enum class FrameQuantity { tension, normal, friction, slip, mu };

struct FrameQuantityInfo {
  FrameQuantity q;
  const char* key;    // Lua name
  const char* label;  // colour-bar title
  const char* unit;
  bool is_signed;     // diverging colour map
};
const std::vector<FrameQuantityInfo>& frame_quantities();
const FrameQuantityInfo& frame_quantity_info(FrameQuantity q);

struct FrameSettings {
  double fps = 30;             // frames per second of video
  double slowdown = 10;        // seconds of video per simulated second (10: ten times slower than life)
  int width = 1280, height = 720;  // [px], even for a video (H.264 in yuv420p)
  FrameQuantity quantity = FrameQuantity::tension;
  std::optional<double> range_lo, range_hi;  // colour-bar range; unset: the quantity's default for the scene
  int levels = 10;             // colour bands (0: continuous)
  double magnify = 1;          // factor on the belt's deviation from its nominal path
  std::optional<Vec2> view_centre;   // [m] camera centre; unset: fit the layout
  std::optional<double> view_width;  // [m] visible width; unset: fit the layout
  std::string png_dir;         // "" : no PNG files; else frames as DIR/frame_00000.png ...
  int png_every = 1;           // a PNG of every n-th frame only (the video gets them all)
  std::string video_path;      // "" : no video; else an MP4 file
  double t_start = 0;          // [s] first frame time (frames at t_start + k / (fps·slowdown))
  long first_number = 0;       // number of the first frame written (a resumed run numbers on)
  // a title before the time in the text band (a mode's number and frequency,
  // render/mode_frames.cpp); "" none. Not a run's key, not in a checkpoint
  std::string caption;
  // the belt coloured by values the caller gives each picture (FrameDrawer::draw's `values`) in
  // place of `quantity`: their name and unit for the text band and the colour bar, on the diverging
  // map, and the legend's line saying what + is (a mode's tension change, render/mode_frames.cpp);
  // unset: the quantity. Not a run's key, not in a checkpoint
  struct Given {
    std::string label, unit, plus;
  };
  std::optional<Given> given;
  // each pulley's line of the text band in place of its speed and slip (how a mode moves it,
  // render/mode_frames.cpp: the mode's state is no running drive's); empty: the speeds and slips.
  // Not a run's key, not in a checkpoint
  std::vector<std::string> pulley_lines;
  // the frames a video is to have when it is written whole (beltsim render's, one per state):
  // named video_path when it has them all, else partial_video_path's name (media/video_writer.hpp:
  // a render stopped before its end), an earlier video_path left as it was; 0: written in place as
  // the frames come (a run's, whose fragments a kill leaves). Not a run's key, not in a checkpoint
  long video_whole_frames = 0;

  // simulated time between frames [s]
  double frame_dt() const { return 1.0 / (fps * slowdown); }
  // a picture is drawn (else the settings give only the times, for a run's kept states)
  bool draws() const { return !png_dir.empty() || !video_path.empty(); }
};

// An observer that turns states into pictures. frame() is called at t_start + k·frame_dt with the
// dense-output state and the drive as it is then (run events may change μ or a law while running);
// finish() finalises the outputs (also called when the run stops early: error, divergence,
// Ctrl-C).
class FrameSink {
 public:
  virtual ~FrameSink() = default;
  // obs: what is observed at t (sim/simulation.hpp Simulation::observation), or null to observe y
  virtual void frame(double t, const double* y, const Drive& drive, const Observation* obs = nullptr) = 0;
  virtual void finish() = 0;
  virtual long frames_written() const = 0;
};

using FrameSinkFactory =
    std::function<std::unique_ptr<FrameSink>(const Scene& scene, const FrameSettings& settings)>;

// The rules validate applies to a colour range, a magnify and a view's width, for a caller that
// names the setting its own way (render's --range): "" when the value is taken, else the reason.
std::string range_problem(double lo, double hi);
std::string magnify_problem(double magnify);
std::string view_width_problem(double width);

// Checks the settings (width and height in 16..8192, even with a video, fps in (0, 240], slowdown > 0,
// magnify > 0, a range with lo < hi, levels 0 or 2..64, png_every >= 1, a video's name ending in
// .mp4 and not png's folder's, at least one output unless times_only: the times of a run's kept
// states); throws std::invalid_argument "frames.KEY: reason
// (got value)".
void validate(const FrameSettings& f, bool times_only = false);

}  // namespace beltsim
