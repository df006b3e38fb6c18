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
  script::Interpreter lua;
  lua.set_overrides(o);
  lua.set_capture(&cap);
  lua.run_file(path);
  if (!cap.scene) throw std::runtime_error(path + ": the script never calls scene:run{}");
  if (!cap.definition)
    throw std::runtime_error(path + ": its scene's belt.mu is a Lua function: no definition to build");
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

SceneDef automotive_wet() {
  SceneDef d;
  auto pulley = [](const char* name, Vec2 c, double r, WrapSide w, double inertia) {
    PulleyDef p;
    p.name = name;
    p.centre = c;
    p.radius = r;
    p.wrap = w;
    p.inertia = inertia;
    return p;
  };
  PulleyDef crank = pulley("crankshaft", {0.09, -0.27}, 0.080, WrapSide::inside, 0.02);
  crank.torque = paper_dry().pulleys[0].torque;  // the paper's torques (Fig. 7)
  PulleyDef idler = pulley("tensioner", {0.015, -0.12}, 0.031, WrapSide::back, 5e-5);
  PulleyDef alt = pulley("alternator", {0, 0}, 0.027, WrapSide::inside, 2e-3);
  PulleyDef pump = pulley("pump", {0.16, -0.06}, 0.056, WrapSide::inside, 1e-3);
  pump.torque = paper_dry().pulleys[1].torque;
  d.pulleys = {crank, idler, alt, pump};
  d.belt.elements = 150;
  d.belt.pretension = 280;
  d.belt.loop_sense = -1;
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
  SceneDef d = automotive_wet();
  d.belt.mu_at = nullptr;
  TensionerDef& t = d.pulleys[1].tensioner.emplace();
  t.pivot = {0.075, -0.14};
  t.inertia = 1e-3;
  t.stiffness = 30;
  t.damping = 0.05;
  t.friction_torque = 0.5;
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
