// A scene's inputs as a run reports them: every parameter of the parameter table the scene uses
// (scene/parameters.hpp), its value after defaults, and whether it was given (SceneDef::given) or
// a default was taken, with whose that default is. parameters.csv lists them all and a run's
// first lines name the defaults, so a user who gave EA, EI and the axial damping sees that the
// bending damping is the paper's.

#include <cmath>

#include "io/number_text.hpp"
#include "scene/scene.hpp"

namespace beltsim {

SceneInput scene_input(const Parameter& par, const std::string& name, double value, const std::string& text,
                       bool given) {
  std::string note(par.note);
  if (par.whose != Whose::none) note.append("; default: ").append(whose_text(par.whose));
  return {name, value, text, std::string(text.empty() ? par.unit : ""), given, note, "", ""};
}

std::vector<SceneInput> scene_inputs(const SceneDef& d) {
  std::vector<SceneInput> in;
  auto add = [&](const Parameter* par, const PulleyDef* p) {
    if (par->applies && !par->applies(d)) return;
    // a pulley's: "pulley.driver.radius", "pulley.idler.tensioner.stiffness"
    const std::string name =
        p ? "pulley." + p->name + par->dotted().substr(std::string_view("pulley").size()) : par->dotted();
    const std::string text = par->word ? par->word(d, p ? *p : PulleyDef{}) : "";
    const std::optional<double> v = value_of(*par, d, p);
    if (text.empty() && !v) return;  // read by its own code, or an alternative not given
    in.push_back(scene_input(*par, name, text.empty() ? *v : 0, text, d.given.count(name) > 0));
    if (d.from_preset.count(name)) in.back().preset = d.belt.preset;
  };
  for (const char* table : {"belt", "belt.sde", "contact", "friction", "scene"})
    for (const Parameter* par : parameters_of(table)) add(par, nullptr);
  for (const PulleyDef& p : d.pulleys) {
    for (const Parameter* par : parameters_of("pulley")) add(par, &p);
    if (p.tensioner)
      for (const Parameter* par : parameters_of("pulley.tensioner")) add(par, &p);
    if (p.coupling)
      for (const Parameter* par : parameters_of("pulley.coupling")) add(par, &p);
  }
  // a friction segment's: "friction.segments.1.from", "friction.segments.1.law", and its law's numbers
  for (size_t k = 0; k < d.friction_segments.size(); ++k) {
    const FrictionSegment& g = d.friction_segments[k];
    const std::string pre = "friction.segments." + std::to_string(k + 1) + ".";
    for (const auto& [key, v] : {std::pair{"from", g.from}, std::pair{"to", g.to}})
      in.push_back(scene_input(*find_parameter(std::string("friction.segments.") + key), pre + key, v, "", true));
    SceneDef own;
    own.friction = g.law;
    for (const Parameter* par : parameters_of("friction")) {
      const std::string key(par->key);
      if (key == "dv" || key == "segments" || (par->applies && !par->applies(own))) continue;
      const std::string text = par->word ? par->word(own, PulleyDef{}) : "";
      const std::optional<double> v = value_of(*par, own, nullptr);
      if (text.empty() && !v) continue;
      // given: in the segment, or in the friction table the segment's law starts from
      const bool given = d.given.count(pre + key) > 0 || d.given.count("friction." + key) > 0;
      in.push_back(scene_input(*par, pre + key, text.empty() ? *v : 0, text, given));
    }
  }
  // a spray zone's: "spray.1.radius"; `to` is "never" when it does not stop
  for (size_t k = 0; k < d.spray.size(); ++k) {
    const SprayZone& z = d.spray[k];
    const std::string pre = "spray." + std::to_string(k + 1) + ".";
    const std::pair<const char*, double> numbers[] = {
        {"radius", z.radius}, {"mu", z.mu}, {"from", z.from}, {"to", z.to}, {"drying_length", z.drying_length}};
    for (const auto& [key, v] : numbers) {
      const std::string name = pre + key;
      const bool never = std::isinf(v);
      in.push_back(scene_input(*find_parameter(std::string("spray.") + key), name, never ? 0 : v, never ? "never" : "",
                               d.given.count(name) > 0));
    }
  }
  mark_derived(in);
  return in;
}

void mark_derived(std::vector<SceneInput>& inputs) {
  const auto find = [&](std::string_view name) -> SceneInput* {
    for (SceneInput& in : inputs)
      if (in.name == name) return &in;
    return nullptr;
  };
  SceneInput *mu = find("belt.mu"), *flank = find("belt.mu_flank"), *angle = find("belt.rib_angle");
  if (!mu || !flank || !angle || !mu->text.empty()) return;
  mu->derived = "belt.mu_flank = " + rounded_text(flank->value, 6) +
                " and belt.rib_angle = " + rounded_text(angle->value, 6) + "°";
  mu->note = std::string(find_parameter("belt.mu")->note) + "; derived: mu_flank/sin(rib_angle/2) from " + mu->derived;
}

}  // namespace beltsim
