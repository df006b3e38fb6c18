// Checkpoints' scenes and drives (scene/scene_io.hpp) in the checkpoint text (io/checkpoint_text.hpp):
// a built scene and a changed drive come back bit for bit; a text cut short, damaged, or holding
// a scene a script could not give is refused, naming the line; counts are believed only as far
// as the text holding them goes.
#include "scene/scene_io.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "io/checkpoint_text.hpp"
#include "io/number_text.hpp"
#include "scene/parameters.hpp"
#include "scene/presets.hpp"
#include "scene/scene.hpp"
#include "support/checkpoint_edit.hpp"
#include "support/dry_scene.hpp"

namespace beltsim {
namespace {

using test::dry_scene;
using test::line_of;
using test::resealed;
using test::with_line;

bool same(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

#define EXPECT_SAME(a, b) EXPECT_TRUE(same(a, b)) << #a << ": " << (a) << " vs " << (b)

void expect_same(const Vec2& a, const Vec2& b, const char* what) {
  EXPECT_TRUE(same(a.x(), b.x()) && same(a.y(), b.y())) << what;
}
void expect_same(const double* a, const double* b, size_t na, size_t nb, const char* what) {
  ASSERT_EQ(na, nb) << what;
  for (size_t i = 0; i < na; ++i) EXPECT_TRUE(same(a[i], b[i])) << what << "[" << i << "]: " << a[i] << " vs " << b[i];
}
void expect_same(const std::vector<double>& a, const std::vector<double>& b, const char* what) {
  expect_same(a.data(), b.data(), a.size(), b.size(), what);
}
void expect_same(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const char* what) {
  expect_same(a.data(), b.data(), a.size(), b.size(), what);
}
void expect_same(const std::map<std::string, double>& a, const std::map<std::string, double>& b, const char* what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  for (auto i = a.begin(), j = b.begin(); i != a.end(); ++i, ++j) {
    EXPECT_EQ(i->first, j->first) << what;
    EXPECT_TRUE(same(i->second, j->second)) << what << "[" << i->first << "]";
  }
}

void expect_same(const TimeSpeedLaw& a, const TimeSpeedLaw& b) {
  EXPECT_SAME(a.constant, b.constant);
  EXPECT_SAME(a.per_speed, b.per_speed);
  expect_same(a.t, b.t, "law.t");
  expect_same(a.value, b.value, "law.value");
  expect_same(a.omega, b.omega, "law.omega");
  expect_same(a.omega_value, b.omega_value, "law.omega_value");
  ASSERT_EQ(a.ramps.size(), b.ramps.size());
  for (size_t k = 0; k < a.ramps.size(); ++k) {
    EXPECT_SAME(a.ramps[k].t0, b.ramps[k].t0);
    EXPECT_SAME(a.ramps[k].t1, b.ramps[k].t1);
    EXPECT_SAME(a.ramps[k].from, b.ramps[k].from);
    EXPECT_SAME(a.ramps[k].to, b.ramps[k].to);
    EXPECT_EQ(a.ramps[k].cosine, b.ramps[k].cosine);
  }
  ASSERT_EQ(a.sines.size(), b.sines.size());
  for (size_t k = 0; k < a.sines.size(); ++k) {
    EXPECT_SAME(a.sines[k].mean, b.sines[k].mean);
    EXPECT_SAME(a.sines[k].amplitude, b.sines[k].amplitude);
    EXPECT_SAME(a.sines[k].frequency, b.sines[k].frequency);
    EXPECT_SAME(a.sines[k].phase, b.sines[k].phase);
  }
  ASSERT_EQ(a.harmonics.size(), b.harmonics.size());
  for (size_t k = 0; k < a.harmonics.size(); ++k) {
    EXPECT_SAME(a.harmonics[k].order, b.harmonics[k].order);
    EXPECT_SAME(a.harmonics[k].amplitude, b.harmonics[k].amplitude);
    EXPECT_SAME(a.harmonics[k].phase, b.harmonics[k].phase);
    EXPECT_SAME(a.harmonics[k].mean_speed, b.harmonics[k].mean_speed);
  }
}

void expect_same(const Model& a, const Model& b) {
  ASSERT_EQ(a.pulleys.size(), b.pulleys.size());
  for (size_t j = 0; j < a.pulleys.size(); ++j) {
    const Pulley &p = a.pulleys[j], &q = b.pulleys[j];
    EXPECT_EQ(p.name, q.name);
    expect_same(p.centre, q.centre, "pulley.centre");
    EXPECT_SAME(p.radius, q.radius);
    EXPECT_SAME(p.inertia, q.inertia);
    EXPECT_EQ(p.wrap, q.wrap);
  }
  EXPECT_EQ(a.belt.n, b.belt.n);
  EXPECT_SAME(a.belt.pitch, b.belt.pitch);
  EXPECT_SAME(a.belt.rigid_length, b.belt.rigid_length);
  EXPECT_SAME(a.belt.mass, b.belt.mass);
  EXPECT_SAME(a.belt.rot_inertia, b.belt.rot_inertia);
  EXPECT_SAME(a.belt.k, b.belt.k);
  EXPECT_SAME(a.belt.c, b.belt.c);
  EXPECT_SAME(a.belt.kt, b.belt.kt);
  EXPECT_SAME(a.belt.ct, b.belt.ct);
  EXPECT_SAME(a.belt.e_tra, b.belt.e_tra);
  EXPECT_SAME(a.belt.e_tor, b.belt.e_tor);
  EXPECT_SAME(a.contact.c1, b.contact.c1);
  EXPECT_SAME(a.contact.c2, b.contact.c2);
  EXPECT_SAME(a.contact.b, b.contact.b);
  EXPECT_SAME(a.contact.p_max, b.contact.p_max);
  EXPECT_SAME(a.friction.dv, b.friction.dv);
  EXPECT_EQ(a.friction.law, b.friction.law);
  EXPECT_SAME(a.friction.static_ratio, b.friction.static_ratio);
  EXPECT_SAME(a.friction.stribeck_speed, b.friction.stribeck_speed);
  EXPECT_SAME(a.friction.exponent, b.friction.exponent);
  EXPECT_SAME(a.friction.viscous, b.friction.viscous);
  EXPECT_SAME(a.gravity, b.gravity);
  EXPECT_EQ(a.track_energy, b.track_energy);
}

void expect_same(const Drive& a, const Drive& b) {
  ASSERT_EQ(a.pulleys.size(), b.pulleys.size());
  for (size_t j = 0; j < a.pulleys.size(); ++j) {
    const PulleyDrive &p = a.pulleys[j], &q = b.pulleys[j];
    EXPECT_EQ(p.kinematic, q.kinematic);
    expect_same(p.torque, q.torque);
    expect_same(p.speed, q.speed);
  }
  expect_same(a.mu, b.mu, "mu");
  EXPECT_SAME(a.restart_time, b.restart_time);
}

void expect_same(const Scene& a, const Scene& b) {
  expect_same(a.model, b.model);
  expect_same(a.drive, b.drive);
  expect_same(a.y0, b.y0, "y0");
  ASSERT_EQ(a.route.spans.size(), b.route.spans.size());
  for (size_t k = 0; k < a.route.spans.size(); ++k) {
    expect_same(a.route.spans[k].from, b.route.spans[k].from, "span.from");
    expect_same(a.route.spans[k].to, b.route.spans[k].to, "span.to");
    EXPECT_SAME(a.route.spans[k].length, b.route.spans[k].length);
  }
  ASSERT_EQ(a.route.arcs.size(), b.route.arcs.size());
  for (size_t k = 0; k < a.route.arcs.size(); ++k) {
    const Route::Arc &p = a.route.arcs[k], &q = b.route.arcs[k];
    expect_same(p.centre, q.centre, "arc.centre");
    EXPECT_SAME(p.radius, q.radius);
    EXPECT_EQ(p.sense, q.sense);
    EXPECT_SAME(p.start_angle, q.start_angle);
    EXPECT_SAME(p.angle, q.angle);
  }
  EXPECT_SAME(a.route.length, b.route.length);
  EXPECT_EQ(a.route_names, b.route_names);
  EXPECT_EQ(a.route_pulleys, b.route_pulleys);
  expect_same(a.penetration, b.penetration, "penetration");
  EXPECT_EQ(a.reading, b.reading);
  EXPECT_SAME(a.static_tension, b.static_tension);
  EXPECT_SAME(a.static_residual, b.static_residual);
  EXPECT_EQ(a.static_retried, b.static_retried);
  EXPECT_EQ(a.span_sde, b.span_sde);
  ASSERT_EQ(a.sites.size(), b.sites.size());
  for (size_t i = 0; i < a.sites.size(); ++i) {
    const ElementSite &p = a.sites[i], &q = b.sites[i];
    EXPECT_EQ(p.index, q.index);
    expect_same(p.centre, q.centre, "site.centre");
    EXPECT_SAME(p.s, q.s);
    EXPECT_SAME(p.length, q.length);
    EXPECT_EQ(p.pulley, q.pulley);
    expect_same(p.meets, q.meets, "site.meets");
    expect_same(p.leaves, q.leaves, "site.leaves");
  }
}

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
    EXPECT_EQ(std::string(e.what()), "line 3: 'pulley.drive': expected the drive of pulley 'driver'");
  }
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
            "line 1: a version 4 checkpoint; this beltsim reads version " + std::to_string(kCheckpointVersion) +
                " only: resume it with the beltsim that wrote it, or run the scene again from its script");
  // version 5 held each input's unit and note; 6 takes them from the parameter table; 7 holds spray zones, the
  // friction law and the couplings; 8 LuGre's parameters, the bristles' deflections and the run's keep_states;
  // 9 the frames' paths as given (relative ones inside the output folder), not joined to the folder
  for (const int v : {5, 6, 7, 8})
    EXPECT_EQ(read_error("beltsim-checkpoint " + std::to_string(v) + "\nscene 4\n"),
              "line 1: a version " + std::to_string(v) +
                  " checkpoint; this beltsim reads version " + std::to_string(kCheckpointVersion) +
                  " only: resume it "
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
            "line " + std::to_string(line_of(text, "belt.mu")) + ": 'belt.mu': 60 values, more than the 59 this " +
                "checkpoint's scene has room for");
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
  // a law a script could not give
  EXPECT_EQ(read_error(resealed(with_line(text, "pulley.torque.table", "pulley.torque.table 2 0.1 1 0.05 2"))),
            "line " + std::to_string(line_of(text, "pulley.torque.harmonics")) +
                ": 'pulley.torque.harmonics': pulley 'driver'.torque.table entry 2 must be larger than the entry "
                "before it (got 0.05 s)");
}

}  // namespace
}  // namespace beltsim
