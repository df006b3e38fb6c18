// The changes a live simulation takes while it runs (sim/simulation.hpp): a pulley's torque or
// speed law, an arm's or a rotor's state, the belt's μ, a spray zone switched; each recorded in
// events.csv and applied through Simulation::changed. The rest of Simulation is in simulation.cpp.
#include <cmath>
#include <stdexcept>

#include "io/number_text.hpp"
#include "model/forces.hpp"
#include "scene/validate.hpp"
#include "sim/simulation.hpp"

namespace beltsim {

void Simulation::keep_states_law(int j, const char* what, const TimeSpeedLaw& law) const {
  if (!rs_.keep_states || !law.fn) return;
  throw std::invalid_argument("keep_states: pulley " + model_.pulleys[j].name + "'s " + what + " law is Lua code (" +
                              law.fn->describe() +
                              "), which a kept state (a checkpoint) cannot hold; give the law as a table "
                              "(constant, ramps, sines, ...) or keep no states");
}

void Simulation::set_torque(int j, const TimeSpeedLaw& law, const std::string& text) {
  require_open("set_torque");
  keep_states_law(j, "torque", law);
  before_change();
  PulleyDrive& p = drive_.pulleys.at(j);
  p.torque = law;
  const bool was_kinematic = p.kinematic;
  p.kinematic = false;
  write_event(now(), model_.pulleys[j].name + ".torque", text);
  if (was_kinematic) {
    // it turns freely from here, at the speed it was driven at
    Eigen::VectorXd y = state();
    y[model_.n_coord() + model_.pulley_coord(j)] = p.speed.eval(now(), 0.0, true);
    changed(&y);
  } else {
    changed();
  }
}

void Simulation::set_speed(int j, const TimeSpeedLaw& law, const std::string& text) {
  require_open("set_speed");
  keep_states_law(j, "speed", law);
  before_change();
  PulleyDrive& p = drive_.pulleys.at(j);
  p.speed = law;
  p.speed.per_speed = 0;
  p.kinematic = true;
  write_event(now(), model_.pulleys[j].name + ".speed", text);
  Eigen::VectorXd y = state();
  y[model_.n_coord() + model_.pulley_coord(j)] = p.speed.eval(now(), 0.0, true);  // it restarts here
  changed(&y);
}

void Simulation::set_arm(int j, std::optional<double> angle, std::optional<double> rate) {
  require_open("set_arm");
  const int a = model_.pulleys.at(j).arm;
  if (a < 0) throw std::invalid_argument("pulley '" + model_.pulleys[j].name + "' has no tensioner arm");
  Eigen::VectorXd y = state();
  const int k = model_.arm_coord(a);
  std::string text;
  if (angle) y[k] = *angle, text += "angle " + number_text(*angle) + " rad";
  if (rate)
    y[model_.n_coord() + k] = *rate,
                         text += std::string(text.empty() ? "" : ", ") + "rate " + number_text(*rate) + " rad/s";
  write_event(now(), model_.pulleys[j].name + ".arm", text);
  changed(&y);
}

void Simulation::set_rotor(int j, std::optional<double> angle, std::optional<double> speed) {
  require_open("set_rotor");
  const int c = model_.pulleys.at(j).coupling;
  if (c < 0) throw std::invalid_argument("pulley '" + model_.pulleys[j].name + "' has no coupling");
  Eigen::VectorXd y = state();
  const int k = model_.rotor_coord(c);
  std::string text;
  if (angle) y[k] = *angle, text += "angle " + number_text(*angle) + " rad";
  if (speed)
    y[model_.n_coord() + k] = *speed,
                         text += std::string(text.empty() ? "" : ", ") + "speed " + number_text(*speed) + " rad/s";
  write_event(now(), model_.pulleys[j].name + ".rotor", text);
  changed(&y);
}

void Simulation::set_mu(const std::vector<double>& mu, const std::string& what, const std::string& text) {
  require_open(what.c_str());
  if (static_cast<int>(mu.size()) != model_.n_el())
    throw std::invalid_argument(what + ": one μ per element expected (" + std::to_string(model_.n_el()) + "), got " +
                                std::to_string(mu.size()));
  for (size_t i = 0; i < mu.size(); ++i)
    if (const std::string bad = std::isnan(mu[i]) ? "" : mu_problem(mu[i], static_cast<int>(i)); !bad.empty())
      throw std::invalid_argument(what + ": μ " + bad);
  before_change();
  for (size_t i = 0; i < mu.size(); ++i)
    if (!std::isnan(mu[i])) drive_.mu[i] = mu[i];
  write_event(now(), what, text);
  changed();
}

std::string Simulation::spray_name(int z) {
  return "spray" + std::to_string(z + 1);
}

void Simulation::spray_at(double t) {
  before_change();  // (the interval means up to now with the spray as it was)
  const Eigen::VectorXd& y = state();
  const std::vector<int> switched = spray_switch(drive_.spray, t);
  for (int z : switched) write_event(t, spray_name(z), drive_.spray.zones[z].on ? "on" : "off");
  const bool moved = spray_update(drive_.spray, model_.n_el(), t, y.data(), y.data() + model_.n_coord());
  if (moved || !switched.empty()) changed();
}

void Simulation::set_spray(int z, bool enabled) {
  require_open("spray");
  if (z < 0 || z >= static_cast<int>(drive_.spray.zones.size()))
    throw std::invalid_argument("spray: no zone " + std::to_string(z + 1) + " (the scene has " +
                                std::to_string(drive_.spray.zones.size()) + ")");
  before_change();
  drive_.spray.zones[z].enabled = enabled;
  write_event(now(), spray_name(z), enabled ? "enabled" : "disabled");
  spray_at(now());
}

}  // namespace beltsim
