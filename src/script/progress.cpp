#include "script/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/duration_text.hpp"

namespace beltsim::script {

ProgressLine::ProgressLine(bool enabled, long steps_before, bool* ended)
    : enabled_(enabled), tty_(isatty(STDERR_FILENO)), steps_before_(steps_before), ended_(ended) {}

ProgressLine::~ProgressLine() {
  if (drawn_ && tty_) {
    std::fputc('\n', stderr);
    if (ended_) *ended_ = true;
  }
}

RunProgress ProgressLine::callback() {
  if (!enabled_) return {};
  return [this](double t, double target, const WorkCounters& w, double wall) {
    if (t0_ < 0) t0_ = t;
    // the integrator's last step may end past the target (the samples and callbacks up to the
    // target are read from its dense output): the line shows the run's progress, at most all of it
    t = std::min(t, target);
    if (wall < 1.0 || wall - last_ < (tty_ ? 0.5 : 10.0)) return;
    last_ = wall;
    drawn_ = true;
    const double done = t - t0_, todo = target - t;
    const double left = done > 0 ? std::max(0.0, wall * todo / done) : NAN;
    const double pct = target > t0_ ? 100 * done / (target - t0_) : 100;
    std::fprintf(stderr, "%sbeltsim: t = %.4f s of %.4g s (%.0f %%), %s elapsed, about %s left, %ld steps%s",
                 tty_ ? "\r" : "", t, target, pct, duration_text(wall).c_str(), duration_text(left).c_str(),
                 w.steps - steps_before_, tty_ ? "   " : "\n");
    std::fflush(stderr);
  };
}

}  // namespace beltsim::script
