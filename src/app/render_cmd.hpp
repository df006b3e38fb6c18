// `beltsim render CHECKPOINT --out PNG`: the state a checkpoint holds (sim:save) drawn by the
// renderer of a run's frames, with the run's frame settings or those given, so a picture (and a
// golden image of it) does not depend on integrating again. Exit status 0, 1 when the checkpoint
// cannot be read or the picture cannot be drawn or written, 2 on bad usage.
#pragma once

#include <optional>
#include <string>

namespace beltsim::app {

struct RenderOptions {
  std::string checkpoint, out;
  std::optional<std::string> quantity, size, view, magnify, range;
};

int cmd_render(const RenderOptions& o);

}  // namespace beltsim::app
