#include "scene/presets.hpp"

#include <cmath>

namespace beltsim::presets {

namespace {
TimeSpeedLaw ramp(double t1, double value) {
  TimeSpeedLaw law;
  law.t = {0.0, t1};
  law.value = {0.0, value};
  return law;
}
TimeSpeedLaw viscous(double per_speed) {
  TimeSpeedLaw law;
  law.per_speed = per_speed;
  return law;
}
// 70 N·m at 700 rpm, opposing rotation
constexpr double kResistance = 70.0 / (700.0 * 2.0 * M_PI / 60.0);
}  // namespace

SceneDef paper_dry() {
  SceneDef d;
  PulleyDef driver;
  driver.name = "driver";
  driver.centre = {0, 0};
  driver.torque = ramp(0.3, -70.0);
  PulleyDef driven;
  driven.name = "driven";
  driven.centre = {0.29, 0};
  driven.torque = viscous(-kResistance);
  d.pulleys = {driver, driven};
  d.belt.loop_sense = -1;
  return d;
}

SceneDef paper_wet() {
  SceneDef d = paper_dry();
  // wet (μ = 0.2) where the element centres start at x > l_p/2
  d.belt.mu_at = [](const ElementSite& e) { return e.centre.x() > 0.145 ? 0.2 : 1.0; };
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
  crank.torque = ramp(0.3, -70.0);
  PulleyDef idler = pulley("tensioner", {0.015, -0.12}, 0.031, WrapSide::back, 5e-5);
  PulleyDef alt = pulley("alternator", {0, 0}, 0.027, WrapSide::inside, 2e-3);
  PulleyDef pump = pulley("pump", {0.16, -0.06}, 0.056, WrapSide::inside, 1e-3);
  pump.torque = viscous(-kResistance);
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
