// The PK belt presets (belt_presets.hpp); docs/belts.md gives each per-rib value's source and how
// the derived ones were found.
#include "scene/belt_presets.hpp"

#include <cctype>
#include <stdexcept>

#include "io/number_text.hpp"
#include "io/suggest.hpp"
#include "scene/parameters.hpp"
#include "scene/scene_types.hpp"

namespace beltsim {

namespace {

// one rib of a PK belt; every value but rib_angle scales with the number of ribs
struct PerRib {
  const char* key;
  double value;
  bool per_rib;
};
constexpr PerRib kPkRib[] = {
    // Kubas's 5PK (0.096 kg/m) per rib
    {"mass_per_length", 0.0192, true},
    // Kubas's 5PK c_tra (1.52e5 N, read as EA: docs/model.md) per rib
    {"EA", 30400, true},
    // Bando, EP 1 367 291 A3 / EP 1 046 835 A3: a flexural rigidity of 7.84 N·cm² per rib
    {"EI", 7.84e-4, true},
    // Kubas's 5PK b_tra (20.5 N·s, per length) per rib
    {"axial_damping", 4.1, true},
    // derived (docs/belts.md): the bending loss 2 % of the power on docs/automotive.md's drive
    {"bending_viscosity", 1.4e-7, true},
    // ISO 9982
    {"rib_angle", 40, false},
};
constexpr int kFewestRibs = 3, kMostRibs = 8;

std::vector<BeltPreset> make_presets() {
  std::vector<BeltPreset> out;
  for (int ribs = kFewestRibs; ribs <= kMostRibs; ++ribs) {
    BeltPreset& p = out.emplace_back();
    p.name = std::to_string(ribs) + "PK";
    p.ribs = ribs;
    // to 6 digits, so that 5PK's mass is the paper's 0.096 kg/m and not 0.09599999999999999
    for (const PerRib& r : kPkRib)
      p.values.emplace_back(r.key, r.per_rib ? *parse_number(rounded_text(r.value * ribs, 6)) : r.value);
  }
  return out;
}

bool is_rigidity(const std::string& key) {
  return key == "EA" || key == "EI" || key == "axial_damping" || key == "bending_viscosity";
}

}  // namespace

const std::vector<BeltPreset>& belt_presets() {
  static const std::vector<BeltPreset> presets = make_presets();
  return presets;
}

const BeltPreset* find_belt_preset(std::string_view name) {
  for (const BeltPreset& p : belt_presets())
    if (p.name == name) return &p;
  return nullptr;
}

std::vector<std::string> belt_preset_names() {
  std::vector<std::string> out;
  for (const BeltPreset& p : belt_presets()) out.push_back(p.name);
  return out;
}

std::string belt_preset_hint(const std::string& name) {
  std::string upper = name;
  for (char& c : upper) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  if (find_belt_preset(upper)) return " (did you mean '" + upper + "'?)";
  return "; the presets: " + join(belt_preset_names());
}

void apply_belt_preset(const BeltPreset& p, SceneDef& d, const std::function<bool(const std::string&)>& own) {
  PulleyDef none;
  for (const auto& [key, value] : p.values) {
    if (own(key) || (key == "bending_viscosity" && own("bending_damping")) || (is_rigidity(key) && own("sde")))
      continue;
    const Parameter* par = find_parameter("belt." + key);
    const Slot slot = par ? par->slot(d, none) : Slot();
    if (double* const* x = std::get_if<double*>(&slot))
      **x = value;
    else if (std::optional<double>* const* o = std::get_if<std::optional<double>*>(&slot))
      **o = value;
    else
      throw std::logic_error("belt preset " + p.name + ": '" + key + "' is not a number of the belt table");
    d.given.insert("belt." + key);
    d.from_preset.insert("belt." + key);
  }
}

std::string belt_presets_markdown() {
  std::string md = "| preset |";
  std::string rule = "|---|";
  for (const PerRib& r : kPkRib) {
    const Parameter* par = find_parameter(std::string("belt.") + r.key);
    md.append(" `").append(r.key).append("` [").append(par ? par->unit : "").append("] |");
    rule.append("---|");
  }
  md.append("\n").append(rule).append("\n");
  for (const BeltPreset& p : belt_presets()) {
    md.append("| `\"").append(p.name).append("\"` |");
    for (const auto& [key, value] : p.values) md.append(" ").append(number_text(value)).append(" |");
    md.append("\n");
  }
  return md;
}

}  // namespace beltsim
