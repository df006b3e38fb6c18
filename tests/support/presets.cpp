// The tests' scenes (support/presets.hpp): the paper's drive read from scripts/paper_dry.lua.
#include "support/presets.hpp"

#include <cmath>
#include <stdexcept>

#include "script/interpreter.hpp"
#include "script/script_args.hpp"

namespace beltsim::presets {

namespace {
TimeSpeedLaw viscous(double per_speed) {
  TimeSpeedLaw law;
  law.per_speed = per_speed;
  return law;
}
}  // namespace

SceneDef script_scene(const std::string& script, const std::vector<std::string>& set) {
  const std::string path = std::string(BELTSIM_SOURCE_DIR) + "/" + script;
  script::Overrides o;
  o.no_frames = true;
  o.set = script::parse_sets(set);
  script::Captured cap;
  cap.definition_only = true;
  script::Interpreter lua;
  lua.set_overrides(o);
  lua.set_capture(&cap);
  lua.run_file(path);
  if (!cap.definition)
    throw std::runtime_error(path + ": no beltsim.scene{}, or its belt.mu is a Lua function: no definition to build");
  return *cap.definition;
}

SceneDef paper_dry() {
  static const SceneDef d = [] {
    SceneDef s = script_scene("scripts/paper_dry.lua");
    s.track_energy = false;
    return s;
  }();
  return d;
}

SceneDef paper_wet() {
  SceneDef d = paper_dry();
  // wet (μ = 0.2) where the element centres start at x > l_p/2
  const double half = d.pulleys[1].centre.x() / 2;
  d.belt.mu_at = [half](const ElementSite& e) { return e.centre.x() > half ? 0.2 : 1.0; };
  return d;
}

namespace {
// tests/support/automotive_scene.lua's drive (the layout of tests/support/automotive.lua), with the
// paper's torques (Fig. 7) on the crankshaft and the pump
SceneDef automotive(bool arm) {
  SceneDef d = script_scene("tests/support/automotive_scene.lua",
                            arm ? std::vector<std::string>{"arm=true"} : std::vector<std::string>{});
  d.pulleys[0].torque = paper_dry().pulleys[0].torque;
  d.pulleys[3].torque = paper_dry().pulleys[1].torque;
  // its 280 N as if not given: the tests set the tension at rest by a tensioner's preload instead
  d.given.erase("belt.pretension");
  return d;
}
}  // namespace

SceneDef automotive_wet() {
  static const SceneDef fixed = automotive(false);
  SceneDef d = fixed;
  // wet 30 % of the belt, its leading end where the belt leaves the pump, extending upstream
  d.belt.mu_at = [](const ElementSite& e) {
    const double lead = e.leaves.at("pump");
    double behind = std::fmod(lead - e.s, e.length);
    if (behind < 0) behind += e.length;
    return behind < 0.3 * e.length ? 0.2 : 1.0;
  };
  return d;
}

SceneDef automotive_tensioner() {
  static const SceneDef d = [] {
    SceneDef s = automotive(true);
    TensionerDef& t = *s.pulleys[1].tensioner;
    t.damping = 0.05;
    t.friction_torque = 0.5;
    return s;
  }();
  return d;
}

SceneDef automotive_accessories(double crank_rpm) {
  SceneDef d = automotive_wet();
  d.belt.mu_at = nullptr;
  PulleyDef& crank = d.pulleys[0];
  crank.torque = TimeSpeedLaw{};
  crank.kinematic = true;
  crank.speed.ramps.push_back({.t0 = 0, .t1 = 0.05, .from = 0, .to = -crank_rpm * 2 * M_PI / 60, .cosine = true});
  d.pulleys[2].torque = viscous(-0.01);
  d.pulleys[3].torque = viscous(-0.05);
  return d;
}

}  // namespace beltsim::presets
