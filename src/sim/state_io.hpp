// A run's state (sim/sim_state.hpp) in a checkpoint's text (io/checkpoint_text.hpp): the one place
// where each part's plain data becomes lines and back, after the settings and the scene
// (sim/checkpoint.cpp, scene/scene_io.hpp). Four parts:
//
//   part drive        the drive now (scene_io.hpp: write_drive)
//   part schedule     now, each stream's and every-action's next index, each condition's value
//                     and located crossing, the timed μ changes still ahead
//   part outputs      rows, frames and the files' sizes and fingerprints (the last row's time,
//                     FNV-1a 64 of each file's bytes; from version 13); the interval means;
//                     callbacks, wall time
//   part integrator   the held step: its ends, their derivatives, step sizes, counters
//
// Reading checks what the text and the scene decide: every count against the lines holding it and
// the scene's sizes, every number's range, an event's time after now. Whether the state fits the
// run it is set into (a position of each stream at now, now inside the held step) is
// Simulation::set_state's to check; its StateError names the key, and CheckpointReader::line_of the
// line. Changing what is written here means raising kCheckpointVersion.
#pragma once

#include "io/checkpoint_text.hpp"
#include "scene/scene.hpp"
#include "sim/sim_state.hpp"

namespace beltsim {

void write_state(CheckpointWriter& w, const Model& m, const SimState& s);
// the state of a run of scene sc (refused: CheckpointError naming the line)
SimState read_state(CheckpointReader& r, const Scene& sc);

}  // namespace beltsim
