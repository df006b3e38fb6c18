// A run's state in memory (sim/sim_state.hpp: Simulation::get_state, set_state): taken at a pause
// or while the run goes on, and set back (as it is, or through a checkpoint's text), the run
// continues as it did the first time, bit for bit in its state, its CSV files, its kept samples and
// its counters; a state that does not fit is refused naming the field or the file, and changes
// nothing.
#include "sim/sim_state.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <optional>

#include "io/checkpoint_text.hpp"
#include "scene/scene.hpp"
#include "sim/simulation.hpp"
#include "sim/state_io.hpp"
#include "support/files.hpp"
#include "support/presets.hpp"
#include "support/scratch.hpp"
#include "support/warning_guard.hpp"

namespace beltsim::sim_state_test {  // (its own: the test programs are built in unity batches)
namespace {

namespace fs = std::filesystem;
using test::slurp;

fs::path temp(const std::string& name) {
  const fs::path p = test::scratch_dir("beltsim_sim_state_test") / name;
  fs::remove_all(p);
  return p;
}

const Scene& dry() {
  static const Scene sc = build_scene(presets::paper_dry());
  return sc;
}

// esdirk32 with snapshots (every 7 ms and at listed times), kept samples and a μ event at 24 ms
RunSettings settings(const fs::path& out) {
  RunSettings rs;
  rs.integrator = "esdirk32";
  rs.rtol = 1e-4;
  rs.sample_dt = 1e-3;
  rs.out_dir = out.string();
  rs.keep_samples = true;
  rs.snapshot_times = {0.01, 0.0137, 0.019, 0.025};
  rs.snapshot_every = 0.007;
  rs.mu_events = {{0.024, std::vector<double>(dry().model.n_el(), 0.8), "dry", "", {}}};
  return rs;
}

// μ 0.3 on elements 10..29 and a constant driving torque from 5 ms
void change(Simulation& s) {
  s.run_to(0.005);
  std::vector<double> mu(dry().model.n_el(), std::nan(""));
  for (int i = 10; i < 30; ++i) mu[i] = 0.3;
  s.set_mu(mu, "wet", "test");
  TimeSpeedLaw law;
  law.constant = -20;
  s.set_torque(0, law, "-20");
}

bool same_bits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0;
}

bool same_rows(const std::vector<std::vector<double>>& a, const std::vector<std::vector<double>>& b) {
  if (a.size() != b.size()) return false;
  for (size_t k = 0; k < a.size(); ++k)  // (NaN where a mean has no interval yet: compared as bits)
    if (a[k].size() != b[k].size() || std::memcmp(a[k].data(), b[k].data(), sizeof(double) * a[k].size()) != 0)
      return false;
  return true;
}

// what a run ends in: its state, its outputs, its kept samples and its step count
struct Ending {
  Eigen::VectorXd y;
  std::string csv, snapshots;
  std::vector<std::vector<double>> samples;
  long steps = 0;
};
Ending ending(const Simulation& s) {
  return {s.state(), slurp(fs::path(s.csv_path())), slurp(fs::path(s.snapshots_path())), s.samples(), s.stats().steps};
}
void expect_same(const Ending& a, const Ending& b) {
  EXPECT_TRUE(same_bits(a.y, b.y));
  EXPECT_EQ(a.csv, b.csv);
  EXPECT_EQ(a.snapshots, b.snapshots);
  EXPECT_TRUE(same_rows(a.samples, b.samples));
  EXPECT_EQ(a.steps, b.steps);
}

// the state through a checkpoint's text (sim/state_io.hpp) and back
SimState through_text(const Simulation& s, const SimState& state) {
  CheckpointWriter w;
  write_state(w, s.model(), state);
  CheckpointReader r(w.finish());
  SimState back = read_state(r, s.scene());
  r.finish();
  return back;
}

// taken at a pause (inside a step, off the sample grid, with changed laws and μ and an event
// still ahead), the run goes on to 30 ms; set back, in memory or through the checkpoint's text,
// it goes to 30 ms again: the same ending, the CSV cut back to the rows written when the state was
// taken. With esdirk32 (a Hermite dense output) and trbdf2 (through its stage values, kept in the
// integrator's state).
TEST(SimState, SetBackTheRunContinuesBitForBit) {
  // the paper's dry drive has failed implicit steps from 0.036 s (esdirk32)
  test::expect_warnings({WarningKind::failed_step});
  for (const char* integrator : {"esdirk32", "trbdf2"}) {
    SCOPED_TRACE(integrator);
    RunSettings rs = settings(temp(std::string("pause_") + integrator));
    rs.integrator = integrator;
    Simulation s(dry(), rs);
    change(s);
    // right after a restart the held step is a point, with no interior states (trbdf2's)
    EXPECT_NO_THROW(through_text(s, s.get_state()));
    s.run_to(0.0137);
    const SimState at = s.get_state();
    const Eigen::VectorXd y_at = s.state();  // (read from the held step's dense output)
    EXPECT_EQ(at.now(), 0.0137);
    s.run_to(0.03);
    const Ending first = ending(s);
    ASSERT_EQ(s.drive().mu[12], 0.8);  // the event ran
    for (const bool text : {false, true}) {
      s.set_state(text ? through_text(s, at) : at);
      EXPECT_EQ(s.now(), 0.0137);
      EXPECT_TRUE(same_bits(s.state(), y_at));
      EXPECT_EQ(s.drive().mu[12], 0.3);
      EXPECT_EQ(s.drive().pulleys[0].torque.constant, -20.0);
      EXPECT_EQ(slurp(fs::path(s.csv_path())), first.csv.substr(0, static_cast<size_t>(at.outputs.csv_bytes)));
      EXPECT_EQ(s.samples().size(), static_cast<size_t>(at.outputs.rows));
      s.run_to(0.03);
      expect_same(ending(s), first);
      EXPECT_EQ(s.drive().mu[12], 0.8);
    }
  }
}

// taken from run_to's progress while the run goes on (as a live view takes it), between two
// steps: set back after the run, the run continues to the same ending
TEST(SimState, TakenWhileTheRunGoesOn) {
  test::expect_warnings({WarningKind::failed_step});
  Simulation s(dry(), settings(temp("progress")));
  change(s);
  std::optional<SimState> taken;
  s.run_to(0.03, nullptr, [&](double t, double, const WorkCounters&, double) {
    if (!taken && t > 0.012) taken = s.get_state();
  });
  const Ending first = ending(s);
  ASSERT_TRUE(taken);
  EXPECT_GT(taken->now(), 0.005);
  EXPECT_LT(taken->now(), 0.03);
  s.set_state(*taken);
  s.run_to(0.03);
  expect_same(ending(s), first);
}

// refused, naming the field or the file, and nothing changed: a state of another scene, one whose
// outputs are past what the files hold now, one set from inside a callback; a run with CVODE has
// no state to take
TEST(SimState, AStateThatDoesNotFitIsRefused) {
  test::expect_warnings({WarningKind::failed_step});
  SceneDef d = presets::paper_dry();
  d.belt.elements = 40;
  RunSettings rs_other = settings(temp("other"));
  rs_other.mu_events.clear();
  Simulation other(build_scene(d), rs_other);
  Simulation s(dry(), settings(temp("refused")));
  s.run_to(0.004);
  const SimState early = s.get_state();
  s.run_to(0.006);
  const SimState later = s.get_state();
  try {
    s.set_state(other.get_state());
    ADD_FAILURE() << "set a state of another scene";
  } catch (const StateError& e) {
    EXPECT_EQ(e.key, "belt.mu");
    EXPECT_STREQ(e.what(), "40 values for 60 elements");
  }
  EXPECT_EQ(s.now(), 0.006);
  s.set_state(early);
  const std::string csv = slurp(fs::path(s.csv_path()));
  EXPECT_EQ(test::what_of([&] { s.set_state(later); }), "the run's output " + s.csv_path() + " (" +
                                                            std::to_string(csv.size()) +
                                                            " bytes) is shorter than when the checkpoint was taken (" +
                                                            std::to_string(later.outputs.csv_bytes) + ")");
  EXPECT_EQ(s.now(), 0.004);
  EXPECT_EQ(slurp(fs::path(s.csv_path())), csv);
  s.every(1e-3, [&] { s.set_state(early); });
  EXPECT_EQ(test::what_of([&] { s.run_to(0.006); }), "set_state: not inside a callback (set it between run_to calls)");
  RunSettings rs = settings(temp("cvode"));
  rs.integrator = "cvode";
  Simulation c(dry(), rs);
  EXPECT_NE(test::what_of([&] { c.get_state(); }).find("one-step integrator"), std::string::npos);
}

}  // namespace
}  // namespace beltsim::sim_state_test
