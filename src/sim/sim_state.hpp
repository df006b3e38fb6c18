// A run's state, as plain data (MuJoCo's mj_getState/mj_setState): everything a continuation
// needs to write the uninterrupted run's outputs and reach its state bit for bit, each part as the
// part itself exposes it. Simulation::get_state takes it, Simulation::set_state puts it back, and a
// checkpoint is the run's settings and scene with this state, in text (sim/state_io.hpp). The
// scene (the Model) never changes during a run and is not part of it; neither are the callbacks
// (Lua functions), which a script registers again.
#pragma once

#include <vector>

#include "integrate/integrator.hpp"
#include "integrate/timeline.hpp"
#include "model/drive.hpp"
#include "sim/interval_means.hpp"
#include "sim/outputs.hpp"
#include "sim/run_settings.hpp"

namespace beltsim {

struct SimState {
  Drive drive;                   // the laws and μ now, the spray records, the last restart's time
  std::vector<MuEvent> pending;  // timed μ changes still ahead
  Timeline::State schedule;      // now, the streams' and every-actions' next times, the conditions'
  IntegratorState integrator;    // the held step
  IntervalMeans::State means;    // the interval means' integrals so far
  Outputs::State outputs;        // rows and frames written, the files' sizes
  int callbacks = 0;             // the callbacks registered when it was taken (not themselves)
  double wall = 0;               // [s] integration wall time so far
  double now() const { return schedule.now; }
};

}  // namespace beltsim
