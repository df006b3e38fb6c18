// Checkpoints (scene/scene_io.hpp): a built scene, a model, a law and vectors come back bit for
// bit through text; truncated or altered text throws, naming the field that was expected.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "scene/presets.hpp"
#include "scene/scene.hpp"
#include "scene/scene_io.hpp"

namespace beltsim {
namespace {

// bit-equal, or both NaN (a NaN's payload is not kept)
bool same(double a, double b) {
  return (std::isnan(a) && std::isnan(b) && std::signbit(a) == std::signbit(b)) ||
         std::memcmp(&a, &b, sizeof a) == 0;
}

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

Scene round_trip(const Scene& sc) {
  std::stringstream s;
  write_scene(s, sc);
  return read_scene(s);
}

// the message of what `read` throws on `text`, "" when it does not throw
template <class F>
std::string error_of(const std::string& text, F read) {
  std::istringstream s(text);
  try {
    read(s);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

const Scene& dry() {
  static const Scene sc = build_scene(presets::paper_dry());
  return sc;
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
  const Scene& sc = dry();
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

TEST(SceneIo, SpecialValues) {
  Scene sc = dry();
  sc.static_residual = std::numeric_limits<double>::quiet_NaN();
  sc.static_tension = -std::numeric_limits<double>::quiet_NaN();
  sc.y0[0] = -0.0;
  sc.y0[1] = std::numeric_limits<double>::denorm_min();
  sc.y0[2] = -std::numeric_limits<double>::infinity();
  sc.y0[3] = std::numeric_limits<double>::max();
  sc.drive.pulleys[0].torque.constant = std::numeric_limits<double>::infinity();
  sc.sites[0].pulley = "a name\nwith \\ \"odd\" # characters";
  sc.reading = StiffnessReading::per_sde;
  const Scene back = round_trip(sc);
  expect_same(sc, back);
  EXPECT_TRUE(std::isnan(back.static_residual));
  EXPECT_TRUE(std::signbit(back.static_tension));
  EXPECT_TRUE(std::signbit(back.y0[0]));
}

TEST(SceneIo, ModelDriveLawVectorsInOneStream) {
  const Scene& sc = automotive();
  const Model& m = sc.model;
  Drive d = sc.drive;
  d.mu[3] = 0.123456789;
  const std::vector<double> v = {1.0 / 3, -0.0, 1e-310};
  // every kind of law term, with values that need all 17 digits
  TimeSpeedLaw& law = d.pulleys[2].speed;
  law.omega = {0.0, 1.0 / 3};
  law.omega_value = {2.0 / 3, -0.0};
  law.ramps = {{0.1, 0.3, 1.0 / 7, -2.0, true}, {0.2, 0.2, 0.0, 5e-300, false}};
  law.sines = {{1.0, 1.0 / 9, 50.0, M_PI}};
  law.harmonics = {{0.5, 1.0 / 11, -1.0, 83.77580409572781}};
  d.restart_time = 0.2;
  std::stringstream s;
  s.imbue(std::locale::classic());
  s << std::hex << std::setw(12);  // the writers do not depend on the caller's flags...
  write_model(s, m);
  write_drive(s, d);
  write_law(s, d.pulleys[2].speed, "alternator.speed");
  write_vector(s, sc.y0, "y");
  write_vector(s, v);
  EXPECT_TRUE(s.flags() & std::ios_base::hex);  // ...and leave them as they were
  expect_same(m, read_model(s));
  expect_same(d, read_drive(s));
  expect_same(d.pulleys[2].speed, read_law(s, "alternator.speed"));
  expect_same(sc.y0, read_vector(s, "y"), "y");
  expect_same(v, read_std_vector(s), "vector");
  EXPECT_NE(error_of(s.str(), [](std::istream& in) { read_law(in, "law"); }).find("expected 'law.constant'"),
            std::string::npos);
}

TEST(SceneIo, TruncatedInputThrowsNamingTheField) {
  std::stringstream s;
  write_scene(s, automotive());
  const std::string text = s.str();
  // anywhere in the text, and at every character of the last lines
  std::vector<size_t> cuts;
  for (size_t k = 0; k < 300; ++k) cuts.push_back(k * text.size() / 300);
  for (size_t k = text.size() > 200 ? text.size() - 200 : 0; k < text.size(); ++k) cuts.push_back(k);
  for (size_t cut : cuts) {
    const std::string e = error_of(text.substr(0, cut), read_scene);
    EXPECT_EQ(e.rfind("checkpoint: ", 0), 0u) << "cut at " << cut << " of " << text.size() << ": '" << e << "'";
  }
  // cut before a whole line: that field is named
  const size_t at = text.find("\nstatic_residual ");
  ASSERT_NE(at, std::string::npos);
  EXPECT_EQ(error_of(text.substr(0, at + 1), read_scene),
            "checkpoint: expected 'static_residual', got the end of the input");
  // cut inside a line (inside a number)
  const size_t y0 = text.find("\ny0 ");
  EXPECT_NE(error_of(text.substr(0, y0 + 40), read_scene).find("'y0'"), std::string::npos);
  // a sequence shorter than its count
  std::string shorter = text;
  const size_t mu = shorter.find("\nmu 150 ");
  ASSERT_NE(mu, std::string::npos);
  shorter.replace(mu, 7, "\nmu 151 ");
  EXPECT_EQ(error_of(shorter, read_scene), "checkpoint: 'mu': expected a number, got the end of the line");
}

TEST(SceneIo, WrongKeywordOrVersionThrows) {
  std::stringstream s;
  write_scene(s, dry());
  const std::string text = s.str();
  auto with = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    const size_t at = t.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return t.replace(at, from.size(), to);
  };
  EXPECT_EQ(error_of(with("\nbelt.pitch ", "\nbelt.pitck "), read_scene),
            "checkpoint: expected 'belt.pitch', got 'belt.pitck'");
  EXPECT_EQ(error_of(with("scene " + std::to_string(kCheckpointVersion) + "\n", "scene 99\n"), read_scene),
            "checkpoint: 'scene' is in format 99, this build reads format " + std::to_string(kCheckpointVersion));
  EXPECT_EQ(error_of(with("pulley.wrap inside", "pulley.wrap outside"), read_scene),
            "checkpoint: 'pulley.wrap': expected inside or back, got 'outside'");
  EXPECT_EQ(error_of(with("\nstatic_tension 0x", "\nstatic_tension zz0x"), read_scene).rfind(
                "checkpoint: 'static_tension': expected a number, got 'zz0x", 0),
            0u);
  EXPECT_EQ(error_of(with("end scene", "end model"), read_scene), "checkpoint: expected 'end scene', got 'end model'");
  EXPECT_EQ(error_of(text, read_model), "checkpoint: expected 'model', got 'scene'");
  // comments and blank lines are allowed
  expect_same(dry(), [&] {
    std::istringstream in(with("\nbelt.pitch ", "\n# a note\n\nbelt.pitch "));
    return read_scene(in);
  }());
}

}  // namespace
}  // namespace beltsim
