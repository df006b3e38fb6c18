// The PK belt presets (scene/belt_presets.hpp): values of the belt table's numbers, scaled per rib,
// which the belt table's own keys override. Their Lua side (belt.preset, beltsim.belts):
// script/parameters_test.cpp.
#include "scene/belt_presets.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "scene/parameters.hpp"
#include "scene/scene.hpp"
#include "scene/validate.hpp"

namespace beltsim {
namespace {

// Every preset's key is a number of the belt table within its rule; 5PK is the paper's belt in
// mass, axial rigidity and axial damping; the values scale with the ribs
TEST(BeltPresets, EveryValueIsABeltNumberWithinItsRule) {
  ASSERT_EQ(belt_preset_names(), (std::vector<std::string>{"3PK", "4PK", "5PK", "6PK", "7PK", "8PK"}));
  for (const BeltPreset& p : belt_presets())
    for (const auto& [key, value] : p.values) {
      const Parameter* par = find_parameter("belt." + key);
      ASSERT_NE(par, nullptr) << key;
      EXPECT_EQ(par->kind, Kind::number) << key;
      EXPECT_NO_THROW(check_rule(*par, p.name + "." + key, value)) << key;
    }
  const auto value = [](const std::string& preset, const std::string& key) {
    for (const auto& [k, v] : find_belt_preset(preset)->values)
      if (k == key) return v;
    return std::nan("");
  };
  EXPECT_EQ(value("5PK", "mass_per_length"), parameter_default("belt.mass_per_length"));
  EXPECT_EQ(value("5PK", "EA"), parameter_default("belt.EA"));
  EXPECT_EQ(value("5PK", "axial_damping"), parameter_default("belt.axial_damping"));
  EXPECT_DOUBLE_EQ(value("8PK", "EI"), 8.0 / 3.0 * value("3PK", "EI"));
  EXPECT_EQ(value("3PK", "rib_angle"), value("8PK", "rib_angle"));
}

// A preset's values are given; the table's own keys override them, and a bending damping of the
// table's own excludes the preset's viscosity (the two are alternatives)
TEST(BeltPresets, TheTablesOwnKeysOverrideThePreset) {
  SceneDef d;
  d.belt.EI = 0.01;
  d.belt.bending_damping = 0.001;
  apply_belt_preset(*find_belt_preset("6PK"), d,
                    [](const std::string& key) { return key == "EI" || key == "bending_damping"; });
  EXPECT_EQ(d.belt.EI, 0.01);
  EXPECT_FALSE(d.belt.bending_viscosity);
  EXPECT_EQ(d.belt.EA, 182400);
  EXPECT_EQ(d.given.count("belt.EA"), 1u);
  EXPECT_EQ(d.given.count("belt.EI"), 0u);
  EXPECT_EQ(belt_preset_hint("6pk"), " (did you mean '6PK'?)");
  EXPECT_EQ(belt_preset_hint("9PK"), "; the presets: 3PK, 4PK, 5PK, 6PK, 7PK, 8PK");
}

}  // namespace
}  // namespace beltsim
