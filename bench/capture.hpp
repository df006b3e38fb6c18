// A script's scene:run{} captured instead of run (script::Interpreter::set_capture): its scene and
// run settings, frames left out, for a benchmark to run as it measures. script: a path under the
// source folder; o: the command line's overrides (t_end, --set ...).
#pragma once

#include <stdexcept>
#include <string>

#include "script/interpreter.hpp"

namespace beltsim {

inline script::Captured capture_run(const std::string& script, script::Overrides o = {}) {
  script::Captured cap;
  script::Interpreter lua(script::Safety{});
  o.no_frames = true;
  lua.set_overrides(o);
  lua.set_capture(&cap);
  lua.run_file(BELTSIM_SOURCE_DIR "/" + script);
  if (!cap.scene) throw std::runtime_error(script + " never calls scene:run{}");
  return cap;
}

}  // namespace beltsim
