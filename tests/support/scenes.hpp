// The test scenes in Lua, one definition for every test that runs one.
//
// two_pulley: the paper's two-pulley drive (scripts/paper_dry.lua's geometry: two pulleys of
// 0.1 m, 0.29 m apart, the belt at 500 N turning clockwise), with what a test varies. Its text
// has 7 lines (8 with `extra`): a script's next line is line 8 (9), which the tests' expected
// messages name.
//
// runaway: a frictionless belt leaves the driver free to spin up under 1e6 N·m (4e7 rad/s² on
// 0.025 kg·m²), past the runaway check (1e5 rad/s) after 2.5 ms; 7 lines.
#pragma once

#include <string>

namespace beltsim::test {

struct TwoPulley {
  std::string assign = "local s = ";                        // what the scene's value goes to
  std::string driver = "torque = beltsim.ramp(0.3, -70)";   // the driver's keys after its geometry
  std::string driven_at = "centre = {0.29, 0}, radius = 0.1";
  std::string driven = "torque = { per_speed = -0.955 }";  // the driven pulley's keys after its geometry
  int elements = 40;
  std::string belt;   // more keys of the belt table
  std::string extra;  // a line of more keys of the scene table
};

inline std::string two_pulley(const TwoPulley& p = {}) {
  return p.assign + "beltsim.scene {\n"
         "  pulleys = {\n"
         "    { name = 'driver', centre = {0, 0}, radius = 0.1, " + p.driver + " },\n"
         "    { name = 'driven', " + p.driven_at + ", " + p.driven + " },\n"
         "  },\n"
         "  belt = { elements = " + std::to_string(p.elements) + ", pretension = 500, direction = 'cw'" +
         (p.belt.empty() ? "" : ", " + p.belt) + " },\n" +
         (p.extra.empty() ? "" : "  " + p.extra + "\n") + "}\n";
}

inline std::string runaway() {
  return "local s = beltsim.scene {\n"
         "  pulleys = {\n"
         "    { name = 'driver', centre = {0, 0}, radius = 0.1, torque = 1e6 },\n"
         "    { name = 'driven', centre = {0.29, 0}, radius = 0.1 },\n"
         "  },\n"
         "  belt = { mu = 0 },\n"
         "}\n";
}

}  // namespace beltsim::test
