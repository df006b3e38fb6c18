// One progress line on stderr for integrations that take more than a second: simulated time
// reached of the target, wall time, an estimate of what is left, the steps of this integration (as
// the call returns them: a simulation's steps before it, steps_before, are not counted). Redrawn in place on a
// terminal (every 0.5 s), a line every 10 s otherwise. Not part of the engine: the engine reports
// progress through a callback (sim/simulation.hpp RunProgress) and this prints it.
#pragma once

#include "sim/simulation.hpp"

namespace beltsim::script {

class ProgressLine {
 public:
  // ended: set when the destructor ends a line it drew (the console then knows the cursor is at a
  // line's start after a run that Ctrl-C stopped)
  explicit ProgressLine(bool enabled, long steps_before = 0, bool* ended = nullptr);
  ~ProgressLine();  // ends the line if one was drawn
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;
  RunProgress callback();

 private:
  bool enabled_, tty_, drawn_ = false;
  double last_ = 0, t0_ = -1;
  long steps_before_ = 0;
  bool* ended_ = nullptr;
};

}  // namespace beltsim::script
