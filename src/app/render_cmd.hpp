// `beltsim render STATE... [--out PNG|DIR] [--video MP4]`: stored states (a checkpoint of sim:save,
// the states a run kept with keep_states) drawn by the renderer of a run's frames, with the run's
// frame settings or those given, so a picture (and a golden image of it) does not depend on
// integrating again, and frames can be made after the run. Exit status 0, 1 when a state cannot
// be read or a picture cannot be drawn or written (those written before are kept), 2 on bad usage,
// 130/143/129 when a stop signal ended it between two states (script/signals.hpp). The video is
// written whole (VideoOptions::whole): one that misses states is named NAME.partial.mp4.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace beltsim::app {

struct RenderOptions {
  std::vector<std::string> states;  // checkpoint files and/or folders of them
  std::optional<std::string> out, video;
  std::optional<std::string> quantity, size, view, magnify, range;
};

int cmd_render(const RenderOptions& o);

}  // namespace beltsim::app
