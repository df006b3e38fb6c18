// A run's check of its own error (sim/run_check.hpp, issue 42 §2): the estimate within a factor 3
// of the true error (the run against one at rtol 1e-7, the §1 measure) at two tolerances; the run's
// own answer unchanged by it; the warning while it runs past 10×rtol, at the end past the accuracy
// contract's bounds (speeds 3×rtol, span tensions 10×rtol), and none below; the figures in parameters.csv; a jump of
// the state at a pause applied to the companion too.
//
// The scene: the paper's dry drive at 30 elements over its first 0.05 s (speeds to 4.2 rad/s).
// Measured (the check of 29c8d26), true error / estimate: rtol 1e-2: speeds 0.228 / 0.227 (past
// 3×rtol: it warns), tensions 2.9e-3 / 2.4e-3; rtol 1e-3: speeds 3.3e-3 / 2.4e-3, tensions
// 2.3e-3 / 1.3e-3 (no warning); rtol 1e-4: speeds 1.8e-3 / 1.6e-3, tensions 1.9e-3 / 1.8e-3.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "io/number_text.hpp"
#include "sim/run_error.hpp"
#include "sim/simulation.hpp"
#include "support/files.hpp"
#include "support/presets.hpp"
#include "support/scratch.hpp"
#include "support/warning_guard.hpp"

namespace beltsim {
namespace {

namespace fs = std::filesystem;

const Scene& small_scene() {
  static const Scene sc = [] {
    SceneDef d = presets::paper_dry();
    d.belt.elements = 30;
    return build_scene(d);
  }();
  return sc;
}

RunSettings settings(double rtol, const std::string& name, bool check) {
  RunSettings rs;
  rs.t_end = 0.05;
  rs.rtol = rtol;
  rs.check = check;
  rs.keep_samples = true;
  rs.out_dir = (test::scratch_dir("beltsim_run_check_test") / name).string();
  return rs;
}

const RunResult& reference() {
  static const RunResult r = run(small_scene(), settings(1e-7, "reference", false));
  return r;
}

struct Errors {
  double speed = 0, tension = 0;
};

// the true error of a run's samples against a reference's, as §1 and `beltsim wp` measure it
Errors true_error(const std::vector<std::vector<double>>& run, const std::vector<std::vector<double>>& ref) {
  const std::vector<std::string> cols = timeseries_columns(small_scene());
  std::vector<size_t> speed, tension;
  for (size_t k = 0; k < cols.size(); ++k) {
    const std::string& c = cols[k];
    if (c.size() > 6 && c.compare(c.size() - 6, 6, ".omega") == 0) speed.push_back(k);
    if (c.rfind("span_", 0) == 0 && c.compare(c.size() - 8, 8, ".tension") == 0) tension.push_back(k);
  }
  EXPECT_EQ(speed.size(), 2u);
  EXPECT_EQ(tension.size(), 2u);
  EXPECT_EQ(run.size(), ref.size());
  ErrorMeter ms(speed.size()), mt(tension.size());
  for (size_t k = 0; k < std::min(run.size(), ref.size()); ++k) {
    std::vector<double> x, xr;
    for (size_t c : speed) x.push_back(run[k][c]), xr.push_back(ref[k][c]);
    ms.add(x.data(), xr.data());
    x.clear(), xr.clear();
    for (size_t c : tension) x.push_back(run[k][c]), xr.push_back(ref[k][c]);
    mt.add(x.data(), xr.data());
  }
  return {ms.error(), mt.error()};
}

TEST(RunCheck, EstimateWithinAFactor3OfTheTrueError) {
  test::expect_warnings({WarningKind::failed_step});
  for (double rtol : {1e-2, 1e-4}) {
    SCOPED_TRACE("rtol " + rounded_text(rtol));
    const RunResult r = run(small_scene(), settings(rtol, "estimate", true));
    ASSERT_TRUE(r.check.on);
    EXPECT_TRUE(r.check.failed.empty()) << r.check.failed;
    const Errors e = true_error(r.samples, reference().samples);
    EXPECT_GT(e.speed, 0);
    EXPECT_GT(e.tension, 0);
    EXPECT_GT(r.check.err_speed, e.speed / 3) << e.speed;
    EXPECT_LT(r.check.err_speed, e.speed * 3) << e.speed;
    EXPECT_GT(r.check.err_tension, e.tension / 3) << e.tension;
    EXPECT_LT(r.check.err_tension, e.tension * 3) << e.tension;
  }
}

// the companion only reads the run: the run's samples are those of the same run unchecked
TEST(RunCheck, TheRunsAnswerIsUnchanged) {
  test::expect_warnings({WarningKind::failed_step});
  const RunResult a = run(small_scene(), settings(1e-2, "plain", false));
  const RunResult b = run(small_scene(), settings(1e-2, "checked", true));
  EXPECT_FALSE(a.check.on);
  EXPECT_EQ(a.check_line, "");
  // bit for bit (the first row's interval means are NaN in both)
  ASSERT_EQ(a.samples.size(), b.samples.size());
  for (size_t k = 0; k < a.samples.size(); ++k) {
    ASSERT_EQ(a.samples[k].size(), b.samples[k].size());
    for (size_t c = 0; c < a.samples[k].size(); ++c)
      EXPECT_EQ(number_text(a.samples[k][c]), number_text(b.samples[k][c])) << "row " << k << " column " << c;
  }
  EXPECT_EQ(a.work.steps, b.work.steps);
}

// The limits are the accuracy contract's bounds: the speeds 3×rtol, the span tensions 10×rtol; a
// speed estimate between the two is past (a single 10×rtol let it pass)
TEST(RunCheck, LimitsAreTheContractsBounds) {
  CheckEstimate e;
  e.rtol = 1e-3;
  e.err_speed = 5e-3, e.err_tension = 5e-3;
  EXPECT_TRUE(e.over());
  EXPECT_TRUE(e.speeds_over());
  e.err_speed = 2.9e-3, e.err_tension = 9.9e-3;
  EXPECT_FALSE(e.over());
  e.err_tension = 1.01e-2;
  EXPECT_TRUE(e.over());
  EXPECT_FALSE(e.speeds_over());
  EXPECT_FALSE(e.near());  // past: over, not near
}

// Within the bounds but above 0.7 of one the closing line warns that the run may be past it (the
// estimate is 0.8 to 1.4 times the true error: a user's trial saw a run 9 % past its bound pass);
// below 0.7 of both it does not
TEST(RunCheck, AnEstimateNearItsLimitWarns) {
  CheckEstimate e;
  e.rtol = 1e-3;
  e.err_speed = 2e-3, e.err_tension = 6.9e-3;
  EXPECT_FALSE(e.near());
  EXPECT_FALSE(e.warns());
  e.err_tension = 7.1e-3;
  EXPECT_TRUE(e.near());
  EXPECT_TRUE(e.warns());
  e.err_speed = 2.2e-3, e.err_tension = 1e-3;
  EXPECT_TRUE(e.near());
}

TEST(RunCheck, WarnsPastTheContractOnceAndSaysSoAtTheEnd) {
  test::expect_warnings({WarningKind::failed_step});
  std::vector<std::string> said;
  // ros34pw2: under the answer's error control trbdf2 (2.3e-3) and esdirk32 (4.5e-3) keep this
  // scene within the limit at 1e-2; ros34pw2's frozen Jacobian carries a wrong friction branch
  // through a step (docs/integration.md)
  RunSettings rs = settings(1e-2, "warns", true);
  rs.integrator = "ros34pw2";
  rs.on_warning = [&](const std::string& m) { said.push_back(m); };
  const RunResult r = run(small_scene(), rs);
  EXPECT_GT(r.check.err_speed, 10 * 1e-2);  // measured 0.366
  EXPECT_TRUE(r.check.over());
  ASSERT_EQ(said.size(), 1u);
  EXPECT_EQ(said[0].rfind("check: at t = " + rounded_text(r.check.warned_t) +
                              " s the estimated error so far of the "
                              "pulley speeds is ",
                          0),
            0u)
      << said[0];
  EXPECT_NE(said[0].find("past 10×rtol = 0.1"), std::string::npos) << said[0];
  EXPECT_GT(r.check.warned_t, 0);
  EXPECT_LE(r.check.warned_t, 0.05);
  EXPECT_NE(r.check_line.find("past 3×rtol = 0.03: do not trust"), std::string::npos) << r.check_line;

  // below the limit: not a word while it runs, and none at the end
  said.clear();
  rs = settings(1e-3, "quiet", true);
  rs.on_warning = [&](const std::string& m) { said.push_back(m); };
  const RunResult q = run(small_scene(), rs);
  EXPECT_LT(q.check.err_speed, 3e-3);  // measured 2.4e-3
  EXPECT_LT(q.check.err_tension, 1e-2);  // measured 1.3e-3
  EXPECT_FALSE(q.check.over());
  EXPECT_TRUE(said.empty()) << said[0];
  EXPECT_LT(q.check.warned_t, 0);
  EXPECT_EQ(q.check_line.rfind("check: estimated error of the pulley speeds ", 0), 0u) << q.check_line;
  EXPECT_EQ(q.check_line.find("past"), std::string::npos) << q.check_line;
}

// A run by an integrator that the accuracy contract's measurement found outside it (esdirk32,
// ros34pw2, rkf45; CVODE below rtol 1e-3: docs/accuracy.md) says so as it starts, unless it
// checks its own error; one that keeps it (trbdf2, CVODE at 1e-3) says nothing
TEST(RunCheck, AnIntegratorOutsideTheContractSaysSoAtTheStart) {
  for (const std::string name : {"esdirk32", "ros34pw2", "rkf45", "trbdf2", "cvode"}) {
    for (const double rtol : {1e-3, 1e-4}) {
      for (const bool check : {false, true}) {
        std::vector<std::string> said;
        RunSettings rs = settings(rtol, "start_" + name + (check ? "_checked" : ""), check);
        rs.integrator = name;
        rs.on_warning = [&](const std::string& m) { said.push_back(m); };
        const Simulation sim(small_scene(), rs);
        const bool outside = name != "trbdf2" && (name != "cvode" || rtol < 1e-3);
        if (!outside || check) {
          EXPECT_TRUE(said.empty()) << name << ": " << said[0];
          continue;
        }
        ASSERT_EQ(said.size(), 1u) << name;
        EXPECT_EQ(said[0].rfind("integrator " + name + " does not keep the accuracy contract", 0), 0u) << said[0];
        EXPECT_NE(said[0].find("trbdf2 (the default)"), std::string::npos) << said[0];
      }
    }
  }
}

// a drive with what the contract was measured not to hold with (scene_contract_misses: Stribeck's law
// below rtol 1e-3, an overrunning decoupler at and below 1e-3, μ changing along the belt at any rtol)
// says so as the run starts, or when a stretch is wetted, once; not where the matrix's rows kept it,
// nor when the run checks its own error
TEST(RunCheck, ADriveOutsideTheContractSaysSo) {
  SceneDef stribeck = presets::paper_dry(), decoupled = presets::paper_dry();
  stribeck.belt.elements = decoupled.belt.elements = 30;
  stribeck.friction.law = FrictionKind::stribeck;
  decoupled.pulleys[1].coupling = CouplingDef{.inertia = 0.01, .stiffness = 50, .one_way = true};
  const Scene scenes[] = {build_scene(stribeck), build_scene(decoupled)};
  const char* const words[] = {"Stribeck's law", "an overrunning decoupler"};
  for (int k = 0; k < 2; ++k) {
    for (const double rtol : {1e-3, 1e-4}) {
      for (const bool check : {false, true}) {
        std::vector<std::string> said;
        RunSettings rs = settings(rtol, "drive_" + std::to_string(k), check);
        rs.on_warning = [&](const std::string& m) { said.push_back(m); };
        const Simulation sim(scenes[k], rs);
        const double from = k == 0 ? 1e-3 : 1e-2;  // the rtol from which the matrix's row keeps the contract
        if (rtol >= from || check) {
          EXPECT_TRUE(said.empty()) << words[k] << " at " << rtol << ": " << said[0];
          continue;
        }
        ASSERT_EQ(said.size(), 1u) << words[k];
        EXPECT_EQ(said[0].rfind("at rtol " + rounded_text(rtol) + " this drive may not keep the accuracy contract", 0),
                  0u)
            << said[0];
        EXPECT_NE(said[0].find(words[k]), std::string::npos) << said[0];
      }
    }
  }
  for (const double rtol : {1e-3, 1e-4}) {
    std::vector<std::string> said;
    RunSettings rs = settings(rtol, "wetted", false);
    rs.on_warning = [&](const std::string& m) { said.push_back(m); };
    Simulation sim(small_scene(), rs);
    EXPECT_TRUE(said.empty()) << said[0];  // dry
    std::vector<double> mu(30, std::nan(""));
    for (int i = 0; i < 10; ++i) mu[i] = 0.1;
    sim.set_mu(mu, "wet", "test");
    sim.set_mu(mu, "wet", "again");
    ASSERT_EQ(said.size(), 1u);  // once
    EXPECT_NE(said[0].find("where μ changes along the belt"), std::string::npos) << said[0];
  }
}

// the overrunning decoupler's warning is given at the start whether the clutch overruns or not;
// a run whose clutch never overran (the summary's overrun_count 0) says at its end that it did not
// apply; one whose clutch overran (its rotor set ahead of the pulley) or that was not warned says nothing
TEST(RunCheck, ADecouplerThatNeverOverranSaysTheWarningDidNotApply) {
  SceneDef d = presets::paper_dry();
  d.belt.elements = 30;
  d.pulleys[1].coupling = CouplingDef{.inertia = 0.01, .stiffness = 50, .one_way = true};
  const Scene sc = build_scene(d);
  const auto ran = [&](double rtol, const std::string& name, bool overrun) {
    RunSettings rs = settings(rtol, name, false);
    rs.on_warning = [](const std::string&) {};
    Simulation sim(sc, rs);
    sim.run_to(0.01);
    if (overrun) {
      const double omega = sim.pulley(1).omega;  // the rotor runs ahead: the clutch opens
      sim.set_rotor(1, std::nullopt, omega + (omega < 0 ? -50 : 50));
    }
    sim.run_to(0.012);
    sim.close();
    return sim.unapplied_warnings();
  };
  EXPECT_EQ(ran(1e-3, "decoupler_engaged", false),
            "the start's warning of an overrunning decoupler's accuracy did not apply to this run: the clutch of "
            "pulley 'driven' never overran up to t = 0.012 s (overrun_count 0 in its summary, docs/summary.md)");
  EXPECT_EQ(ran(1e-3, "decoupler_overrun", true), "");
  EXPECT_EQ(ran(1e-2, "decoupler_unwarned", false), "");  // no warning at the start
}

TEST(RunCheck, ParametersCsvHoldsTheFigures) {
  test::expect_warnings({WarningKind::failed_step});
  const RunResult r = run(small_scene(), settings(1e-3, "parameters", true));
  const std::string p = test::slurp(r.parameters_path);
  for (const std::string& row : {std::string("\nrun.check,1,,run,"), std::string("\ncheck.rtol,1e-04,,derived,"),
                                 "\ncheck.err_speed," + number_text(r.check.err_speed) + ",,derived,",
                                 "\ncheck.err_tension," + number_text(r.check.err_tension) + ",,derived,",
                                 std::string("\ncheck.limit_speed,0.003,,derived,"),
                                 std::string("\ncheck.limit_tension,0.01,,derived,"), std::string("\ncheck.over,0,,derived,"),
                                 std::string("\ncheck.warned_t,,,derived,"), std::string("\ncheck.failed,,,derived,")})
    EXPECT_NE(p.find(row), std::string::npos) << row << " in\n" << p;
  const std::string plain = test::slurp(run(small_scene(), settings(1e-2, "parameters_plain", false)).parameters_path);
  EXPECT_NE(plain.find("\nrun.check,0,,run,"), std::string::npos);
  EXPECT_EQ(plain.find("\ncheck."), std::string::npos);
}

// a jump of the state at a pause (the driven pulley's speed set, then freed again) reaches the
// companion: the estimate is within a factor 3 of the true error (a run at 1e-7 with the same
// changes). Without it the companion would go on from its speed before the jump (-1.7 rad/s
// against -3) and the estimate would be of the jump's size.
TEST(RunCheck, AJumpAtAPauseIsAppliedToTheCompanion) {
  test::expect_warnings({WarningKind::failed_step});
  auto jumps = [](double rtol, const std::string& name) {
    auto sim = std::make_unique<Simulation>(small_scene(), settings(rtol, name, rtol > 1e-7));
    sim->run_to(0.02);
    TimeSpeedLaw law;
    law.constant = -3.0;
    sim->set_speed(1, law, "-3");
    sim->run_to(0.03);
    sim->set_torque(1, TimeSpeedLaw{}, "0");  // turns freely from -3 rad/s
    sim->run_to(0.05);
    return sim;
  };
  const auto sim = jumps(1e-3, "jump"), ref = jumps(1e-7, "jump_reference");
  const CheckEstimate c = sim->check_estimate();
  ASSERT_TRUE(c.on);
  const Errors e = true_error(sim->samples(), ref->samples());
  EXPECT_GT(c.err_speed, e.speed / 3) << e.speed;
  EXPECT_LT(c.err_speed, e.speed * 3) << e.speed;
  EXPECT_GT(c.err_tension, e.tension / 3) << e.tension;
  EXPECT_LT(c.err_tension, e.tension * 3) << e.tension;
}

}  // namespace
}  // namespace beltsim
