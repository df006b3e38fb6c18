// The parameter table (scene/parameters.hpp) is the one place of the scene's keys: every number in
// it is read from Lua, checked by its rule with the reason and the value, written to
// parameters.csv with its unit and source, and docs/lua-api.md holds its tables as generated.
#include "scene/parameters.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "io/number_text.hpp"
#include "run_script.hpp"
#include "script/interpreter.hpp"
#include "sim/run_table.hpp"
#include "support/files.hpp"
#include "support/scenes.hpp"
#include "support/scratch.hpp"

namespace beltsim::script {
namespace parameters_test {

using beltsim::test::slurp;

namespace fs = std::filesystem;

fs::path temp_dir() { return beltsim::test::scratch_dir("beltsim_parameters_test"); }

// A two-pulley scene (pulleys 'a' and 'b') with the given values as Lua expressions, each under its
// dotted key ("belt.EA", "belt.sde.k", "pulley.radius": pulley a's, "pulley.tensioner.stiffness":
// pulley a's arm, pivoted 0.1 m above its centre, "pulley.coupling.stiffness": pulley a's
// coupling, "gravity"; a friction law's own parameters with that law) and `friction` (more keys of
// the friction table, as Lua writes them), then a run of one millisecond writing parameters.csv.
// The scene of this file's tests, not the shared test scene (support/scenes.hpp): it gives nothing
// but the values under test (no radius, pretension or element count), which the tests find in
// parameters.csv as given and the rest as defaults.
std::string scene_with(std::map<std::string, std::string> values, const std::string& friction = "") {
  // a friction law's own parameters (those that apply to some laws only) come with LuGre's, which
  // takes them all
  for (const auto& [dotted, v] : std::map<std::string, std::string>(values)) {
    const Parameter* p = find_parameter(dotted);
    if (p && p->table == "friction" && p->applies && !values.count("friction.law"))
      values["friction.law"] = "'lugre'";
  }
  std::map<std::string, std::string> tables;
  for (const auto& [dotted, v] : values) {
    const Parameter* p = find_parameter(dotted);
    EXPECT_NE(p, nullptr) << dotted;
    if (p) tables[std::string(p->table)] += std::string(p->key) + " = " + v + ", ";
  }
  std::string belt = tables["belt"];
  if (!tables["belt.sde"].empty()) belt += "sde = { " + tables["belt.sde"] + "}, ";
  std::string pulley = tables["pulley"];
  // a spray zone's keys: one zone, off the belt's path
  const std::string spray =
      tables["spray"].empty() ? "" : "spray = { { centre = {0.145, 0.5}, " + tables["spray"] + "} },";
  if (!tables["pulley.tensioner"].empty())
    pulley += "tensioner = { pivot = {0, 0.1}, " + tables["pulley.tensioner"] + "}, ";
  if (!tables["pulley.coupling"].empty()) pulley += "coupling = { " + tables["pulley.coupling"] + "}, ";
  return "local s = beltsim.scene {\n"
         "  pulleys = { { name = 'a', centre = {0, 0}, torque = -1, " +
         pulley +
         "},\n"
         "              { name = 'b', centre = {0.29, 0} } },\n"
         "  belt = { " +
         belt +
         "},\n"
         "  contact = { " +
         tables["contact"] +
         "},\n"
         "  friction = { " +
         tables["friction"] + friction +
         " },\n"
         "  " +
         tables["scene"] + spray +
         "\n"
         "}\n"
         "s:run { t_end = 1e-3, progress = false }\n";
}

// "file:N: " with N the line of `text` where `written` stands: an error about a key names the line
// where the key was written
std::string at_line_of(const std::string& text, const std::string& written) {
  const size_t k = text.find(written);
  EXPECT_NE(k, std::string::npos) << written << " in\n" << text;
  const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(std::min(k, text.size())), '\n');
  return (temp_dir() / "scene.lua").string() + ":" + std::to_string(line) + ": ";
}

std::string run_text(const std::string& text) {
  Interpreter lua;
  return test::run_script(lua, temp_dir() / "scene.lua", text, temp_dir() / "out");
}

// a value that breaks the rule, as Lua writes it and as the error shows it
std::pair<std::string, std::string> breaking(Rule r) {
  switch (r) {
    case Rule::positive: return {"0", "0"};
    case Rule::non_negative: return {"-1", "-1"};
    case Rule::exponent: return {"0.5", "0.5"};
    case Rule::at_least_three: return {"2", "2"};
    case Rule::friction_coefficient: return {"11", "11"};
    case Rule::slip_band: return {"2", "2"};
    case Rule::pulley_radius:
      return {"100", "100"};
    case Rule::strain:
      return {"0.9", "0.9"};
    case Rule::finite: return {"1/0", "inf"};
    case Rule::none: break;
  }
  return {};
}

// the per-SDE values are given all four or none
const std::map<std::string, std::string> kSde{
    {"belt.sde.k", "7.5e6"}, {"belt.sde.c", "1000"}, {"belt.sde.kt", "1.3"}, {"belt.sde.ct", "0.05"}};
// a tensioner requires these two
const std::map<std::string, std::string> kTensioner{{"pulley.tensioner.inertia", "0.01"},
                                                    {"pulley.tensioner.stiffness", "3000"}};
// a coupling requires these two
const std::map<std::string, std::string> kCoupling{{"pulley.coupling.inertia", "0.01"},
                                                   {"pulley.coupling.stiffness", "50"}};
// the required keys of both
std::map<std::string, std::string> required() {
  std::map<std::string, std::string> r = kTensioner;
  r.insert(kCoupling.begin(), kCoupling.end());
  return r;
}

// a spray zone requires these three
const std::map<std::string, std::string> kSpray{
    {"spray.radius", "0.01"}, {"spray.mu", "0.2"}, {"spray.drying_length", "1"}};

// the name a key of pulley `pulley`'s has in parameters.csv ("pulley.a.radius",
// "pulley.a.tensioner.stiffness"), the dotted key otherwise
std::string csv_name(const Parameter& p, const std::string& pulley) {
  return p.table.starts_with("pulley") ? "pulley." + pulley + p.dotted().substr(6) : p.dotted();
}

// every rule of the table stops the script at the key's line with the key, the reason and the value
TEST(Parameters, EveryRuleStopsTheScriptWithTheKeyTheReasonAndTheValue) {
  int checked = 0;
  for (const Parameter& p : parameters()) {
    if (p.rule == Rule::none) continue;
    const auto [lua, shown] = breaking(p.rule);
    std::map<std::string, std::string> values;
    if (p.table == "belt.sde") values = kSde;
    if (p.table == "pulley.tensioner") values = kTensioner;
    if (p.table == "spray") values = kSpray;
    if (p.table == "pulley.coupling") values = kCoupling;
    values[p.dotted()] = lua;
    const std::string what = p.table.starts_with("pulley") ? "pulley 'a'." + p.dotted().substr(7)
                             : p.table == "spray"          ? "spray 1." + std::string(p.key)
                                                           : p.dotted();
    const std::string text = scene_with(values);
    const std::string expected = at_line_of(text, std::string(p.key) + " = " + lua + ", ") + what + " " +
                                 std::string(rule_text(p.rule)) + " (got " + shown + (p.unit.empty() ? "" : " ") +
                                 std::string(p.unit) + ")";
    EXPECT_EQ(run_text(text).rfind(expected, 0), 0u)
        << p.dotted() << ": expected '" << expected << "', got '" << run_text(text) << "'";
    ++checked;
  }
  EXPECT_GE(checked, 25);  // every number of the scene has a rule
}

// the value of every number a scene gives reaches parameters.csv with its unit as given, and every
// default taken as default; the alternatives (rest_length, strain, per SDE, per length) in
// scenes of their own
TEST(Parameters, EveryNumberReachesParametersCsv) {
  std::map<std::string, std::string> primary = required(), per_length{{"belt.rest_length", "1.2045"}}, per_sde = kSde;
  per_sde["belt.strain"] = "0.005";
  per_length["belt.bending_viscosity"] = "1e-3";
  per_length["contact.c1_per_length"] = "1.5e11";
  per_length["contact.c2_per_length"] = "3.25e7";
  per_length["contact.damping_per_length"] = "1.5e4";
  for (const Parameter& p : parameters()) {
    if (!p.slot || !p.fallback) continue;
    // 5 % off the default (0.05 for a default of 0), a whole number for an integer
    const double v = p.kind == Kind::integer ? *p.fallback + 2 : *p.fallback == 0 ? 0.05 : *p.fallback * 1.05;
    primary[p.dotted()] = number_text(v);
  }
  auto row = [](const std::string& csv, const std::string& name) {
    const size_t at = csv.find("\n" + name + ",");
    return at == std::string::npos ? std::string() : csv.substr(at + 1, csv.find('\n', at + 1) - at - 1);
  };
  for (const auto* values : {&primary, &per_length, &per_sde}) {
    ASSERT_EQ(run_text(scene_with(*values)), "");
    const std::string csv = slurp(temp_dir() / "out" / "parameters.csv");
    for (const auto& [dotted, v] : *values) {
      const Parameter* p = find_parameter(dotted);
      const std::string name = csv_name(*p, "a");
      const std::string expected = name + "," + number_text(std::stod(v)) + "," + std::string(p->unit) + ",given,";
      EXPECT_EQ(row(csv, name).rfind(expected, 0), 0u)
          << "expected '" << expected << "', got '" << row(csv, name) << "'";
    }
  }
  // nothing given (but a tensioner's and a coupling's required two, and the law whose parameters
  // apply): the defaults, marked so
  std::map<std::string, std::string> none = required();
  none["friction.law"] = "'lugre'";
  ASSERT_EQ(run_text(scene_with(none)), "");
  const std::string csv = slurp(temp_dir() / "out" / "parameters.csv");
  for (const auto& [dotted, v] : primary) {
    const Parameter* p = find_parameter(dotted);
    if (!p->fallback) continue;  // a required key
    const std::string name = csv_name(*p, p->table == "pulley" ? "b" : "a");
    const std::string expected =
        name + "," + number_text(*p->fallback) + "," + std::string(p->unit) + ",default," ;
    EXPECT_EQ(row(csv, name).rfind(expected, 0), 0u) << "expected '" << expected << "', got '" << row(csv, name) << "'";
    EXPECT_NE(row(csv, name).find(whose_text(p->whose)), std::string::npos) << row(csv, name);
  }
}

// docs/lua-api.md holds the table's Markdown between its markers, exactly (regenerate it with
// `beltsim help parameters`): no key, unit, default or range in the docs differs from the code's
TEST(Parameters, TheDocsHoldTheTable) {
  const std::string docs = slurp(fs::path(BELTSIM_SOURCE_DIR) / "docs" / "lua-api.md");
  const std::string begin = "<!-- parameters: begin (beltsim help parameters) -->\n", end = "<!-- parameters: end -->";
  const size_t b = docs.find(begin), e = docs.find(end);
  ASSERT_NE(b, std::string::npos);
  ASSERT_NE(e, std::string::npos);
  EXPECT_EQ(docs.substr(b + begin.size(), e - b - begin.size()), parameters_markdown())
      << "docs/lua-api.md's parameter tables differ from the code's: put the output of 'beltsim help parameters' "
         "between the markers";
  EXPECT_EQ(docs.find(begin, b + 1), std::string::npos) << "one copy of the tables";
}

// docs/lua-api.md holds the run-settings table between its markers, exactly (regenerate it with
// `beltsim help run-settings`): no key, unit, default, option or checkpoint mark differs from the code's
TEST(Parameters, TheDocsHoldTheRunSettingsTable) {
  const std::string docs = slurp(fs::path(BELTSIM_SOURCE_DIR) / "docs" / "lua-api.md");
  const std::string begin = "<!-- run settings: begin (beltsim help run-settings) -->\n",
                    end = "<!-- run settings: end -->";
  const size_t b = docs.find(begin), e = docs.find(end);
  ASSERT_NE(b, std::string::npos);
  ASSERT_NE(e, std::string::npos);
  EXPECT_EQ(docs.substr(b + begin.size(), e - b - begin.size()), run_settings_markdown())
      << "docs/lua-api.md's run-settings table differs from the code's: put the output of 'beltsim help "
         "run-settings' between the markers";
  EXPECT_EQ(docs.find(begin, b + 1), std::string::npos) << "one copy of the table";
}

// friction.law takes the three words and names a fourth; a law's own parameter under another law is
// refused with both names (it would otherwise be ignored without a word)
TEST(Parameters, FrictionLawWordsAndTheirParameters) {
  const std::string at = at_line_of(scene_with({}), "friction = {");  // the friction table's line
  EXPECT_EQ(run_text(scene_with({{"friction.law", "'coulomb'"}})),
            at + "friction.law: 'threlfall', 'stribeck' or 'lugre' expected, got 'coulomb'");
  EXPECT_EQ(run_text(scene_with({{"friction.law", "'stribek'"}})),
            at + "friction.law: 'threlfall', 'stribeck' or 'lugre' expected, got 'stribek' (did you mean 'stribeck'?)");
  EXPECT_EQ(run_text(scene_with({{"friction.law", "'stribeck'"}, {"friction.bristle_stiffness", "1e5"}})),
            at + "friction.bristle_stiffness: a parameter of another law; this scene's law is 'stribeck'");
  EXPECT_EQ(run_text(scene_with({{"friction.law", "'threlfall'"}, {"friction.static_ratio", "1.5"}})),
            at + "friction.static_ratio: a parameter of another law; this scene's law is 'threlfall'");
  EXPECT_EQ(run_text(scene_with({{"friction.law", "'stribeck'"}, {"friction.static_ratio", "1.5"}})), "");
  const std::string csv = slurp(temp_dir() / "out" / "parameters.csv");
  EXPECT_NE(csv.find("\nfriction.law,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("stribeck"), std::string::npos) << csv;
  EXPECT_EQ(run_text(scene_with({{"friction.law", "'lugre'"}, {"friction.static_ratio", "1.5"}})), "");
  EXPECT_NE(slurp(temp_dir() / "out" / "parameters.csv").find("\nfriction.bristle_stiffness,"), std::string::npos);
}

// the other words a scene takes (a pulley's wrap, the belt's direction, a ramp's shape): a near miss
// gets a suggestion, as friction.law's, on the key's line
TEST(Parameters, MisspeltWordsGetASuggestion) {
  const std::string wrap = scene_with({{"pulley.wrap", "'bakc'"}});
  EXPECT_EQ(run_text(wrap), at_line_of(wrap, "wrap = ") +
                                "pulley 'a'.wrap: 'inside' or 'back' expected, got 'bakc' (did you mean 'back'?)");
  const std::string direction = scene_with({{"belt.direction", "'cww'"}});
  EXPECT_EQ(run_text(direction), at_line_of(direction, "direction = ") +
                                     "belt.direction: 'cw' or 'ccw' expected, got 'cww' (did you mean 'cw' or 'ccw'?)");
  const std::string ok = scene_with({});
  EXPECT_EQ(run_text(ok.substr(0, ok.find("s:run")) + "local r = beltsim.ramp{ t1 = 1, to = 2, shape = 'cosin' }\n"),
            at_line_of(ok, "s:run") +
                "beltsim.ramp.shape: 'linear' or 'cosine' expected, got 'cosin' (did you mean "
                "'cosine'?)");
}

// friction.segments: each segment's law starts from the scene's and takes its own keys; their rows
// in parameters.csv; a missing end, a misspelt key, another law's parameter and a value past its
// rule are refused with file:line and the segment's number
TEST(Parameters, FrictionSegments) {
  auto scene = [](const std::string& segments) { return scene_with({}, "segments = " + segments); };
  const std::string at = at_line_of(scene("{}"), "segments =");  // the friction table's line
  EXPECT_EQ(run_text(scene_with({{"friction.static_ratio", "1.4"}, {"friction.law", "'stribeck'"}},
                                "segments = { { from = 0.1, to = 0.3, stribeck_speed = 0.05 }, "
                                "{ from = 0.5, to = 0.7, law = 'lugre', bristle_damping = 0.1 } }")),
            "");
  const std::string csv = slurp(temp_dir() / "out" / "parameters.csv");
  // (a segment's law starts from the friction table's: what that table gave, the segment was given)
  for (const char* row : {"friction.segments.1.from,0.1,m,given", "friction.segments.1.law,stribeck,,given",
                          "friction.segments.1.static_ratio,1.4,,given", "friction.segments.1.stribeck_speed,0.05,m/s,given",
                          "friction.segments.1.exponent,2,,default", "friction.segments.2.law,lugre,,given",
                          "friction.segments.2.bristle_damping,0.1,s/m,given",
                          "friction.segments.2.bristle_stiffness,1e+05,1/m,default"})
    EXPECT_NE(csv.find(std::string("\n") + row), std::string::npos) << row << " in\n" << csv;
  // (about no key but a list position: the line of that entry's table, as key_line_test's
  // MessagePathsAsTheErrorsSpellThem has it; here the friction table's)
  EXPECT_EQ(
      run_text(scene("{ { from = 0.1, law = 'stribeck' } }")),
      at + "friction.segments[1]: from and to [m] (where the segment begins and ends along the belt) are required");
  EXPECT_EQ(run_text(scene("{ { from = 0.1, to = 0.2, dv = 1e-4 } }"))
                .rfind(at + "unknown key 'dv' in friction.segments[1]", 0),
            0u);
  EXPECT_EQ(run_text(scene("{ { from = 0.1, to = 0.2, law = 'stribeck', bristle_damping = 1 } }")),
            at + "friction.segments[1].bristle_damping: a parameter of another law; this segment's law is 'stribeck'");
  EXPECT_EQ(run_text(scene("{ { from = 0.1, to = 0.2 }, { from = 0.1, to = 0.2, law = 'lugre', "
                           "release_time = 0 } }")),
            at + "friction.segments[2].release_time must be > 0 (got 0 s)");
  EXPECT_EQ(run_text(scene("{ { from = -0.1, to = 0.2 } }")),
            at + "friction.segments[1].from must be >= 0 (got -0.1 m)");
}

// every key a scene table takes is in the table once
TEST(Parameters, EachKeyOnce) {
  std::map<std::string, int> seen;
  for (const Parameter& p : parameters()) EXPECT_EQ(++seen[p.dotted()], 1) << p.dotted();
  EXPECT_EQ(find_parameter("contact.b"), nullptr);  // the model's name, not the scenario's
  EXPECT_EQ(find_parameter("contact.damping")->unit, "N·s/m");
}

// belt.preset: a PK section's values (scene/belt_presets.hpp) are taken, the table's own keys
// override them and parameters.csv names the preset as their source (a user's trial read them as
// given by the script); a name that is no preset is refused
TEST(Parameters, ABeltPresetGivesItsValues) {
  ASSERT_EQ(run_text(scene_with({{"belt.preset", "'6PK'"}, {"belt.EI", "0.01"}})), "");
  const std::string csv = slurp(temp_dir() / "out" / "parameters.csv");
  for (const char* expected : {"\nbelt.preset,6PK,,given,", "\nbelt.EA,182400,N,preset,", "\nbelt.EI,0.01,N·m²,given,",
                               "\nbelt.bending_viscosity,8.4e-07,N·m²·s,preset,",
                               "\nbelt.mass_per_length,0.1152,kg/m,preset,", "; from the 6PK preset\"\n"})
    EXPECT_NE(csv.find(expected), std::string::npos) << expected << " in\n" << csv;
  EXPECT_EQ(csv.find("\nbelt.bending_damping,"), std::string::npos) << csv;
  const std::string bad = scene_with({{"belt.preset", "'6pk'"}});
  EXPECT_EQ(run_text(bad), at_line_of(bad, "preset =") + "belt.preset: no preset '6pk' (did you mean '6PK'?)");
}

// beltsim.belts["6PK"] is a new table of the preset's values each time, which a scene's belt
// takes; beltsim.belts lists the presets and is read-only. scene:info() gives the bending loss
// estimated at the drive's speeds, and the paper's drive (6.5 % in its bending dampers) is warned
// of where its 5PK preset is not.
TEST(Parameters, BeltsTablesAndTheBendingLossInInfo) {
  // the 5PK preset's softer bending: the static start's retry (scene/bending_loss_test.cpp)
  beltsim::test::expect_warnings({WarningKind::static_retry});
  // the test scene (support/scenes.hpp) with no belt table (the defaults: the paper's belt) and with
  // the 5PK preset's
  beltsim::test::TwoPulley own, pk5;
  own.assign = "local paper = ", own.belt_lines = "";
  pk5.assign = "local paper_5pk = ", pk5.belt_lines = "  belt = beltsim.belts['5PK'],\n";
  const std::string text =
      "local b = beltsim.belts['6PK']\n"
      "assert(b.preset == '6PK' and b.EI == 0.004704 and b.bending_viscosity == 8.4e-7)\n"
      "b.EI = 1\n"
      "assert(beltsim.belts['6PK'].EI == 0.004704, 'a new table each time')\n"
      "local names = {}\n"
      "for name in pairs(beltsim.belts) do names[#names + 1] = name end\n"
      "assert(table.concat(names, ' ') == '3PK 4PK 5PK 6PK 7PK 8PK')\n" +
      beltsim::test::two_pulley(own) +
      "local i = paper:info()\n"
      "assert(i.bending_loss.share > 0.05 and #i.warnings == 1, i.warnings[1])\n"
      "assert(i.warnings[1]:find('bending dampers', 1, true))\n" +
      beltsim::test::two_pulley(pk5) +
      "local p = paper_5pk:info()\n"
      "assert(p.bending_loss.share < 0.05 and #p.warnings == 0, p.warnings[1])\n"
      "beltsim.belts['9PK'] = b\n";
  EXPECT_EQ(run_text(text),
            at_line_of(text, "beltsim.belts['9PK'] = b") +
                "beltsim.belts is read-only: change the table beltsim.belts[name] returns (a new one each time)");
}

}  // namespace parameters_test
}  // namespace beltsim::script
