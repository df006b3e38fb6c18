// The renderer as a run's frame observer: a FrameSink that builds the draw list of each frame,
// renders it on its GL context and hands the image to the PNG and video writers it was asked
// for. make_frame_recorder is the FrameSinkFactory the scripting layer gives to run().
#pragma once

#include <memory>
#include <string>

#include "media/image.hpp"
#include "render/draw_list.hpp"
#include "sim/frames.hpp"

namespace beltsim {
struct Scene;
}

namespace beltsim::render {

// Creates the GL context (BELTSIM_GL: osmesa or egl), the renderer and the writers. Throws
// std::runtime_error with a clear message when any of them cannot be created.
std::unique_ptr<FrameSink> make_frame_recorder(const Scene& scene, const FrameSettings& settings);

// Frames of one scene drawn one after another into images, with a GL context of its own: made,
// used and destroyed on one thread (a GL context is current on one thread; the live view's frame
// thread). The scene must outlive it. Throws std::runtime_error as make_frame_recorder does.
class FrameDrawer {
 public:
  FrameDrawer(const Scene& scene, const FrameSettings& settings);
  ~FrameDrawer();
  FrameDrawer(const FrameDrawer&) = delete;
  FrameDrawer& operator=(const FrameDrawer&) = delete;
  // the frame of state y at t with the drive's μ and spray zones; obs: what is observed there
  // (null: computed from y and the drive, whose laws it then evaluates); values: each element's
  // colour value when the settings give their own (FrameSettings::given)
  Image draw(double t, const double* y, const Drive& drive, const Observation* obs,
             const std::vector<double>* values = nullptr);
  // the title of the next frames' text band (FrameSettings::caption), the GL context kept
  void set_caption(const std::string& caption);
  // each pulley's line of the next frames' text band (FrameSettings::pulley_lines)
  void set_pulley_lines(const std::vector<std::string>& lines);
  // the elements as the last draw placed them (centres in pixels from the top left), by index
  const std::vector<ElementDraw>& drawn_elements() const;

 private:
  struct Parts;
  std::unique_ptr<Parts> p_;
};

// One frame of the state y at time t (drive: as it is now) written to a PNG file, with a GL
// context of its own (Lua sim:show). Throws std::runtime_error.
void render_snapshot(const Scene& scene, const FrameSettings& settings, double t, const double* y,
                     const Drive& drive, const std::string& png, const Observation* obs = nullptr);

}  // namespace beltsim::render
