// A friction law and a torque or speed law in a checkpoint's text (io/checkpoint_text.hpp), for
// the scene's and the drive's readers and writers (scene_io.hpp): one line per number, the keys
// under a prefix ("friction.dv 1e-05", "pulley.torque.constant 2", "pulley.torque.ramp ...").
#pragma once

#include <string>

#include "io/checkpoint_text.hpp"
#include "model/laws.hpp"
#include "model/model.hpp"

namespace beltsim {

inline constexpr size_t kFrictionLines = 9;  // the lines of one friction law

void write_friction(CheckpointWriter& w, const std::string& pre, const Friction& f);
Friction read_friction(CheckpointReader& r, const std::string& pre);

// a law held by Lua code cannot be written: std::runtime_error naming it
void write_law(CheckpointWriter& w, const TimeSpeedLaw& law, const std::string& k);
TimeSpeedLaw read_law(CheckpointReader& r, const std::string& k);

}  // namespace beltsim
