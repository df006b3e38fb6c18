// A built Scene, and a Drive (what a run changes: laws, μ), in a checkpoint's text
// (io/checkpoint_text.hpp: the format, its one version, its strict reader). The keys are the
// scenario's Lua names, the parameter table's (scene/parameters.hpp), where the scenario has one
// (pulley.inertia, belt.sde.k, contact.damping, friction.dv, energy); the values a build derives
// (belt.pitch, the route, the element sites) carry the names of scene:info() and of the element
// sites. The scene's inputs (parameters.csv's first rows) are kept as name, value and whether
// given; their units and notes come from the table, and a name the table lacks is refused.
//
// Reading checks as it goes that every count fits the text that holds it and the scene it
// belongs to (the pulleys, the elements, the state's size), then validates the scene as a
// script's scene is validated (validate(SceneDef), validate.hpp) and the drive with the same rules
// (validate_law, μ >= 0 per element). Errors are CheckpointError ("line N: ...") for the text and
// for what a single line gets wrong, and CheckpointError naming the lines of the scene for what
// the validation refuses.
//
// The fields of each struct are listed once, in scene/scene_fields.hpp: the writer, the reader,
// the definition a scene gives back and the comparison of two scenes all follow those lists.
// Adding a field means adding it there and raising kCheckpointVersion.
#pragma once

#include "io/checkpoint_text.hpp"
#include "model/model.hpp"
#include "scene/scene.hpp"

namespace beltsim {

void write_scene(CheckpointWriter& w, const Scene& sc);
// the definition a built scene gives back: what the scenario gave that the scene keeps (the
// pulleys, arms, couplings, the belt per SDE and by its rest length, mass per rest length, μ per
// element, contact per element, friction, spray zones); what validate(SceneDef) checks of a
// script's scene it checks of a checkpoint's. allow_large is set: the file's size bounds a scene read.
SceneDef definition(const Scene& sc);
Scene read_scene(CheckpointReader& r);

// the drive: each pulley's torque and speed laws and which of them drives it, μ per element,
// the time of the last restart
void write_drive(CheckpointWriter& w, const Model& m, const Drive& d);
// the drive of the model's scene (its pulleys' names, its element count): validated
Drive read_drive(CheckpointReader& r, const Model& m);

// the key of the first field in which two scenes (two drives) differ, bit for bit ("belt.sde.k",
// "pulley.centre [1]"), "" when they are the same in every field a checkpoint holds
std::string scene_difference(const Scene& a, const Scene& b);
std::string drive_difference(const Drive& a, const Drive& b);

}  // namespace beltsim
