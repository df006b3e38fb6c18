// The paper's dry drive (support/presets.hpp), built once for every test of a program that runs it.
#pragma once

#include "scene/scene.hpp"
#include "support/presets.hpp"

namespace beltsim::test {

inline const Scene& dry_scene() {
  static const Scene sc = build_scene(presets::paper_dry());
  return sc;
}

}  // namespace beltsim::test
