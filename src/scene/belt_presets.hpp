// Belt presets: the PK sections 3PK … 8PK (ISO 9982: ribs 3.56 mm apart, 40° rib angle) as values
// of the belt table's keys (scene/parameters.hpp), scaled per rib from one set of per-rib values
// whose sources and derivations docs/belts.md gives. A scenario names one as belt.preset ("6PK",
// or `belt = beltsim.belts["6PK"]`, which holds the same values and the name); the belt table's
// own keys override the preset's.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace beltsim {

struct SceneDef;

struct BeltPreset {
  std::string name;  // "6PK"
  int ribs = 0;
  std::vector<std::pair<std::string, double>> values;  // belt keys ("EI") and their values, SI
};

// 3PK … 8PK, in that order
const std::vector<BeltPreset>& belt_presets();
// the preset of that name, nullptr when none
const BeltPreset* find_belt_preset(std::string_view name);
std::vector<std::string> belt_preset_names();
// why `name` is no preset, for an error after "no preset 'name'": the one it misspells in case
// ("6pk": did you mean '6PK'?), else the presets' names
std::string belt_preset_hint(const std::string& name);

// Sets d.belt's values of preset p but those the belt table gives itself (own(key)), and notes the
// keys set in d.given ("belt.EI"): a value given through a preset is given. A bending_damping of
// the table's own excludes the preset's bending_viscosity; an sde table excludes its rigidities
// and dampings.
void apply_belt_preset(const BeltPreset& p, SceneDef& d, const std::function<bool(const std::string&)>& own);

// The presets as docs/lua-api.md and `beltsim help parameters` show them: one row per preset.
std::string belt_presets_markdown();

}  // namespace beltsim
