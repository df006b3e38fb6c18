// The scenes the tests and benchmarks build in C++. The paper's drive is scripts/paper_dry.lua's,
// read through the interpreter as `beltsim run` reads it (its first beltsim.scene{} captured, nothing
// built): the script is its one definition. The automotive drive is tests/support/automotive.lua's,
// which the Lua tests' scripts use too.
#pragma once

#include <string>
#include <vector>

#include "scene/scene.hpp"

namespace beltsim::presets {

// the definition of the script's first beltsim.scene{}, with --set KEY=VALUE
// values; throws std::runtime_error naming the script when it cannot give one
SceneDef script_scene(const std::string& script, const std::vector<std::string>& set = {});

// Two-pulley drive of paper §3 (scripts/paper_dry.lua): driver at the origin, driven at (0.29, 0),
// r = 0.1 m, 60 elements, 500 N, belt travelling clockwise; M_d1 = -70·min(t/0.3, 1) N·m,
// M_d2 = -0.955·Ω N·m; without the energy the script tracks (the state is the belt's and pulleys')
SceneDef paper_dry();
// The same with μ = 0.2 on the half of the belt whose centres start at x > l_p/2.
SceneDef paper_wet();
// The automotive drive of paper §4 with our layout (docs/model.md, Our choices) (crankshaft, tensioner, alternator,
// pump), 150 elements, 280 N; wet 30 % of the belt ending where it leaves the pump.
SceneDef automotive_wet();
// The same drive dry, with the idler on a tensioner arm pivoted at (0.075, -0.14) (arm 63 mm):
// 1e-3 kg·m², 30 N·m/rad, damping 0.05 N·m·s/rad, friction torque 0.5 N·m; the spring's free
// angle holds the belt's 280 N (scripts/automotive_tensioner.lua describes the same arm).
SceneDef automotive_tensioner();
// The automotive drive's layout (automotive_wet's, dry, the idler fixed) as an accessory drive
// at the speed of scripts/automotive_tensioner.lua without its pulsation: the crankshaft
// kinematic, a cosine ramp to crank_rpm clockwise over 0.05 s; the alternator loaded with
// -0.01 N·m·s/rad, the pump with -0.05 N·m·s/rad (1.33 kW in all at 800 rpm); the paper's belt,
// 150 elements at 280 N.
SceneDef automotive_accessories(double crank_rpm = 800);

}  // namespace beltsim::presets
