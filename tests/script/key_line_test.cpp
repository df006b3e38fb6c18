// key_line: the line where a script wrote the key an error is about, read from the script's text
// (comments, strings and function bodies stepped over; the tables around the key must be the
// path's); and, through a script, errors about a scene's or a run's value name that line.
#include "script/key_line.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <optional>
#include <string>

#include "run_script.hpp"
#include "scene/scene.hpp"
#include "scene/validate.hpp"
#include "script/interpreter.hpp"
#include "support/presets.hpp"
#include "support/scenes.hpp"
#include "support/scratch.hpp"

namespace beltsim::script {
namespace key_line_test {

std::optional<int> line_of(const std::string& text, int call_line, const std::string& message) {
  return key_line(text, call_line, message_path(message));
}

TEST(KeyLine, MessagePathsAsTheErrorsSpellThem) {
  auto chain = [](const std::string& m) {
    const KeyPath p = message_path(m);
    std::string s = p.pulley.empty() ? "" : "<" + p.pulley + ">";
    for (const std::string& c : p.chain) s += "/" + c;
    return s;
  };
  EXPECT_EQ(chain("belt.mass_per_length must be > 0 (got -1 kg/m)"), "/belt/mass_per_length");
  EXPECT_EQ(chain("belt.sde.k must be > 0 (got -5 N/m)"), "/belt/sde/k");
  EXPECT_EQ(chain("pulley 'driver' inertia must be > 0 (got 0 kg·m²)"), "<driver>/inertia");
  EXPECT_EQ(chain("pulley 'idler'.tensioner.stiffness must be > 0"), "<idler>/tensioner/stiffness");
  EXPECT_EQ(chain("pulley 'a' tensioner.inertia must be > 0"), "<a>/tensioner/inertia");
  EXPECT_EQ(chain("unknown key 'radus' in pulley 'driver' (did you mean 'radius'?)"), "<driver>/radus");
  EXPECT_EQ(chain("unknown key 'radus' in pulley 1 (did you mean 'radius'?)"), "/pulleys/1/radus");
  EXPECT_EQ(chain("unknown key 'c11' in contact (did you mean 'c1'?); valid keys: c1"), "/contact/c11");
  EXPECT_EQ(chain("friction.segments[2].release_time must be > 0 (got 0 s)"), "/friction/segments/2/release_time");
  EXPECT_EQ(chain("friction.segments.2.from must be >= 0"), "/friction/segments/2/from");
  EXPECT_EQ(chain("spray 1.radius must be > 0 (got 0 m)"), "/spray/1/radius");
  EXPECT_EQ(chain("unknown key 'drying_lenght' in spray 1 (did you mean 'drying_length'?)"), "/spray/1/drying_lenght");
  EXPECT_EQ(chain("spray 2: a centre {x, y} [m] is required"), "/spray/2");
  EXPECT_EQ(chain("run.frames.fps: must be in (0, 240] (got -30)"), "/run/frames/fps");
  // a path that ends at a list position names that entry (key_line finds its table's line)
  EXPECT_EQ(chain("friction.segments[2]: from and to [m] are required"), "/friction/segments/2");
  EXPECT_EQ(chain("pulley 2.name: a name is required"), "/pulleys/2/name");
  // no key: a sentence
  EXPECT_EQ(chain("the script is empty"), "/the");  // a word that no table holds as a key
  EXPECT_EQ(chain("(an error object that is a table value)"), "");
}

// a scene of its own: the layout is what these lines test (keys a comment, a string, a function's
// table or a name written later could be mistaken for), so it is written out here
const std::string kScene =
    "-- a scene with what could mislead a scan\n"                                           // 1
    "local k = 3000\n"                                                                      // 2
    "local drive = beltsim.scene {\n"                                                       // 3
    "  pulleys = {\n"                                                                       // 4
    "    { name = 'crank', centre = {0, 0}, radius = 0.08,\n"                               // 5
    "      torque = function(t, w) local radius = { radius = 1 } return 0 end },\n"         // 6
    "    { centre = {0.3, 0}, radius = 0.05,\n"                                             // 7
    "      tensioner = { pivot = {0.3, 0.1},\n"                                             // 8
    "                    stiffness = k },\n"                                                // 9
    "      name = \"idler\" },\n"                                                           // 10
    "  },\n"                                                                                // 11
    "  --[[ belt = { mass_per_length = 1 }, ]] note = 'belt = { mass_per_length = 2 }',\n"  // 12
    "  belt = { elements = 60, [\"mu\"] = 1,\n"                                             // 13
    "    mass_per_length = [[0.1]],\n"                                                      // 14
    "    sde = { k = 1 }, k = 2 },\n"                                                       // 15
    "  friction = { segments = { { from = 0, to = 0.1, mu = 1 },\n"                         // 16
    "                            { from = 0.2, to = 0.3,\n"                                 // 17
    "                              mu = 2 } } },\n"                                         // 18
    "}\n"                                                                                   // 19
    "drive:run { t_end = 1 }\n";                                                            // 20

TEST(KeyLine, FindsTheKeyWhoseTablesMatchThePath) {
  EXPECT_EQ(line_of(kScene, 3, "belt.mass_per_length must be > 0"), 14);  // not the comment's, not the string's
  EXPECT_EQ(line_of(kScene, 3, "belt.sde.k must be > 0"), 15);
  EXPECT_EQ(line_of(kScene, 3, "belt.k is beyond what double precision integrates"), 15);  // `k` of belt, not of sde
  EXPECT_EQ(line_of(kScene, 3, "belt.elements: number expected"), 13);
  EXPECT_EQ(line_of(kScene, 3, "pulley 'crank' radius must be > 0"), 5);  // not the function's local table
  EXPECT_EQ(line_of(kScene, 3, "pulley 'idler' radius must be > 0"), 7);  // its name comes after the key
  EXPECT_EQ(line_of(kScene, 3, "pulley 'idler'.tensioner.stiffness must be > 0"), 9);
  EXPECT_EQ(line_of(kScene, 3, "unknown key 'radius' in pulley 2"), 7);
  EXPECT_EQ(line_of(kScene, 3, "friction.segments[2].mu must be in [0, 10]"), 18);
  EXPECT_EQ(line_of(kScene, 3, "friction.segments.1.to must be >= 0"), 16);
  EXPECT_EQ(line_of(kScene, 3, "scene.friction.segments[1].mu"), 16);  // "scene" names the call's table
  EXPECT_EQ(line_of(kScene, 20, "run.t_end must be > 0"), 20);
  EXPECT_EQ(line_of(kScene, 3, "contact.c1 must be > 0"), std::nullopt);      // not written
  EXPECT_EQ(line_of(kScene, 3, "belt.mu must be in [0, 10]"), std::nullopt);  // written as ["mu"]
  EXPECT_EQ(line_of(kScene, 3, "pulley 'pump' radius must be > 0"), std::nullopt);
  EXPECT_EQ(line_of(kScene, 2, "belt.elements: number expected"), std::nullopt);  // no table opens on line 2
  EXPECT_EQ(line_of(kScene, 3, "friction.segments.mu"), std::nullopt);            // mu is a segment's, not the list's
  // unfinished text and nesting deeper than Lua's parser takes: no answer, no crash
  EXPECT_EQ(line_of("x = beltsim.scene { belt = { elements = 'a", 1, "belt.elements"), 1);
  EXPECT_EQ(line_of("x = beltsim.scene { " + std::string(100000, '{'), 1, "belt.elements"), std::nullopt);
  // a list position past int: no match, no exception
  EXPECT_EQ(line_of(kScene, 3, "friction.segments[99999999999999999999].mu"), std::nullopt);
  // a path that names a table: a list entry or a pulley, at the line its constructor opens on; a
  // key such a table does not hold as written, at that line too (but not in a keyed table's: the
  // tensioner's, the belt's)
  EXPECT_EQ(line_of(kScene, 3, "pulley 'idler': a centre {x, y} [m] is required"), 7);
  EXPECT_EQ(line_of(kScene, 3, "pulley 2.name: a name is required"), 10);
  EXPECT_EQ(line_of(kScene, 3, "pulley 1.name: a name is required"), 5);
  EXPECT_EQ(line_of(kScene, 3, "pulley 'idler'.inertia must be > 0"), 7);  // not written: the pulley's line
  EXPECT_EQ(line_of(kScene, 3, "friction.segments[2]: from and to [m] are required"), 17);
  EXPECT_EQ(line_of(kScene, 3, "pulley 'idler'.tensioner.damping must be >= 0"), std::nullopt);
  EXPECT_EQ(line_of(kScene, 3, "pulley 3.name: a name is required"), std::nullopt);  // no third pulley
  // a key written twice in one table: which one?
  EXPECT_EQ(line_of("x = beltsim.scene { belt = { elements = 1,\n elements = 2 } }\n", 1, "belt.elements"),
            std::nullopt);
}

// The test scene (support/scenes.hpp: its beltsim.scene on line 1, the pulleys on lines 2 to 5)
// with `belt_lines` for its belt line 6 and `before` ahead of `local s = `. The tests below are
// about the line an error names, so the belt is each test's own, its key on a line of its own;
// with no belt lines the scene's closing brace is line 6.
std::string with_belt(const std::string& belt_lines, const std::string& before = "") {
  beltsim::test::TwoPulley p;
  p.belt_lines = belt_lines;
  if (!before.empty()) p.assign = before + "local s = ";
  return beltsim::test::two_pulley(p);
}

// a scratch folder whose drive.lua each run() writes and runs; the error text it returns
struct ScriptDir {
  std::filesystem::path dir = beltsim::test::scratch_dir("beltsim_key_line_test");
  std::string file = (dir / "drive.lua").string();
  std::string run(const std::string& text) const {
    Interpreter lua;
    return test::run_script(lua, dir / "drive.lua", text, dir / "out");
  }
};

// through the interpreter: the message names the key's line; a value that the scan cannot place
// keeps the call's line
TEST(KeyLine, ScriptErrorsNameTheLineOfTheKey) {
  const ScriptDir sd;
  const std::string& file = sd.file;
  auto run = [&](const std::string& text) { return sd.run(text); };
  EXPECT_EQ(run(with_belt("  belt = {\n    pretension = -5,\n  },\n"))
                .rfind(file + ":7: belt.pretension must be > 0 (got -5 N)", 0),
            0u);
  EXPECT_EQ(run(with_belt("  belt = { pretention = 5 },\n")).rfind(file + ":6: unknown key 'pretention' in belt", 0),
            0u);
  EXPECT_EQ(run(with_belt("") + "s:run {\n  t_end = 0.01,\n  sample = -1,\n}\n").rfind(file + ":9: run.sample", 0), 0u);
  // a belt table made elsewhere: the call's line
  EXPECT_EQ(run(with_belt("  belt = b,\n", "local b = { pretension = -5 }\n"))
                .rfind(file + ":2: belt.pretension must be > 0", 0),
            0u);
}

// A spray zone's unknown key names the key's line, as a pulley's does ("in spray 1": the first
// entry of `spray`); a key left out names the zone's line
TEST(KeyLine, SprayZoneErrorsNameTheZonesLines) {
  const ScriptDir sd;
  const std::string& file = sd.file;
  const std::string unknown =
      sd.run(with_belt("  spray = {\n"                                                      // 6
                       "    { centre = {0.145, 0.1}, radius = 0.03, mu = 0.2, to = 0.5,\n"  // 7
                       "      drying_lenght = 2 } },\n"));                                  // 8
  EXPECT_EQ(unknown.rfind(file + ":8: unknown key 'drying_lenght' in spray 1", 0), 0u) << unknown;
  const std::string centre =
      sd.run(with_belt("  spray = {\n"                            // 6
                       "    { radius = 0.03, mu = 0.2 } },\n"));  // 7
  EXPECT_EQ(centre.rfind(file + ":7: spray 1: a centre {x, y} [m] is required", 0), 0u) << centre;
}

// The errors about a pulley as a whole name that pulley's line (the key at fault in it, or its
// table when the key is not written), not the line of the beltsim.scene call (1): a name that is
// nil (written without quotes) or left out, two pulleys of one name, torque and speed both given,
// two pulleys that overlap (found by validate(), which names the path of the key).
TEST(KeyLine, PulleyErrorsNameThePulleysLine) {
  const ScriptDir sd;
  // the second pulley's name line (6), centre (7) and speed line (9) as given
  auto scene = [](const std::string& name_line, const std::string& centre, const std::string& speed_line) {
    std::string text =
        "local s = beltsim.scene {\n"                              // 1
        "  pulleys = {\n"                                          // 2
        "    { name = 'driver', centre = {0, 0}, radius = 0.1,\n"  // 3
        "      torque = beltsim.ramp(0.3, -70) },\n"               // 4
        "    {\n"                                                  // 5
        "      NAME\n"                                             // 6
        "      centre = CENTRE, radius = 0.1,\n"                   // 7
        "      torque = -1,\n"                                     // 8
        "      SPEED },\n"                                         // 9
        "  },\n"                                                   // 10
        "  belt = { elements = 40 },\n"                            // 11
        "}\n";
    for (const auto& [from, to] : {std::pair{"NAME", name_line}, {"CENTRE", centre}, {"SPEED", speed_line}})
      text.replace(text.find(from), std::string_view(from).size(), to);
    return text;
  };
  const std::string& file = sd.file;
  const std::string nil_name = sd.run(scene("name = driven,", "{0.29, 0}", ""));
  EXPECT_EQ(nil_name.rfind(file + ":6: pulley 2.name: a name is required, got nil", 0), 0u) << nil_name;
  const std::string no_name = sd.run(scene("", "{0.29, 0}", ""));
  EXPECT_EQ(no_name.rfind(file + ":5: pulley 2.name: a name is required", 0), 0u) << no_name;
  const std::string control = sd.run(scene("name = 'b\\nc',", "{0.29, 0}", ""));
  EXPECT_EQ(control.rfind(file + ":6: pulley 2.name: a name may not hold a control character", 0), 0u) << control;
  const std::string twice = sd.run(scene("name = 'driver',", "{0.29, 0}", ""));
  EXPECT_EQ(twice.rfind(file + ":6: pulley 2.name: pulleys 1 and 2 are both named 'driver'", 0), 0u) << twice;
  const std::string both = sd.run(scene("name = 'driven',", "{0.29, 0}", "speed = -40,"));
  EXPECT_EQ(both.rfind(file + ":9: pulley 'driven'.speed: give either a torque or a prescribed speed, not both (got "
                              "torque = -1 and speed = -40)",
                       0),
            0u)
      << both;
  const std::string overlap = sd.run(scene("name = 'driven',", "{0.15, 0}", ""));
  EXPECT_EQ(overlap.rfind(file + ":7: pulley 'driven'.centre: pulleys 'driver' and 'driven' overlap: centres 0.15 m "
                                 "apart, radii add up to 0.2 m",
                          0),
            0u)
      << overlap;
}

// An error carries what it is about (scene/validate.hpp, ParameterError): the parameter's path and
// the value as fields, so the line comes from the path and not from the message's words. A scene
// key's error and a run key's (one found by the reader, one by the run's check) name the key's line;
// and an error reworded so that no path starts it still finds that line through its field.
TEST(KeyLine, TheLineComesFromTheErrorsPathNotItsWords) {
  const ScriptDir sd;
  const std::string& file = sd.file;
  auto run = [&](const std::string& text) { return sd.run(text); };
  const std::string scene = with_belt("  belt = {\n    mass_per_length = -1,\n  },\n");
  EXPECT_EQ(run(scene).rfind(file + ":7: belt.mass_per_length must be > 0 (got -1 kg/m)", 0), 0u) << run(scene);
  const std::string ok = with_belt("");
  // (frames.t_start after t_end: refused by the run's check, not by the reader)
  const std::string late =
      ok + "s:run {\n  t_end = 0.01,\n  frames = {\n    png = true,\n    t_start = 0.5,\n  },\n}\n";
  EXPECT_EQ(run(late).rfind(file + ":11: run.frames.t_start: must be <= t_end = 0.01 s (got 0.5 s)", 0), 0u)
      << run(late);
  const std::string atol = ok + "s:run {\n  t_end = 0.01,\n  atol = -1e-9,\n}\n";
  EXPECT_EQ(run(atol).rfind(file + ":9: run.atol: must be > 0 and finite, or left out to mean rtol (got -1e-09)", 0),
            0u)
      << run(atol);

  // the fields of the scene's error, as validate() throws it
  SceneDef d = presets::paper_dry();
  d.belt.mass_per_length = -1;
  std::optional<ParameterError> e;
  try {
    validate(d);
  } catch (const ParameterError& x) {
    e = x;
  }
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(path_text(e->path), "belt.mass_per_length");
  EXPECT_EQ(e->value, -1.0);
  EXPECT_EQ(e->unit, "kg/m");
  // reworded: its words name no key, its path still finds the line
  const ParameterError reworded(e->path, "the mass of the belt per metre cannot be negative");
  EXPECT_TRUE(message_path(reworded.what()).chain.empty() || message_path(reworded.what()).chain[0] != "belt");
  EXPECT_EQ(key_line(scene, 1, reworded.path), 7);
}

}  // namespace key_line_test
}  // namespace beltsim::script
