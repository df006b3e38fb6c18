// The paper's dry drive (scene/presets.hpp), built once for every test of a program that runs it.
#pragma once

#include "scene/presets.hpp"
#include "scene/scene.hpp"

namespace beltsim::test {

inline const Scene& dry_scene() {
  static const Scene sc = build_scene(presets::paper_dry());
  return sc;
}

}  // namespace beltsim::test
