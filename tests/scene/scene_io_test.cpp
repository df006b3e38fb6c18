// Checkpoints' scenes and drives (scene/scene_io.hpp) in the checkpoint text (io/checkpoint_text.hpp):
// a built scene and a changed drive come back bit for bit; a text cut short, damaged, or holding
// a scene a script could not give is refused, naming the line; counts are believed only as far
// as the text holding them goes.
#include "scene/scene_io.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "io/checkpoint_text.hpp"
#include "io/number_text.hpp"
#include "scene/parameters.hpp"
#include "support/presets.hpp"
#include "scene/scene.hpp"
#include "support/checkpoint_edit.hpp"
#include "support/dry_scene.hpp"

namespace beltsim {
namespace {

using test::dry_scene;
using test::line_of;
using test::resealed;
using test::with_line;

// every field a checkpoint holds is the same, bit for bit (the fields' lists, scene/scene_fields.hpp)
void expect_same(const Scene& a, const Scene& b) { EXPECT_EQ(scene_difference(a, b), ""); }
void expect_same(const Drive& a, const Drive& b) { EXPECT_EQ(drive_difference(a, b), ""); }

std::string scene_text(const Scene& sc) {
  CheckpointWriter w;
  write_scene(w, sc);
  return w.finish();
}

Scene read_whole(const std::string& text) {
  CheckpointReader r(text);
  Scene sc = read_scene(r);
  r.finish();
  return sc;
}

Scene round_trip(const Scene& sc) { return read_whole(scene_text(sc)); }

// what reading `text` throws, "" when it reads
std::string read_error(const std::string& text) {
  try {
    read_whole(text);
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

// four pulleys with a back-side idler (its name with a space and a quote), a kinematic alternator
// driven by a speed table, energy tracking
const Scene& automotive() {
  static const Scene sc = [] {
    SceneDef d = presets::automotive_wet();
    d.pulleys[1].name = "back \"idler\"";
    PulleyDef& alt = d.pulleys[2];
    alt.kinematic = true;
    alt.speed.t = {0.0, 0.1, 0.25};
    alt.speed.value = {0.0, -30.0, -45.5};
    d.track_energy = true;
    return build_scene(d);
  }();
  return sc;
}

TEST(SceneIo, DryScene) {
  const Scene& sc = dry_scene();
  ASSERT_EQ(sc.route.spans.size(), 2u);
  ASSERT_FALSE(sc.sites.empty());
  expect_same(sc, round_trip(sc));
}

TEST(SceneIo, AutomotiveScene) {
  const Scene& sc = automotive();
  ASSERT_EQ(sc.model.pulleys[1].wrap, WrapSide::back);
  ASSERT_TRUE(sc.drive.pulleys[2].kinematic);
  ASSERT_EQ(sc.drive.pulleys[2].speed.t.size(), 3u);
  ASSERT_EQ(sc.sites[0].meets.size(), 4u);
  expect_same(sc, round_trip(sc));
}

// Stribeck's law and its parameters come back (the automotive scene's law and values replaced)
TEST(SceneIo, StribeckScene) {
  Scene sc = automotive();
  sc.model.friction.law = FrictionKind::stribeck;
  sc.model.friction.static_ratio = 1.0 / 0.7;
  sc.model.friction.stribeck_speed = 0.003;
  sc.model.friction.exponent = 0.75;
  sc.model.friction.viscous = 1.0 / 300;
  const Scene back = round_trip(sc);
  EXPECT_EQ(back.model.friction.law, FrictionKind::stribeck);
  expect_same(sc, back);
}

// LuGre's law: its parameters and the bristles' deflections, a part of the state, come back
TEST(SceneIo, LugreScene) {
  SceneDef d = presets::paper_dry();
  d.friction.law = FrictionKind::lugre;
  d.friction.bristle_stiffness = 3.0e4, d.friction.bristle_damping = 0.125, d.friction.release_time = 2.5e-3;
  Scene sc = build_scene(d);
  ASSERT_EQ(sc.y0.size(), sc.model.n_state());
  for (int i = 0; i < sc.model.n_bristle(); ++i) sc.y0[sc.model.bristle_offset() + i] = 1e-5 * std::sin(i + 0.5);
  const Scene back = round_trip(sc);
  EXPECT_EQ(back.model.friction.law, FrictionKind::lugre);
  EXPECT_EQ(back.model.friction.bristle_stiffness, 3.0e4);
  EXPECT_EQ(back.model.friction.bristle_damping, 0.125);
  EXPECT_EQ(back.model.friction.release_time, 2.5e-3);
  expect_same(sc, back);
}

// friction segments: their laws and each element's law come back; a law number past the
// segments' count is refused with its line
TEST(SceneIo, FrictionSegments) {
  SceneDef d = presets::paper_dry();
  Friction st = d.friction, lu = d.friction;
  st.law = FrictionKind::stribeck, st.static_ratio = 1.7;
  lu.law = FrictionKind::lugre, lu.bristle_stiffness = 2.5e4;
  d.friction_segments = {{0.1, 0.4, st}, {0.9, 0.05, lu}};  // the second wraps round past s = 0
  const Scene sc = build_scene(d);
  const Scene back = round_trip(sc);
  ASSERT_EQ(back.model.laws.size(), 2u);
  EXPECT_EQ(back.model.laws[0].static_ratio, 1.7);
  EXPECT_EQ(back.model.laws[1].law, FrictionKind::lugre);
  EXPECT_EQ(back.model.laws[1].bristle_stiffness, 2.5e4);
  EXPECT_EQ(back.model.law_of, sc.model.law_of);
  EXPECT_EQ(back.model.n_state(), sc.model.n_state());
  expect_same(sc, back);
}

// the shortest decimal of every double reads back as that double: signed zero, subnormals, the
// largest, thirds; strings with quotes, backslashes, newlines and '#'
TEST(SceneIo, ExactValues) {
  Scene sc = dry_scene();
  sc.y0[0] = -0.0;
  sc.y0[1] = std::numeric_limits<double>::denorm_min();
  sc.y0[2] = -std::numeric_limits<double>::max();
  sc.y0[3] = 1.0 / 3;
  sc.static_residual = std::numeric_limits<double>::min();
  sc.sites[0].pulley = "a name\nwith \\ \"odd\" # characters";
  sc.reading = StiffnessReading::per_sde;
  const Scene back = round_trip(sc);
  expect_same(sc, back);
  EXPECT_TRUE(std::signbit(back.y0[0]));
  EXPECT_EQ(number_text(1.0 / 3), "0.3333333333333333");
}

// the drive a run changes (laws with every kind of term, kinematic or not, μ per element, the
// restart time) comes back for the model of the same scene
TEST(SceneIo, DriveRoundTrip) {
  const Scene& sc = automotive();
  Drive m = sc.drive;
  m.mu[3] = 0.123456789;
  TimeSpeedLaw& law = m.pulleys[0].torque;
  law.per_speed = -0.25;
  law.omega = {0.0, 1.0 / 3};
  law.omega_value = {2.0 / 3, -0.0};
  law.ramps = {{0.1, 0.3, 1.0 / 7, -2.0, true}, {0.2, 0.2, 0.0, 5e-300, false}};
  law.sines = {{1.0, 1.0 / 9, 50.0, M_PI}};
  law.harmonics = {{0.5, 1.0 / 11, -1.0, 83.77580409572781}};
  m.pulleys[2].speed.sines = {{-40.0, 1.0 / 9, 50.0, M_PI}};
  m.pulleys[0].kinematic = true;  // driven by its speed now, its torque law kept
  m.pulleys[0].speed.constant = 12.5;
  m.restart_time = 0.2;
  CheckpointWriter w;
  write_drive(w, sc.model, m);
  const std::string text = w.finish();
  CheckpointReader r(text);
  const Drive back = read_drive(r, sc.model);
  r.finish();
  expect_same(m, back);
  // for the model of another scene: refused
  const Model& other = dry_scene().model;
  CheckpointReader r2(text);
  try {
    read_drive(r2, other);
    ADD_FAILURE() << "read a drive of other pulleys";
  } catch (const CheckpointError& e) {
    EXPECT_EQ(std::string(e.what()), "line " + std::to_string(line_of(text, "belt.mu")) + ": 'belt.mu': " +
                                         std::to_string(sc.model.n_el()) + " values for 60 elements");
  }
}

// The definition a built scene gives back (what a checkpoint's scene is validated as) is the one
// it was built from in every field the scene keeps: the pulleys, the tensioner arm, a one-way
// coupling, the belt's per-SDE values, contact, friction and gravity; and the belt's mass per
// metre of rest length, which the build multiplies by an element's rest length l0 (m = ρ·l0,
// build::set_rest_length), not by its pitch: the belt at rest is stretched, l > l0.
TEST(SceneIo, TheDefinitionIsTheOneTheSceneWasBuiltFrom) {
  SceneDef d = presets::automotive_tensioner();
  CouplingDef& cd = d.pulleys[2].coupling.emplace();
  cd.inertia = 2e-3, cd.stiffness = 40, cd.one_way = true;
  d.track_energy = true;
  const Scene sc = build_scene(d);
  const Belt& belt = sc.model.belt;
  ASSERT_GT(belt.pitch / belt.rigid_length - 1, 1e-4);  // stretched: per pitch and per l0 differ
  const SceneDef back = definition(sc);
  // ρ·l0/l0: two roundings, each within half an ulp of the value
  EXPECT_NEAR(back.belt.mass_per_length, d.belt.mass_per_length, 4e-16 * d.belt.mass_per_length);
  ASSERT_EQ(back.pulleys.size(), d.pulleys.size());
  for (size_t j = 0; j < d.pulleys.size(); ++j) {
    const PulleyDef &a = d.pulleys[j], &b = back.pulleys[j];
    EXPECT_EQ(b.name, a.name);
    EXPECT_EQ(b.centre, a.centre) << a.name;
    EXPECT_EQ(b.radius, a.radius) << a.name;
    EXPECT_EQ(b.inertia, a.inertia) << a.name;
    EXPECT_EQ(b.wrap, a.wrap) << a.name;
    EXPECT_EQ(b.kinematic, a.kinematic) << a.name;
    EXPECT_EQ(b.tensioner.has_value(), a.tensioner.has_value()) << a.name;
    EXPECT_EQ(b.coupling.has_value(), a.coupling.has_value()) << a.name;
  }
  const TensionerDef &t = *d.pulleys[1].tensioner, &tb = *back.pulleys[1].tensioner;
  EXPECT_EQ(tb.pivot, t.pivot);
  for (const auto& [x, y] : {std::pair{tb.inertia, t.inertia},
                             {tb.stiffness, t.stiffness},
                             {tb.damping, t.damping},
                             {tb.friction_torque, t.friction_torque},
                             {tb.friction_speed, t.friction_speed},
                             {tb.asymmetric, t.asymmetric}})
    EXPECT_EQ(x, y);
  const CouplingDef& cb = *back.pulleys[2].coupling;
  for (const auto& [x, y] : {std::pair{cb.inertia, cd.inertia},
                             {cb.stiffness, cd.stiffness},
                             {cb.damping, cd.damping},
                             {cb.hub_inertia, cd.hub_inertia},
                             {cb.lock_damping, cd.lock_damping},
                             {cb.drag_torque, cd.drag_torque}})
    EXPECT_EQ(x, y);
  EXPECT_EQ(cb.one_way, cd.one_way);
  EXPECT_EQ(back.belt.elements, d.belt.elements);
  EXPECT_EQ(back.belt.k, belt.k);
  EXPECT_EQ(back.belt.ct, belt.ct);
  EXPECT_EQ(back.belt.rest_length, belt.rigid_length * belt.n);
  EXPECT_EQ(back.contact.c1, sc.model.contact.c1);
  EXPECT_EQ(back.friction.dv, d.friction.dv);
  EXPECT_EQ(back.gravity, d.gravity);
  EXPECT_EQ(back.track_energy, d.track_energy);
  EXPECT_EQ(back.belt.mu_per_element, sc.drive.mu);
}

// the comparison (scene_difference, the fields' lists) names the first field that differs, bit for
// bit: a -0 for a 0 too, in the state, a law, an element site
TEST(SceneIo, TheDifferenceNamesTheFirstFieldThatDiffers) {
  const Scene& sc = automotive();
  EXPECT_EQ(scene_difference(sc, sc), "");
  auto changed = [&](const std::function<void(Scene&)>& change) {
    Scene other = sc;
    change(other);
    return scene_difference(sc, other);
  };
  EXPECT_EQ(changed([](Scene& s) { s.model.belt.k *= 1 + 1e-16 * 4; }), "belt.sde.k");
  EXPECT_EQ(changed([](Scene& s) { s.model.pulleys[2].centre.y() += 1e-9; }), "pulley.centre [2]");
  EXPECT_EQ(changed([](Scene& s) { s.model.friction.release_time = 1; }), "friction.release_time");
  EXPECT_EQ(changed([](Scene& s) { s.y0[4] = s.y0[4] == 0 ? -0.0 : -s.y0[4]; }), "y0");
  EXPECT_EQ(changed([](Scene& s) { s.drive.pulleys[0].torque.constant += 1; }), "pulley.torque [0]");
  EXPECT_EQ(changed([](Scene& s) { s.drive.mu[7] = 0.5; }), "belt.mu");
  EXPECT_EQ(changed([](Scene& s) { s.sites[9].leaves.begin()->second += 1; }), "site.leaves [9]");
  EXPECT_EQ(changed([](Scene& s) { s.static_retried = !s.static_retried; }), "static_retried");
  EXPECT_EQ(changed([](Scene& s) { s.inputs.pop_back(); }), "input. (count)");
}

// the keys are the scenario's Lua names
TEST(SceneIo, KeysAreTheLuaNames) {
  const std::string text = scene_text(dry_scene());
  for (const char* key : {"\npulley.inertia ", "\nbelt.sde.k ", "\ncontact.damping ", "\ncontact.p_max ",
                          "\nfriction.dv ", "\nenergy false\n", "\nbelt.mu 60 ", "\npulley.torque.constant "})
    EXPECT_NE(text.find(key), std::string::npos) << key;
  EXPECT_EQ(text.find("\ncontact.b "), std::string::npos);
}

TEST(SceneIo, CutShortIsRefusedNamingTheLine) {
  const std::string text = scene_text(automotive());
  // anywhere in the text, and at every character of the last lines
  std::vector<size_t> cuts;
  for (size_t k = 0; k < 300; ++k) cuts.push_back(k * text.size() / 300);
  for (size_t k = text.size() > 200 ? text.size() - 200 : 0; k < text.size(); ++k) cuts.push_back(k);
  for (size_t cut : cuts) {
    const std::string e = read_error(text.substr(0, cut));
    EXPECT_EQ(e.rfind("line ", 0), 0u) << "cut at " << cut << " of " << text.size() << ": '" << e << "'";
  }
  // cut after a whole line: the last line is not the checksum
  const size_t at = text.find("\nstatic_residual ");
  ASSERT_NE(at, std::string::npos);
  const std::string cut = text.substr(0, at + 1);
  EXPECT_EQ(read_error(cut), "line " + std::to_string(line_of(text, "static_residual") - 1) + ": 'static_tension " +
                                 number_text(automotive().static_tension).substr(0, 25) +
                                 "' where the checksum line should end the file: it was cut short or damaged");
  // a whole line missing, the rest sealed again: the line that comes instead is named
  const size_t end = text.find('\n', at + 1);
  EXPECT_EQ(read_error(resealed(text.substr(0, at + 1) + text.substr(end + 1))),
            "line " + std::to_string(line_of(text, "static_residual")) +
                ": expected 'static_residual', got 'static_retried'");
}

TEST(SceneIo, WrongKeywordOrVersionIsRefused) {
  const std::string text = scene_text(dry_scene());
  EXPECT_EQ(read_error(resealed(with_line(text, "belt.pitch", "belt.pitck 0.01"))),
            "line " + std::to_string(line_of(text, "belt.pitch")) + ": expected 'belt.pitch', got 'belt.pitck'");
  // unsealed: the same, and the checksum's verdict
  EXPECT_EQ(read_error(with_line(text, "belt.pitch", "belt.pitck 0.01")),
            "line " + std::to_string(line_of(text, "belt.pitch")) +
                ": expected 'belt.pitch', got 'belt.pitck' (and the file does not match its checksum, line " +
                std::to_string(std::count(text.begin(), text.end(), '\n')) +
                ": it was damaged or changed after it was written)");
  EXPECT_EQ(read_error("beltsim-checkpoint 4\nscene 4\n"),
            "line 1: a version 4 checkpoint; this beltsim reads versions 12 to 14 only: resume it with the beltsim "
            "that wrote it, or run the scene again from its script");
  // version 5 held each input's unit and note; 6 takes them from the parameter table; 7 holds spray zones, the
  // friction law and the couplings; 8 LuGre's parameters, the bristles' deflections and the run's keep_states;
  // 9 the frames' paths as given (relative ones inside the output folder), not joined to the folder; 10 each
  // struct's fields by its list (scene/scene_fields.hpp) and each part of the run's state by its struct
  // (sim/state_io.hpp); 13 the outputs' fingerprints, read from 12 on without them; 14 the arms' and
  // couplings' energy integrals (and one after this beltsim's is refused too)
  for (const int v : {5, 6, 7, 8, 9, 11, 15})
    EXPECT_EQ(read_error("beltsim-checkpoint " + std::to_string(v) + "\nscene 4\n"),
              "line 1: a version " + std::to_string(v) +
                  " checkpoint; this beltsim reads versions 12 to 14 only: resume it "
                  "with the beltsim that wrote it, or run the scene again from its script");
  EXPECT_EQ(read_error("scene 4\nmodel 4\n"), "line 1: not a beltsim checkpoint (it begins 'scene 4')");
  EXPECT_EQ(read_error(resealed(with_line(text, "pulley.wrap", "pulley.wrap outside"))),
            "line " + std::to_string(line_of(text, "pulley.wrap")) +
                ": 'pulley.wrap': expected inside or back, got 'outside'");
}

// the scene's inputs (parameters.csv's first rows) keep their names, values and sources; their
// units and notes come back from the parameter table, which must know every name
TEST(SceneIo, InputsComeBackWithTheTablesUnitsAndNotes) {
  for (const Scene* sc : {&dry_scene(), &automotive()}) {
    const Scene back = round_trip(*sc);
    ASSERT_EQ(back.inputs.size(), sc->inputs.size());
    for (size_t i = 0; i < sc->inputs.size(); ++i) {
      const SceneInput &a = sc->inputs[i], &b = back.inputs[i];
      EXPECT_EQ(b.name, a.name);
      EXPECT_EQ(std::memcmp(&b.value, &a.value, sizeof a.value), 0) << a.name;
      EXPECT_EQ(b.text, a.text) << a.name;
      EXPECT_EQ(b.unit, a.unit) << a.name;
      EXPECT_EQ(b.given, a.given) << a.name;
      EXPECT_EQ(b.note, a.note) << a.name;
    }
  }
  const std::string text = scene_text(dry_scene());
  EXPECT_EQ(read_error(resealed(with_line(text, "input.name", "input.name \"belt.stiffness\""))),
            "line " + std::to_string(line_of(text, "input.name")) +
                ": 'input.name': 'belt.stiffness' is not a scene parameter");
  // a pulley's key under another pulley's name is no parameter either
  EXPECT_EQ(read_error(resealed(with_line(text, "input.name", "input.name \"pulley.nobody.radius\""))),
            "line " + std::to_string(line_of(text, "input.name")) +
                ": 'input.name': 'pulley.nobody.radius' is not a scene parameter");
}

// the scene's fields a scenario gives are under the scenario's keys, the parameter table's
// (contact.damping, not the model's contact.b); the rest are values the build derives or the drive's
TEST(SceneIo, TheScenarioFieldsAreUnderTheTablesKeys) {
  const std::string text = scene_text(automotive());
  const std::set<std::string> derived{"belt.pitch", "belt.rigid_length", "belt.mass", "belt.rot_inertia"};
  int found = 0;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    const std::string key = line.substr(0, line.find(' '));
    if (key == "y0") break;  // the state and what the build derived follow
    const bool scenario = key.rfind("belt.", 0) == 0 || key.rfind("contact.", 0) == 0 ||
                          key.rfind("friction.", 0) == 0 || key == "gravity" ||
                          (key.rfind("pulley.", 0) == 0 && key.rfind("pulley.drive", 0) != 0 &&
                           key.rfind("pulley.torque", 0) != 0 && key.rfind("pulley.speed", 0) != 0);
    if (!scenario || derived.count(key)) continue;
    EXPECT_NE(find_parameter(key), nullptr) << key;
    ++found;
  }
  EXPECT_GE(found, 20);
}

// a value changed without a sign in its syntax: only the checksum sees it
TEST(SceneIo, ChecksumCatchesAChangedValue) {
  const std::string text = scene_text(dry_scene());
  const std::string changed = with_line(text, "belt.mass", "belt.mass 1");
  const int last = static_cast<int>(std::count(text.begin(), text.end(), '\n'));
  EXPECT_EQ(read_error(changed), "line " + std::to_string(last) +
                                     ": the checksum does not match the text before it: the file was damaged or "
                                     "changed after it was written");
  EXPECT_EQ(read_error(resealed(changed)), "");
}

// numbers are whole decimal numbers, finite where the field needs it; nothing else passes
TEST(SceneIo, NumbersAreStrict) {
  const std::string text = scene_text(dry_scene());
  const std::string line = std::to_string(line_of(text, "contact.c2"));
  for (const char* bad : {"0x1.3d6p+19", "0x", "1e", "1.5.2", "+3", "6.5e5x", "1e999", "--1", "1,5", ""})
    EXPECT_EQ(read_error(resealed(with_line(text, "contact.c2", std::string("contact.c2 ") + bad))),
              "line " + line + ": 'contact.c2': " +
                  (*bad ? "expected a number, got '" + std::string(bad) + "'"
                        : std::string("an empty value (two spaces in a row, or a space at the end of the line)")))
        << bad;
  for (const char* bad : {"inf", "-inf", "nan"})
    EXPECT_EQ(read_error(resealed(with_line(text, "contact.c2", std::string("contact.c2 ") + bad))),
              "line " + line + ": 'contact.c2': expected a finite number, got " + bad)
        << bad;
  EXPECT_EQ(read_error(resealed(with_line(text, "contact.c2", "contact.c2 650000 1"))),
            "line " + line + ": 'contact.c2': unexpected ' 1' after the values");
  EXPECT_EQ(read_error(resealed(with_line(text, "contact.c2", "contact.c2  650000"))),
            "line " + line + ": 'contact.c2': an empty value (two spaces in a row, or a space at the end of the line)");
}

// a count is believed only as far as the line (or the file) holds its values, and the scene its
// entries: a huge one allocates nothing
TEST(SceneIo, CountsAreBoundedByTheTextAndTheScene) {
  const std::string text = scene_text(dry_scene());
  EXPECT_EQ(read_error(resealed(with_line(text, "belt.mu", "belt.mu 1000000000 0.5"))),
            "line " + std::to_string(line_of(text, "belt.mu")) +
                ": 'belt.mu': 1000000000 values announced, the line holds 1");
  EXPECT_EQ(read_error(resealed(with_line(text, "pulleys", "pulleys 4000000000"))),
            "line 2: 'pulleys': 4000000000 entries of 5 lines announced, the file has " +
                std::to_string(std::count(text.begin(), text.end(), '\n') - 3) + " lines left");
  EXPECT_EQ(
      read_error(resealed(with_line(text, "sites", "sites 99999999999999999999"))),
      "line " + std::to_string(line_of(text, "sites")) + ": 'sites': expected an integer, got '99999999999999999999'");
  // the element count must agree with every per-element list
  EXPECT_EQ(read_error(resealed(with_line(text, "belt.elements", "belt.elements 59"))),
            "line " + std::to_string(line_of(text, "belt.mu")) + ": 'belt.mu': 60 values for 59 elements");
}

// the scene is checked as a script's scene is (validate(SceneDef)), with the scenario's names
TEST(SceneIo, SceneIsValidatedAsAScriptsScene) {
  const std::string text = scene_text(dry_scene());
  const std::string lines = "lines 2 to " + std::to_string(std::count(text.begin(), text.end(), '\n') - 1) + ": the scene: ";
  EXPECT_EQ(read_error(resealed(with_line(text, "pulley.inertia", "pulley.inertia -1"))),
            lines + "pulley 'driver'.inertia must be > 0 (got -1 kg·m²)");
  EXPECT_EQ(read_error(resealed(with_line(text, "contact.p_max", "contact.p_max 0"))),
            lines + "contact.p_max must be > 0 (got 0 m)");
  EXPECT_EQ(read_error(resealed(with_line(text, "friction.dv", "friction.dv 0"))),
            lines + "friction.dv " + std::string(rule_text(Rule::slip_band)) + " (got 0 m/s)");
  EXPECT_EQ(read_error(resealed(with_line(text, "belt.sde.k", "belt.sde.k -5"))),
            lines + "belt.sde.k must be > 0 (got -5 N/m)");
  // μ (in the drive, read first): negative, or a list of the wrong length
  std::string mu = "belt.mu 60 -0.5";
  for (int i = 1; i < 60; ++i) mu += " 0.3";
  EXPECT_EQ(read_error(resealed(with_line(text, "belt.mu", mu))),
            "line " + std::to_string(line_of(text, "belt.mu")) + ": 'belt.mu': belt.mu of element 0 " +
                std::string(rule_text(Rule::friction_coefficient)) + " (got -0.5)");
  EXPECT_EQ(read_error(resealed(with_line(text, "belt.mu", "belt.mu 2 0.3 0.3"))),
            "line " + std::to_string(line_of(text, "belt.mu")) + ": 'belt.mu': 2 values for 60 elements");
  // a law a script could not give: the lines of its pulley's drive
  EXPECT_EQ(read_error(resealed(with_line(with_line(text, "pulley.torque.table.t", "pulley.torque.table.t 2 0.1 0.05"),
                                          "pulley.torque.table.value", "pulley.torque.table.value 2 1 2"))),
            "lines " + std::to_string(line_of(text, "pulley.drive")) + " to " +
                std::to_string(line_of(text, "pulley.speed.harmonics")) +
                ": pulley 'driver'.torque.table entry 2 must be larger than the entry before it (got 0.05 s)");
}

}  // namespace
}  // namespace beltsim
