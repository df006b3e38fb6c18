// Spray zones (model/spray.hpp) in a live simulation: an element that passes a zone takes its μ
// and dries back over the drying length, the others keep their own, a zone off the belt's path
// changes nothing, entries and exits are located where the element crosses the circle, the state
// goes through a checkpoint, and bad zones are refused with the reason and the value.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "model/forces.hpp"
#include "scene/parameters.hpp"
#include "scene/scene.hpp"
#include "scene/validate.hpp"
#include "sim/simulation.hpp"
#include "support/presets.hpp"
#include "support/scratch.hpp"
#include "support/warning_guard.hpp"

namespace beltsim {
namespace {

namespace fs = std::filesystem;

fs::path temp(const std::string& name) {
  const fs::path p = beltsim::test::scratch_dir("beltsim_spray_test") / name;
  fs::remove_all(p);
  return p;
}

RunSettings settings(const fs::path& out, double rtol = 1e-4) {
  RunSettings rs;
  rs.integrator = "esdirk32";
  rs.rtol = rtol;
  rs.sample_dt = 1e-3;
  rs.out_dir = out.string();
  return rs;
}

// The paper's two pulleys with the driver's speed prescribed, 0 to kOmega over kRamp (a cosine ramp), and the driven
// pulley free without a load: past the start the belt runs at v = kOmega·r on both spans (equal
// tensions, no creep). Clockwise: the upper span (y ≈ +r) runs from the driver to the driven
// pulley, along +x.
constexpr double kOmega = 50, kRamp = 0.1, kRadius = 0.1;
constexpr double kSpeed = kOmega * kRadius;  // [m/s]

// The belt at rest when the driver starts turning slips on it: the first steps fail and are retried
// smaller (failed_step), which each test on this drive declares.
SceneDef running_belt() {
  test::expect_warnings({WarningKind::failed_step});
  SceneDef d = presets::paper_dry();
  PulleyDef& driver = d.pulleys[0];
  driver.torque = TimeSpeedLaw{};
  driver.kinematic = true;
  driver.speed.ramps.push_back({0.0, kRamp, 0.0, -kOmega, true});  // cosine: no jump of the acceleration
  d.pulleys[1].torque = TimeSpeedLaw{};
  return d;
}

SprayZone zone(Vec2 centre, double radius, double mu, double from, double to, double drying) {
  SprayZone z;
  z.centre = centre, z.radius = radius, z.mu = mu, z.from = from, z.to = to, z.drying_length = drying;
  return z;
}

bool same_bits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

// A zone the belt never passes changes nothing: the same steps and the same state, bit for bit,
// and every μ its own (the per-step check of the zone is all it costs).
TEST(Spray, ZoneOffThePathChangesNothing) {
  const Scene plain = build_scene(presets::paper_dry());
  SceneDef d = presets::paper_dry();
  d.spray.push_back(zone({0.145, 0.5}, 0.05, 0.1, 0.0, std::numeric_limits<double>::infinity(), 0.5));
  const Scene sprayed = build_scene(d);
  Simulation a(plain, settings(temp("plain"))), b(sprayed, settings(temp("off_path")));
  a.run_to(0.05), b.run_to(0.05);
  EXPECT_TRUE(same_bits(a.state(), b.state()));
  EXPECT_EQ(a.stats().steps, b.stats().steps);
  for (int i = 0; i < sprayed.model.n_el(); ++i) EXPECT_EQ(b.element(i).mu, plain.drive.mu[i]);
}

// The contact and friction laws see the sprayed μ: the forces of a run with a zone on the driver's
// wrap are, bit for bit, those of the same drive with each element's μ set to the zone's where it
// wets them, and differ from the dry drive's.
TEST(Spray, TheLawsSeeTheSprayedMu) {
  SceneDef d = presets::paper_dry();
  d.spray.push_back(zone({-0.1, 0.0}, 0.03, 0.2, 0.0, std::numeric_limits<double>::infinity(), 0.5));
  const Scene sc = build_scene(d);
  ASSERT_GT(sc.drive.spray.n_wet, 0);
  Simulation sim(sc, settings(temp("laws")));
  sim.run_to(0.02);
  const Model& m = sc.model;
  const double t = sim.now();
  const Drive& sprayed = sim.drive();
  Drive plain = sprayed, dry = sprayed;
  plain.spray = Spray{}, dry.spray = Spray{};
  for (int i = 0; i < m.n_el(); ++i) plain.mu[i] = sprayed.mu_at(i, t);
  Eigen::VectorXd f_sprayed(m.n_coord()), f_plain(m.n_coord()), f_dry(m.n_coord());
  forces(m, sprayed, t, sim.state().data(), f_sprayed.data());
  forces(m, plain, t, sim.state().data(), f_plain.data());
  forces(m, dry, t, sim.state().data(), f_dry.data());
  EXPECT_TRUE(same_bits(f_sprayed, f_plain));
  EXPECT_GT((f_sprayed - f_dry).norm(), 1e-3 * f_dry.norm());
}

struct Sample {
  double t;
  Eigen::VectorXd y;
  std::vector<double> mu;
};

// The known answer: an element that passes the zone while it sprays has the zone's μ inside it,
// leaves with it and recovers its own linearly over drying_length of travel at the belt's speed
// v = Ω·r; an element that never passes keeps its own μ throughout.
TEST(Spray, WetsWhatPassesAndDriesOverTheDryingLength) {
  SceneDef d = running_belt();
  constexpr double from = 0.3, to = 0.34, L = 0.5, mu_z = 0.2, R = 0.02;
  const Scene probe = build_scene(d);
  // the zone on the upper span's midpoint, where the belt runs at y = the element's height there
  const int mid = probe.element_nearest({0.145, kRadius});
  const Vec2 c(0.145, probe.y0[3 * mid + 1]);
  d.spray.push_back(zone(c, R, mu_z, from, to, L));
  const Scene sc = build_scene(d);
  const int n = sc.model.n_el();
  Simulation sim(sc, settings(temp("known")));
  std::vector<Sample> samples;
  constexpr double dt = 2e-4;
  sim.every(dt, [&] {
    Sample s{sim.now(), sim.state(), {}};
    for (int i = 0; i < n; ++i) s.mu.push_back(sim.element(i).mu);
    samples.push_back(std::move(s));
  });
  sim.run_to(to + 1.5 * L / kSpeed);
  // an element inside the circle while it sprays, and one that never comes within a sample's travel of it
  std::vector<bool> passed(n, false), near(n, false);
  for (const Sample& s : samples)
    for (int i = 0; i < n; ++i) {
      const double r = (Vec2(s.y[3 * i], s.y[3 * i + 1]) - c).norm();
      const bool spraying = s.t > from && s.t < to;  // at from itself the sample comes before the landing
      if (spraying && r < R) {
        passed[i] = true;
        EXPECT_EQ(s.mu[i], mu_z) << "element " << i << " inside the zone at t = " << s.t;
      }
      if (spraying && r < R + 2 * kSpeed * dt) near[i] = true;
    }
  int n_passed = 0, n_spared = 0;
  for (int i = 0; i < n; ++i) {
    if (passed[i]) n_passed++;
    if (near[i]) continue;
    n_spared++;
    for (const Sample& s : samples) ASSERT_EQ(s.mu[i], 1.0) << "element " << i << " never passed, t = " << s.t;
  }
  EXPECT_GT(n_passed, 5);
  EXPECT_GT(n_spared, n / 2);
  // drying: the record's exit time and μ, then μ along the travel at the belt's speed; the
  // element's speed when it leaves is the belt's to the span's speed ripple, measured at 3.6e-3 of
  // v at the exits on this drive, which the tolerance on μ carries (0.8·5e-3·the dried fraction)
  const Spray& sp = sim.drive().spray;
  int checked = 0;
  for (int i = 0; i < n; ++i) {
    if (!passed[i]) continue;
    const ElementSpray& e = sp.el[i];
    EXPECT_EQ(e.mu_wet, mu_z);
    EXPECT_NEAR(e.rate * L, kSpeed, 5e-3 * kSpeed) << "element " << i;
    for (const Sample& s : samples) {
      if (s.t < e.t_wet) continue;
      const double f = std::min(1.0, kSpeed * (s.t - e.t_wet) / L);
      EXPECT_NEAR(s.mu[i], mu_z + (1.0 - mu_z) * f, (1 - mu_z) * 5e-3 * f + 1e-15) << "element " << i << " t " << s.t;
      if (s.t > e.t_dry()) {
        EXPECT_EQ(s.mu[i], 1.0);
      }
      checked++;
    }
  }
  EXPECT_GT(checked, 100);
  EXPECT_EQ(sp.n_wet, 0);  // all dry again
}

// Event location: the entry and exit times of an element are where its centre crosses the
// circle. On the dense output: the state at the located entry puts the centre inside the circle
// by at most the travel over the location's bracket (1e-10 s at v: 5e-10 m). Against the analytic
// crossing of an element moving in a straight line at its speed v_a at t_a (the zone's start):
// x(t) = x_a + v_a·(t - t_a), which the span's speed ripple (measured at 2.3e-3 of v on this drive
// at 0.3 s) lets drift by 3e-3 of the time travelled.
TEST(Spray, EntryAndExitAreLocatedOnTheCrossings) {
  SceneDef d = running_belt();
  constexpr double from = 0.3, R = 0.02;
  const Scene probe = build_scene(d);
  const int mid = probe.element_nearest({0.145, kRadius});
  const Vec2 c(0.145, probe.y0[3 * mid + 1]);
  d.spray.push_back(zone(c, R, 0.3, from, std::numeric_limits<double>::infinity(), 0.5));
  const Scene sc = build_scene(d);
  const int n = sc.model.n_el();
  Simulation sim(sc, settings(temp("locate")));
  sim.run_to(from);
  // the first element upstream of the zone (the belt runs along +x on the upper span)
  const Eigen::VectorXd ya = sim.state();
  int next = -1;
  double gap = 1e9;
  for (int i = 0; i < n; ++i) {
    const double x = ya[3 * i], y = ya[3 * i + 1];
    if (std::abs(y - c.y()) > R || x > c.x() - R) continue;
    if ((c.x() - R) - x < gap) gap = (c.x() - R) - x, next = i;
  }
  ASSERT_GE(next, 0);
  const double xa = ya[3 * next], ya_y = ya[3 * next + 1], vx = ya[sc.model.n_coord() + 3 * next];
  EXPECT_NEAR(vx, kSpeed, 3e-3 * kSpeed);
  const double half = std::sqrt(R * R - (ya_y - c.y()) * (ya_y - c.y()));
  const double t_in = from + ((c.x() - half) - xa) / vx;
  const double t_out = from + ((c.x() + half) - xa) / vx;
  sim.run_to(t_out + 2e-3);
  const ElementSpray& e = sim.drive().spray.el[next];
  ASSERT_TRUE(e.drying);
  EXPECT_NEAR(e.t_in, t_in, 3e-3 * (t_in - from));
  EXPECT_NEAR(e.t_wet, t_out, 3e-3 * (t_out - from));
  EXPECT_GT(e.t_in, from);
  // the same run paused at the located entry: its state there is the dense output's
  Simulation again(sc, settings(temp("locate_again")));
  again.run_to(e.t_in);
  const Eigen::VectorXd& y = again.state();
  const double r = (Vec2(y[3 * next], y[3 * next + 1]) - c).norm();
  EXPECT_LE(r, R);
  EXPECT_GT(r, R - 1e-10 * kSpeed * 1.01);
  EXPECT_EQ(again.drive().spray.el[next].zone, 0);
}

// The wetting goes through a checkpoint: a run resumed mid-spray ends as the one that ran through.
TEST(Spray, ResumedRunEndsAsTheOneThatRanThrough) {
  SceneDef d = running_belt();
  const Scene probe = build_scene(d);
  const int mid = probe.element_nearest({0.145, kRadius});
  d.spray.push_back(zone({0.145, probe.y0[3 * mid + 1]}, 0.02, 0.3, 0.1, 0.13, 0.2));
  const Scene sc = build_scene(d);
  Eigen::VectorXd through;
  {
    Simulation a(sc, settings(temp("through")));
    a.run_to(0.16);
    through = a.state();
  }
  const fs::path out = temp("resumed");
  {
    Simulation b(sc, settings(out));
    b.run_to(0.12);
    ASSERT_GT(b.drive().spray.n_wet, 0);
    b.save((out / "mid.ckpt").string());
  }
  const FrameSinkFactory none = [](const Scene&, const FrameSettings&) { return std::unique_ptr<FrameSink>(); };
  std::unique_ptr<Simulation> r = Simulation::resume((out / "mid.ckpt").string(), none);
  r->run_to(0.16);
  EXPECT_TRUE(same_bits(r->state(), through));
  std::ifstream ev((out / "events.csv").string());
  std::stringstream s;
  s << ev.rdbuf();
  EXPECT_NE(s.str().find("spray1"), std::string::npos) << s.str();
}

// A bad zone is refused with the key, the reason and the value.
TEST(Spray, BadZonesAreRefused) {
  auto error = [](SprayZone z) {
    SceneDef d = presets::paper_dry();
    d.spray.push_back(z);
    try {
      validate(d);
    } catch (const ParameterError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const SprayZone good = zone({0.1, 0.1}, 0.02, 0.3, 0.1, 0.2, 0.5);
  EXPECT_EQ(error(good), "");
  SprayZone z = good;
  z.radius = -0.01;
  EXPECT_EQ(error(z), "spray 1.radius must be > 0 (got -0.01 m)");
  z = good, z.drying_length = 0;
  EXPECT_EQ(error(z), "spray 1.drying_length must be > 0 (got 0 m)");
  z = good, z.mu = -1;
  EXPECT_EQ(error(z), "spray 1.mu " + std::string(rule_text(Rule::friction_coefficient)) + " (got -1)");
  z = good, z.mu = 11;
  EXPECT_EQ(error(z), "spray 1.mu " + std::string(rule_text(Rule::friction_coefficient)) + " (got 11)");
  z = good, z.from = 0.3;
  EXPECT_EQ(error(z), "spray 1.to must be after from (0.3 s) (got 0.2 s)");
  z = good, z.centre = {NAN, 0};
  EXPECT_EQ(error(z), "spray 1.centre x must be a finite number (got nan m)");
}

}  // namespace
}  // namespace beltsim
