// The live simulation (sim/simulation.hpp): pausing changes nothing, a change at a pause applies
// from that time on and is logged, events at the same time (or at a law's kink) are landed on
// once, callbacks run at their exact times.
#include "sim/simulation.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "io/csv_writer.hpp"
#include "io/number_text.hpp"
#include "scene/scene.hpp"
#include "support/dry_scene.hpp"
#include "support/files.hpp"
#include "support/presets.hpp"
#include "support/scratch.hpp"
#include "support/warning_guard.hpp"

namespace beltsim {
namespace {

using test::dry_scene;
using test::slurp;

TimeSpeedLaw constant_law(double c) {
  TimeSpeedLaw law;
  law.constant = c;
  return law;
}

namespace fs = std::filesystem;

fs::path temp(const std::string& name) {
  const fs::path p = beltsim::test::scratch_dir("beltsim_simulation_test") / name;
  fs::remove_all(p);
  return p;
}

RunSettings settings(const std::string& integrator, const fs::path& out) {
  RunSettings rs;
  rs.integrator = integrator;
  rs.rtol = 1e-4;
  rs.sample_dt = 1e-3;
  rs.out_dir = out.string();
  return rs;
}

// the t column of snapshots.csv, one entry per snapshot
std::vector<double> snapshot_times(const fs::path& out) {
  std::ifstream f((out / "snapshots.csv").string());
  std::string line;
  std::getline(f, line);
  std::vector<double> t;
  while (std::getline(f, line)) {
    const double v = std::strtod(line.c_str(), nullptr);
    if (t.empty() || t.back() != v) t.push_back(v);
  }
  return t;
}

bool same_bits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

// run_to(a); run_to(b); run_to(c) writes exactly what run_to(c) writes, and ends in the same
// state bit for bit, for a one-step method and for CVODE; the pauses fall inside steps and off
// the sample grid
TEST(Live, PausingChangesNothing) {
  // the paper's dry drive has failed implicit steps from 0.036 s (esdirk32) and CVODE
  // convergence failures from 0.018 s (docs/outputs.md)
  test::expect_warnings({WarningKind::failed_step, WarningKind::cvode_convergence});
  for (const std::string integ : {"esdirk32", "rkf45", "cvode"}) {
    // rkf45 is stability-limited (steps of ~1e-9 s): a short stretch
    const double end = integ == "rkf45" ? 0.0005 : 0.06;
    const fs::path a = temp(integ + "_paused"), b = temp(integ + "_whole");
    Eigen::VectorXd ya, yb;
    // snapshots at listed times (one of them a pause) and every 0.3·end
    RunSettings rs = settings(integ, a);
    rs.sample_dt = end / 8;  // samples on both sides of every pause
    rs.snapshot_times = {0.0123 * end, 0.37 * end, 0.61 * end};
    rs.snapshot_every = 0.3 * end;
    {
      Simulation s(dry_scene(), rs);
      for (double t : {0.1 * end, 0.37 * end, 0.5 * end, 0.77 * end, end}) s.run_to(t);
      ya = s.state();
    }
    rs.out_dir = b.string();
    {
      Simulation s(dry_scene(), rs);
      s.run_to(end);
      yb = s.state();
    }
    // at exactly the times asked for, through every integrator
    const double every = rs.snapshot_every;
    const std::vector<double> expected{0.0, every, 2 * every, 3 * every, 0.0123 * end, 0.37 * end, 0.61 * end};
    std::vector<double> sorted = expected;
    std::sort(sorted.begin(), sorted.end());
    EXPECT_EQ(snapshot_times(b), sorted) << integ;
    const std::string sa = slurp((a / "snapshots.csv").string()), sb = slurp((b / "snapshots.csv").string());
    EXPECT_EQ(std::count(sb.begin(), sb.end(), '\n'), 1 + 7 * dry_scene().model.n_el()) << integ;
    EXPECT_EQ(sa, sb) << integ;
    EXPECT_TRUE(same_bits(ya, yb)) << integ;
    EXPECT_TRUE(ya.allFinite()) << integ;
    const std::string ca = slurp((a / "timeseries.csv").string()), cb = slurp((b / "timeseries.csv").string());
    EXPECT_GT(std::count(ca.begin(), ca.end(), '\n'), 4) << integ;
    EXPECT_EQ(ca, cb) << integ;
  }
}

// a change at a pause: the samples up to the pause are those of the unchanged run, the ones after
// differ, and events.csv has the change at the pause time
TEST(Live, ChangeAtAPauseAppliesFromThen) {
  // the paper's dry drive has failed implicit steps from 0.036 s (esdirk32) and CVODE
  // convergence failures from 0.018 s (docs/outputs.md)
  test::expect_warnings({WarningKind::failed_step});
  const fs::path a = temp("changed"), b = temp("unchanged");
  const double pause = 0.0205;  // off the sample grid
  {
    Simulation s(dry_scene(), settings("esdirk32", a));
    s.run_to(pause);
    EXPECT_EQ(s.now(), pause);
    std::vector<double> mu(s.model().n_el(), std::nan(""));
    for (int i = 0; i < 20; ++i) mu[i] = 0.2;
    s.set_mu(mu, "wet", "test");
    EXPECT_EQ(s.drive().mu[0], 0.2);
    s.set_torque(0, constant_law(-30.0), "-30");
    s.run_to(0.04);
  }
  {
    Simulation s(dry_scene(), settings("esdirk32", b));
    s.run_to(0.04);
  }
  std::istringstream ra(slurp((a / "timeseries.csv").string())), rb(slurp((b / "timeseries.csv").string()));
  std::string la, lb;
  int before = 0, after_differ = 0;
  while (std::getline(ra, la) && std::getline(rb, lb)) {
    if (la.rfind("t,", 0) == 0) continue;
    const double t = std::stod(la.substr(0, la.find(',')));
    if (t <= pause) {
      EXPECT_EQ(la, lb) << "at t = " << t;
      before++;
    } else {
      after_differ += la != lb;
    }
  }
  EXPECT_EQ(before, 21);
  EXPECT_EQ(after_differ, 20);  // every sample after the change: 0.021 .. 0.040 s
  const std::string ev = slurp((a / "events.csv").string());
  EXPECT_NE(ev.find("0.0205,wet,test"), std::string::npos) << ev;
  EXPECT_NE(ev.find("0.0205,driver.torque,-30"), std::string::npos) << ev;
}

// two events at the same time, and one at a torque table's kink, are landed on once: no
// "step size collapsed to 0 s" (esdirk32), no endless loop (rkf45)
TEST(Live, CoincidentEventsAndKinks) {
  SceneDef d = presets::paper_dry();
  d.pulleys[0].torque = TimeSpeedLaw{};
  d.pulleys[0].torque.t = {0.0, 0.0004};  // a kink at 0.0004 s
  d.pulleys[0].torque.value = {0.0, -70.0};
  const Scene sc = build_scene(d);
  for (const std::string integ : {"esdirk32", "rkf45"}) {
    RunSettings rs = settings(integ, temp("coincident_" + integ));
    rs.t_end = 0.0006;  // rkf45 is stability-limited (steps of ~1e-9 s): a short stretch
    std::vector<double> mu(sc.model.n_el(), 0.5);
    rs.mu_events = {
        {0.0004, mu, "a", "", {}}, {0.0004, mu, "b", "", {}}, {0.0002, mu, "c", "", {}}, {0.0002, mu, "d", "", {}}};
    RunResult r;
    ASSERT_NO_THROW(r = run(sc, rs)) << integ;
    EXPECT_EQ(r.t_reached, 0.0006);
    const std::string ev = slurp((fs::path(rs.out_dir) / "events.csv").string());
    EXPECT_NE(ev.find(number_text(0.0002) + ",c"), std::string::npos) << ev;
    EXPECT_NE(ev.find(number_text(0.0004) + ",b"), std::string::npos) << ev;
  }
}

// every(dt) runs at now + k·dt exactly; when() finds a crossing known in closed form: a
// kinematic driver at -10 rad/s turns through -0.5 rad at t = 0.05 s
TEST(Live, EveryAndWhenAtTheirTimes) {
  // the driver jumps to -10 rad/s at the start: a failed implicit step at 0.003 s
  test::expect_warnings({WarningKind::failed_step});
  SceneDef d = presets::paper_dry();
  d.pulleys[0].kinematic = true;
  d.pulleys[0].torque = TimeSpeedLaw{};
  d.pulleys[0].speed = constant_law(-10.0);
  const Scene sc = build_scene(d);
  Simulation s(sc, settings("esdirk32", temp("callbacks")));
  std::vector<double> times;
  s.every(0.0125, [&] { times.push_back(s.now()); });
  double crossing = -1, omega_driven = 0;
  s.when([&] { return s.pulley(0).angle <= -0.5; },
         [&] {
           crossing = s.now();
           omega_driven = s.pulley(1).omega;
         });
  s.run_to(0.06);
  ASSERT_EQ(times.size(), 4u);
  for (size_t k = 0; k < times.size(); ++k) EXPECT_EQ(times[k], static_cast<double>(k + 1) / 80);  // every 1/80 s
  EXPECT_NEAR(crossing, 0.05, 1e-6);
  EXPECT_LT(omega_driven, 0);
}

// save, stop, resume: the continuation writes exactly the uninterrupted run's samples and ends in
// its state bit for bit; the run's outputs are continued in place (the CSV cut back to the rows
// written when the checkpoint was taken); changed laws and μ and pending events are restored
TEST(Live, CheckpointResumesBitForBit) {
  // the paper's dry drive has failed implicit steps from 0.036 s (esdirk32) and CVODE
  // convergence failures from 0.018 s (docs/outputs.md)
  test::expect_warnings({WarningKind::failed_step});
  SceneDef d = presets::paper_dry();
  const Scene sc = build_scene(d);
  std::vector<double> mu(sc.model.n_el(), std::nan(""));
  for (int i = 10; i < 30; ++i) mu[i] = 0.3;
  auto configure = [&](const fs::path& out) {
    RunSettings rs = settings("esdirk32", out);
    rs.snapshot_times = {0.01, 0.0137, 0.019, 0.025};
    rs.snapshot_every = 0.007;
    rs.mu_events = {{0.024, std::vector<double>(sc.model.n_el(), 0.8), "dry", "", {}}};  // still ahead at the save
    return rs;
  };
  auto change = [&](Simulation& s) {
    s.run_to(0.005);
    s.set_mu(mu, "wet", "test");
    s.set_torque(0, constant_law(-20.0), "-20");
  };
  const fs::path whole = temp("ck_whole"), parts = temp("ck_parts");
  Eigen::VectorXd y_whole, y_parts;
  {
    Simulation s(sc, configure(whole));
    change(s);
    s.run_to(0.03);
    y_whole = s.state();
  }
  const std::string ck = (parts / "ck.txt").string();
  {
    Simulation s(sc, configure(parts));
    change(s);
    s.run_to(0.0137);
    s.save(ck);
    s.run_to(0.02);  // written after the checkpoint: resume cuts it off again
  }
  {
    auto s = Simulation::resume(ck, {}, nullptr, {}, true);  // (rewind: the rows after 0.0137 s)
    EXPECT_EQ(s->now(), 0.0137);
    EXPECT_EQ(s->drive().mu[12], 0.3);
    EXPECT_EQ(s->drive().pulleys[0].torque.constant, -20.0);
    s->run_to(0.03);
    y_parts = s->state();
    EXPECT_EQ(s->drive().mu[12], 0.8);  // the pending event ran
  }
  EXPECT_TRUE(same_bits(y_whole, y_parts));
  // the interval means and the snapshots continue too
  EXPECT_EQ(slurp((whole / "timeseries.csv").string()), slurp((parts / "timeseries.csv").string()));
  EXPECT_EQ(slurp((whole / "snapshots.csv").string()), slurp((parts / "snapshots.csv").string()));
  // CVODE's multistep history cannot be exported: saving says so
  Simulation c(sc, settings("cvode", temp("ck_cvode")));
  try {
    c.save((temp("ck_cvode") / "x").string());
    ADD_FAILURE() << "cvode saved a checkpoint";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("one-step integrator"), std::string::npos) << e.what();
  }
}

// a checkpoint a callback asks for (every, when's action) is written once everything due at its
// time is done, the state run_to(t) stops at: resumed, it continues as the run that went on, bit for
// bit (saved inside the callback's time's processing, it held a state no run stands at, and save
// was refused there). A law or a when-condition still cannot save: they run inside a step
TEST(Live, ACheckpointACallbackAsksForResumesBitForBit) {
  test::expect_warnings({WarningKind::failed_step});
  const Scene sc = build_scene(presets::paper_dry());
  auto configure = [&](const fs::path& out) {
    RunSettings rs = settings("trbdf2", out);
    rs.snapshot_every = 0.007;
    return rs;
  };
  // the same callbacks in both runs (a when's action restarts the integrator where it runs): every
  // 0.007 s, off the samples' times but with a snapshot each, and once past 0.0123 s
  const fs::path whole = temp("cb_whole"), parts = temp("cb_parts");
  auto callbacks = [&](Simulation& s, bool save) {
    auto k = std::make_shared<int>(0);
    s.every(0.007, [&s, k, save, parts] {
      if (++*k, save) s.save((parts / ("e" + std::to_string(*k) + ".txt")).string());
    });
    s.when([&s] { return s.now() > 0.0123; },
           [&s, save, parts] {
             if (save) s.save((parts / "w.txt").string());
           });
  };
  Eigen::VectorXd y_whole;
  {
    Simulation s(sc, configure(whole));
    callbacks(s, false);
    s.run_to(0.03);
    y_whole = s.state();
  }
  {
    Simulation s(sc, configure(parts));
    callbacks(s, true);
    s.run_to(0.03);
    EXPECT_TRUE(same_bits(y_whole, s.state()));
    // a law's or a when-condition's save is refused
    const std::string m =
        test::what_of([&] { s.when([&s, parts] { return s.save((parts / "x.txt").string()), false; }, [] {}); });
    EXPECT_NE(m.find("save: not inside a law or a when-condition"), std::string::npos) << m;
  }
  for (const char* name : {"e2.txt", "w.txt", "e4.txt"}) {
    auto s = Simulation::resume((parts / name).string(), {}, nullptr, {}, true);
    if (name[0] == 'e') {
      EXPECT_EQ(s->now(), (name[1] - '0') * 0.007) << name;
    } else {
      EXPECT_GT(s->now(), 0.0123);
    }
    s->run_to(0.03);
    EXPECT_TRUE(same_bits(y_whole, s->state())) << name;
    s->close();
    EXPECT_EQ(slurp((whole / "timeseries.csv").string()), slurp((parts / "timeseries.csv").string())) << name;
    EXPECT_EQ(slurp((whole / "snapshots.csv").string()), slurp((parts / "snapshots.csv").string())) << name;
  }
}

// keep_states: a checkpoint at each frame time, numbered as the frames, holding what the frame was
// drawn from (time, state and observation, bit for bit); a run resumed from a checkpoint keeps the
// same states; without frames the default frame times
struct Seen {
  double t;
  Eigen::VectorXd y;
  std::vector<double> friction;
};
class Recording final : public FrameSink {
 public:
  explicit Recording(std::vector<Seen>* seen) : seen_(seen) {}
  void frame(double t, const double* y, const Drive&, const Observation* obs) override {
    Seen s{t, Eigen::Map<const Eigen::VectorXd>(y, static_cast<Eigen::Index>(y_size_)), {}};
    for (const ElementObs& e : obs->elements) s.friction.push_back(e.friction);
    seen_->push_back(std::move(s));
  }
  void finish() override {}
  long frames_written() const override { return static_cast<long>(seen_->size()); }
  size_t y_size_ = 0;

 private:
  std::vector<Seen>* seen_;
};

std::vector<std::string> listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(Live, KeptStatesAreWhatTheFramesWereDrawnFrom) {
  test::expect_warnings({WarningKind::failed_step});
  const Scene& sc = dry_scene();
  std::vector<Seen> seen;
  auto configure = [&](const fs::path& out, std::vector<Seen>* record) {
    RunSettings rs = settings("esdirk32", out);
    rs.keep_states = true;
    FrameSettings f;
    f.slowdown = 20, f.t_start = 0.0011;  // every 1/600 s from 1.1 ms
    f.png_dir = "unused";                 // drawn by the recording below
    rs.frames = f;
    rs.frame_factory = [record, &sc](const Scene&, const FrameSettings&) {
      auto r = std::make_unique<Recording>(record);
      r->y_size_ = static_cast<size_t>(sc.y0.size());
      return std::unique_ptr<FrameSink>(std::move(r));
    };
    return rs;
  };
  const fs::path whole = temp("keep_whole"), parts = temp("keep_parts");
  {
    Simulation s(sc, configure(whole, &seen));
    s.run_to(0.012);
  }
  ASSERT_EQ(seen.size(), 7u);  // 1.1 ms + k/600 s <= 12 ms: k = 0..6
  std::vector<std::string> names;
  for (size_t k = 0; k < seen.size(); ++k) {
    char name[32];
    std::snprintf(name, sizeof name, "state_%05zu.ckpt", k);
    names.push_back(name);
    const auto kept = Simulation::open_checkpoint((whole / "states" / name).string());
    EXPECT_EQ(kept->now(), seen[k].t) << name;
    EXPECT_TRUE(same_bits(kept->state(), seen[k].y)) << name;
    std::vector<double> friction;
    for (const ElementObs& e : kept->observation().elements) friction.push_back(e.friction);
    EXPECT_EQ(std::memcmp(friction.data(), seen[k].friction.data(), sizeof(double) * friction.size()), 0) << name;
  }
  EXPECT_EQ(listing(whole / "states"), names);
  // saved between frames 3 and 4 and resumed: the same states, bit for bit in state and time
  std::vector<Seen> before, after;
  const std::string ck = (parts / "ck.txt").string();
  {
    Simulation s(sc, configure(parts, &before));
    s.run_to(0.0067);
    s.save(ck);
  }
  {
    RunSettings rs = configure(parts, &after);
    auto s = Simulation::resume(ck, rs.frame_factory);
    s->run_to(0.012);
  }
  EXPECT_EQ(before.size() + after.size(), seen.size());
  EXPECT_EQ(listing(parts / "states"), names);
  for (const std::string& name : names) {
    const auto a = Simulation::open_checkpoint((whole / "states" / name).string());
    const auto b = Simulation::open_checkpoint((parts / "states" / name).string());
    EXPECT_EQ(a->now(), b->now()) << name;
    EXPECT_TRUE(same_bits(a->state(), b->state())) << name;
  }
  // without frames: the default frame times (every 1/300 s from 0), nothing drawn
  const fs::path bare = temp("keep_bare");
  {
    RunSettings rs = settings("esdirk32", bare);
    rs.keep_states = true;
    Simulation s(sc, rs);
    s.run_to(0.011);
    EXPECT_EQ(s.frames_written(), 0);
  }
  const std::vector<std::string> kept = listing(bare / "states");
  ASSERT_EQ(kept.size(), 4u);  // 0, 1/300, 2/300, 3/300 s
  for (size_t k = 0; k < kept.size(); ++k)
    EXPECT_EQ(Simulation::open_checkpoint((bare / "states" / kept[k]).string())->now(),
              static_cast<double>(k) * FrameSettings{}.frame_dt());
  // CVODE's state cannot be kept: refused before anything is written
  RunSettings c = settings("cvode", temp("keep_cvode"));
  c.keep_states = true;
  try {
    Simulation s(sc, c);
    ADD_FAILURE() << "cvode kept states";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("keep_states: cvode keeps a multistep history"), std::string::npos)
        << e.what();
  }
}

// the belt torque a sample reports is the one that turns the pulley: I·dΩ/dt − M, with dΩ/dt by
// central differences of the sampled speeds. Measured worst difference over 0.01–0.28 s: 0.9 N·m
// under esdirk32, 1.3 N·m under trbdf2 (a user's trial, `beltsim run scripts/paper_dry.lua`; the
// differences' own error); recomputing the friction from the interpolated state instead
// gave errors up to 150 N·m (model/observables.hpp, blend_contact), so 2 N·m separates the two.
TEST(Live, SampledBeltTorqueTurnsThePulley) {
  // the paper's dry drive has failed implicit steps from 0.036 s (esdirk32) and CVODE
  // convergence failures from 0.018 s (docs/outputs.md)
  test::expect_warnings({WarningKind::failed_step});
  RunSettings rs = settings("esdirk32", temp("belt_torque"));
  rs.keep_samples = true;
  rs.t_end = 0.29;
  const RunResult r = run(dry_scene(), rs);
  const std::vector<std::string> cols = timeseries_columns(dry_scene());
  auto col = [&](const std::string& name) { return std::find(cols.begin(), cols.end(), name) - cols.begin(); };
  const double I = dry_scene().model.pulleys[0].inertia, dt = rs.sample_dt;
  double worst = 0;
  for (const char* p : {"driver", "driven"}) {
    const auto om = col(std::string(p) + ".omega"), M = col(std::string(p) + ".torque"),
               bt = col(std::string(p) + ".belt_torque");
    for (size_t k = 10; k + 1 < r.samples.size(); ++k) {
      const double predicted = I * (r.samples[k + 1][om] - r.samples[k - 1][om]) / (2 * dt) - r.samples[k][M];
      worst = std::max(worst, std::abs(predicted - r.samples[k][bt]));
    }
  }
  EXPECT_LT(worst, 2.0) << "N·m";
}

// parameters.csv, timeseries.csv and snapshots.csv read back bit for bit (the CSV's numbers are
// the shortest decimals that round-trip; before, "%.10g" lost the last 6-7 digits)
TEST(Live, OutputsReadBackBitForBit) {
  const fs::path out = temp("roundtrip");
  RunSettings rs = settings("esdirk32", out);
  rs.keep_samples = true;
  rs.t_end = 0.003;
  rs.snapshot_times = {0.0};
  const RunResult r = run(dry_scene(), rs);
  auto bits = [](double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; };
  auto fields = [](const std::string& line) {
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
    return f;
  };
  std::ifstream ts((out / "timeseries.csv").string());
  std::string line;
  std::getline(ts, line);
  size_t rows = 0, cells = 0;
  for (; std::getline(ts, line) && rows < r.samples.size(); ++rows) {
    const auto f = fields(line);
    ASSERT_EQ(f.size(), r.samples[rows].size());
    for (size_t k = 0; k < f.size(); ++k) {
      const double v = r.samples[rows][k], back = std::strtod(f[k].c_str(), nullptr);
      if (std::isnan(v)) continue;
      EXPECT_TRUE(bits(back, v)) << f[k] << " should be " << v;
      cells++;
    }
  }
  EXPECT_EQ(rows, r.samples.size());
  EXPECT_GT(cells, 50u);
  std::ifstream pf((out / "parameters.csv").string());
  bool found = false;
  while (std::getline(pf, line))
    if (line.rfind("belt.pitch,", 0) == 0) {
      found = true;
      EXPECT_TRUE(bits(std::strtod(fields(line)[1].c_str(), nullptr), dry_scene().model.belt.pitch)) << line;
    }
  EXPECT_TRUE(found);
  std::ifstream sf((out / "snapshots.csv").string());
  std::getline(sf, line);
  std::getline(sf, line);  // element 0 at t = 0: where the scene put it
  EXPECT_TRUE(bits(std::strtod(fields(line)[3].c_str(), nullptr), dry_scene().y0[0])) << line;
  EXPECT_TRUE(bits(std::strtod(fields(line)[4].c_str(), nullptr), dry_scene().y0[1])) << line;
}

// Interval means (sim/simulation.cpp, "interval means") on a steady drive: a kinematic driver at
// 20 rad/s, the driven pulley loaded by 1.5 N·m·s/rad (30 N·m), 60 elements (an element runs onto
// each pulley every l/v = 10 ms), samples every 12.5 ms from 0.11 s to 0.3 s.
//  - at the free pulley I·dΩ/dt = M + M_belt, so over each interval mean(M) + mean(M_belt) must
//    equal I·ΔΩ/Δt. Measured: worst 0.009 N·m from the step integrals (what is left is the
//    trapezoid against the integrator's own quadrature over the two part-steps at the interval's
//    ends, ~h·ΔM/Δt), 0.65 N·m from the trapezoid of the samples (the means an analyst would make
//    from timeseries.csv: they alias the element passing); bound 0.05 N·m, between the two.
//  - the driver's torque swings as elements run on; from sample to sample it changes by 0.96 N·m
//    (rms), its interval mean by 0.17 N·m (measured; the mean over an interval shorter than the
//    passing period smooths less: 5 ms gave 3.5 against 2.5 N·m); bound: below 0.3 of the samples'.
TEST(Live, IntervalMeansAreExactFromTheSteps) {
  // the paper's dry drive: failed implicit steps from 0.036 s (docs/outputs.md)
  test::expect_warnings({WarningKind::failed_step});
  SceneDef d = presets::paper_dry();
  d.belt.mu = 0.3;
  d.pulleys[0].torque = TimeSpeedLaw{};
  d.pulleys[0].kinematic = true;
  d.pulleys[0].speed.t = {0.0, 0.05};
  d.pulleys[0].speed.value = {0.0, -20.0};
  d.pulleys[1].torque = TimeSpeedLaw{};
  d.pulleys[1].torque.per_speed = -1.5;
  const Scene sc = build_scene(d);
  RunSettings rs = settings("esdirk32", temp("means"));
  rs.keep_samples = true;
  rs.t_end = 0.3;
  rs.sample_dt = 0.0125;  // 1.25 element-passing periods
  const RunResult r = run(sc, rs);
  const std::vector<std::string> cols = timeseries_columns(sc);
  auto col = [&](const std::string& name) {
    const auto k = std::find(cols.begin(), cols.end(), name) - cols.begin();
    EXPECT_LT(k, static_cast<long>(cols.size())) << name;
    return k;
  };
  const double I = sc.model.pulleys[1].inertia, dt = rs.sample_dt;
  const auto om = col("driven.omega"), M = col("driven.torque"), bt = col("driven.belt_torque"),
             Mm = col("driven.torque_mean"), btm = col("driven.belt_torque_mean");
  EXPECT_TRUE(std::isnan(r.samples[0][Mm])) << "no interval before the first sample";
  double worst_steps = 0, worst_samples = 0;
  std::vector<double> inst, mean;
  for (size_t k = 11; k < r.samples.size(); ++k) {
    const std::vector<double>&a = r.samples[k - 1], &b = r.samples[k];
    const double turn = I * (b[om] - a[om]) / dt;
    worst_steps = std::max(worst_steps, std::abs(b[Mm] + b[btm] - turn));
    worst_samples = std::max(worst_samples, std::abs(0.5 * (a[M] + b[M] + a[bt] + b[bt]) - turn));
    // sample-to-sample changes: the slow drift of the load cancels
    inst.push_back(b[col("driver.torque")] - a[col("driver.torque")]);
    mean.push_back(b[col("driver.torque_mean")] - a[col("driver.torque_mean")]);
  }
  auto spread = [](const std::vector<double>& v) {
    double m = 0, s = 0;
    for (double x : v) m += x;
    m /= v.size();
    for (double x : v) s += (x - m) * (x - m);
    return std::sqrt(s / v.size());
  };
  std::printf(
      "identity: worst %.3g N·m from the steps, %.3g N·m from the samples; driver torque spread %.3g N·m, "
      "its mean's %.3g N·m\n",
      worst_steps, worst_samples, spread(inst), spread(mean));
  EXPECT_LT(worst_steps, 0.05) << "N·m";
  EXPECT_GT(worst_samples, 0.05) << "N·m: the samples' trapezoid should not pass (else the test cannot tell)";
  EXPECT_LT(spread(mean), 0.3 * spread(inst)) << "N·m";
  // the span tensions' means are there, and positive
  const auto T = col("span_driver_driven.tension_mean");
  for (size_t k = 11; k < r.samples.size(); ++k) EXPECT_GT(r.samples[k][T], 0) << r.samples[k][0];
}

// the fallbacks are counted and shown: the static start's retry (needed at 120 elements on the
// paper's drive, not at 60: docs/model.md, Initial state) and steps whose iteration failed, with their
// counts and first times, in notes() and parameters.csv, the failed steps in the summary line too
TEST(Live, FallbacksAreCountedAndShown) {
  test::expect_warnings({WarningKind::static_retry, WarningKind::failed_step});
  EXPECT_FALSE(dry_scene().static_retried);
  SceneDef d = presets::paper_dry();
  d.belt.elements = 120;
  EXPECT_TRUE(build_scene(d).static_retried);
  const fs::path out = temp("notes");
  // at rtol 1e-2 the first steps are long enough (about 10 ms) for the iteration to fail twice
  // before 0.05 s (at 1e-3, since the local solve takes whole wraps, it does not fail there)
  RunSettings rs = settings("esdirk32", out);
  rs.rtol = 1e-2;
  Simulation s(build_scene(d), rs);
  s.run_to(0.05);
  const std::vector<std::string> notes = s.notes();
  ASSERT_FALSE(notes.empty());
  EXPECT_NE(notes[0].find("static_retry: 1 time, first at t = 0 s (the static start needed its trust-region retry"),
            std::string::npos)
      << notes[0];
  const WarningStat failed = s.warnings()[WarningKind::failed_step];
  ASSERT_GT(failed.count, 0) << "the paper's drive at 120 elements had failed steps in its first 0.05 s";
  EXPECT_GT(failed.first_t, 0.0);
  EXPECT_LE(failed.first_t, 0.05);
  const std::string summary = s.warning_summary();
  // the retry converged: parameters.csv and notes() count it, the closing line does not
  EXPECT_EQ(summary.find("static_retry"), std::string::npos) << summary;
  EXPECT_NE(summary.find("failed_step " + std::to_string(failed.count) + (failed.count == 1 ? " time" : " times")),
            std::string::npos)
      << summary;
  s.close();
  const std::string p = slurp((out / "parameters.csv").string());
  EXPECT_NE(p.find("warning.static_retry.count,1,,"), std::string::npos) << p;
  EXPECT_NE(p.find("warning.static_retry.first_t,0,s,"), std::string::npos) << p;
  EXPECT_NE(p.find("warning.failed_step.count," + std::to_string(failed.count) + ",,"), std::string::npos) << p;
  // the time as every number of the file: the shortest decimal that reads back as the same double
  EXPECT_NE(p.find("warning.failed_step.first_t," + number_text(failed.first_t) + ",s,"), std::string::npos) << p;
  EXPECT_NE(p.find("warning.cvode_convergence.count,0,,"), std::string::npos) << p;
  EXPECT_NE(p.find("warning.cvode_convergence.first_t,,s,"), std::string::npos) << p;
  // then how it ended, last: at the time it reached, as asked
  EXPECT_NE(p.find("\nend.t," + number_text(s.now()) + ",s,derived,"), std::string::npos) << p;
  EXPECT_NE(p.find("\nend.status,ok,,derived,"), std::string::npos) << p;
}

// the end rows say where the run stopped (its state's time, result.t) and where its time series
// ends (the last row's time), apart: a user's Ctrl-C gave end.t,1.4367092823960343 ("the simulated
// time the outputs reach") while the last row of timeseries.csv was at 1.436
TEST(Live, TheEndRowsSayWhereTheRunAndItsTimeSeriesEnd) {
  auto end_rows = [](const std::string& parameters) { return parameters.substr(parameters.find("\nend.t,") + 1); };
  auto cell = [](const std::string& rows, const std::string& name) {
    const size_t at = rows.find(name + ",") + name.size() + 1;
    return rows.substr(at, rows.find(',', at) - at);
  };
  {  // a live simulation paused between samples (1 ms apart)
    const fs::path out = temp("end_rows");
    Simulation s(dry_scene(), settings("esdirk32", out));
    s.run_to(0.0105);
    s.close();
    const std::string rows = end_rows(slurp((out / "parameters.csv").string()));
    EXPECT_EQ(cell(rows, "end.t"), "0.0105") << rows;
    EXPECT_EQ(cell(rows, "end.last_row_t"), "0.01") << rows;
    EXPECT_EQ(cell(rows, "end.status"), "ok") << rows;
  }
  {  // a batch run stopped at a step's end (its wall-time limit on the test's clock, as Ctrl-C stops)
    test::expect_warnings({WarningKind::failed_step});
    RunSettings rs = settings("esdirk32", temp("end_rows_stopped"));
    rs.t_end = 1;
    rs.sample_dt = 0.01;
    rs.wall_limit = 0.05;
    long looks = 0;
    rs.wall_clock = [&] { return 1e-3 * static_cast<double>(looks++); };
    const RunResult r = run(dry_scene(), rs);
    ASSERT_TRUE(r.over_wall_limit);
    const std::string rows = end_rows(slurp(r.parameters_path));
    const std::string series = slurp(r.csv_path);
    const std::string last = series.substr(series.rfind('\n', series.size() - 2) + 1);
    EXPECT_EQ(cell(rows, "end.t"), number_text(r.t_reached)) << rows;
    EXPECT_EQ(cell(rows, "end.last_row_t"), last.substr(0, last.find(','))) << rows;
    const double row_t = std::stod(cell(rows, "end.last_row_t"));
    EXPECT_LE(row_t, r.t_reached);
    EXPECT_GT(row_t + rs.sample_dt, r.t_reached);
    EXPECT_EQ(cell(rows, "end.status"), "wall_limit") << rows;
  }
}

// invalid requests name what is wrong
TEST(Live, BadRequests) {
  Simulation s(dry_scene(), settings("esdirk32", temp("bad")));
  s.run_to(0.002);
  EXPECT_THROW(s.run_to(0.001), std::invalid_argument);
  EXPECT_THROW(s.run_to(INFINITY), std::invalid_argument);
  EXPECT_THROW(s.every(0, [] {}), std::invalid_argument);
  EXPECT_THROW(s.set_mu(std::vector<double>(3, 0.1), "set_mu", ""), std::invalid_argument);
  EXPECT_THROW(s.set_mu(std::vector<double>(s.model().n_el(), 1e7), "set_mu", ""), std::invalid_argument);
  s.close();
  EXPECT_THROW(s.run_to(0.003), std::logic_error);
}

}  // namespace
}  // namespace beltsim
