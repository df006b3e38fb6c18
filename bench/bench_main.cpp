// Benchmarks (their own target, not part of the test run): the cost of the pieces of one
// implicit step on the paper's dry drive, and of a short simulated interval per integrator.
//   build/bench/beltsim_bench [--benchmark_filter=...]
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "integrate/belt_system.hpp"
#include "integrate/driver.hpp"
#include "integrate/stepper.hpp"
#include "model/contact_law.hpp"
#include "model/rhs.hpp"
#include "sim/simulation.hpp"
#include "support/presets.hpp"

namespace beltsim {
namespace {

// a running state: the paper's drive after 50 ms
const Scene& scene() {
  static const Scene sc = build_scene(presets::paper_dry());
  return sc;
}

Eigen::VectorXd running_state() {
  BeltSystem sys(scene().model, scene().drive);
  auto st = make_stepper("esdirk32");
  DriveOptions o;
  o.t_end = 0.05;
  o.sample_dt = 0.05;
  o.events = scene().drive.breakpoints();
  Eigen::VectorXd y = scene().y0;
  drive(sys, *st, Tolerances{1e-5, -1}, o, y, [](double, const Eigen::VectorXd&) {});
  return y;
}

void BM_Rhs(benchmark::State& state) {
  const Eigen::VectorXd y = running_state();
  Eigen::VectorXd dy(y.size());
  for (auto _ : state) {
    rhs(scene().model, scene().drive, 0.05, y.data(), dy.data());
    benchmark::DoNotOptimize(dy.data());
  }
}
BENCHMARK(BM_Rhs);

void BM_Jacobian(benchmark::State& state) {
  const Eigen::VectorXd y = running_state();
  Jacobian J;
  J.resize(scene().model);
  for (auto _ : state) {
    jacobian(scene().model, scene().drive, 0.05, y.data(), J);
    benchmark::DoNotOptimize(J.K.diag.data());
  }
}
BENCHMARK(BM_Jacobian);

void BM_FactorAndSolve(benchmark::State& state) {
  const Eigen::VectorXd y = running_state();
  BeltSystem sys(scene().model, scene().drive);
  sys.linear.prepare_jacobian(0.05, y.data());
  Eigen::VectorXd r = Eigen::VectorXd::Ones(y.size()), u(y.size());
  for (auto _ : state) {
    sys.linear.factor(1e5);
    sys.linear.solve(r.data(), u.data());
    benchmark::DoNotOptimize(u.data());
  }
}
BENCHMARK(BM_FactorAndSolve);

// the paper's drive with a belt of n elements, in its initial static state
Scene scene_of(int n) {
  SceneDef d = presets::paper_dry();
  d.belt.elements = n;
  return build_scene(d);
}

// the same for belts of 60, 600 and 2 400 elements
void BM_FactorAndSolveN(benchmark::State& state) {
  const Scene sc = scene_of(static_cast<int>(state.range(0)));
  BeltSystem sys(sc.model, sc.drive);
  sys.linear.prepare_jacobian(0.0, sc.y0.data());
  Eigen::VectorXd r = Eigen::VectorXd::Ones(sc.y0.size()), u(sc.y0.size());
  for (auto _ : state) {
    sys.linear.factor(1e5);
    sys.linear.solve(r.data(), u.data());
    benchmark::DoNotOptimize(u.data());
  }
  state.counters["ns_per_element"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * static_cast<double>(state.range(0)),
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_FactorAndSolveN)->Arg(60)->Arg(600)->Arg(2400);

// the right-hand side for belts of 60, 600 and 2 400 elements
void BM_RhsN(benchmark::State& state) {
  const Scene sc = scene_of(static_cast<int>(state.range(0)));
  Eigen::VectorXd dy(sc.y0.size());
  for (auto _ : state) {
    rhs(sc.model, sc.drive, 0.0, sc.y0.data(), dy.data());
    benchmark::DoNotOptimize(dy.data());
  }
}
BENCHMARK(BM_RhsN)->Arg(60)->Arg(600)->Arg(2400)->UseRealTime();

// the same through BeltSystem, which evaluates a belt of kHalvesElements or more in two halves at
// once (wall time: the worker's half is on another core); and its Jacobian
void BM_SystemRhsN(benchmark::State& state) {
  const Scene sc = scene_of(static_cast<int>(state.range(0)));
  BeltSystem sys(sc.model, sc.drive);
  Eigen::VectorXd dy(sc.y0.size());
  for (auto _ : state) {
    sys.problem.rhs(0.0, sc.y0.data(), dy.data());
    benchmark::DoNotOptimize(dy.data());
  }
}
BENCHMARK(BM_SystemRhsN)->Arg(60)->Arg(600)->Arg(2400)->UseRealTime();

void BM_SystemJacobianN(benchmark::State& state) {
  const Scene sc = scene_of(static_cast<int>(state.range(0)));
  BeltSystem sys(sc.model, sc.drive);
  Eigen::VectorXd y = sc.y0;
  for (auto _ : state) {
    y[2] += 1e-12;  // a fresh angle each time: the axis memo must not serve it
    sys.linear.prepare_jacobian(0.0, y.data());
  }
}
BENCHMARK(BM_SystemJacobianN)->Arg(60)->Arg(600)->Arg(2400)->UseRealTime();

// wall time for the first 20 ms of the dry drive (from rest), per integrator
void BM_Simulate20ms(benchmark::State& state, const char* method) {
  for (auto _ : state) {
    BeltSystem sys(scene().model, scene().drive);
    auto st = make_stepper(method);
    DriveOptions o;
    o.t_end = 0.02;
    o.sample_dt = 1e-3;
    o.events = scene().drive.breakpoints();
    Eigen::VectorXd y = scene().y0;
    const DriveResult r = drive(sys, *st, Tolerances{1e-5, -1}, o, y, [](double, const Eigen::VectorXd&) {});
    state.counters["steps"] = static_cast<double>(r.work.steps);
  }
}
BENCHMARK_CAPTURE(BM_Simulate20ms, esdirk32, "esdirk32")->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Simulate20ms, ros34pw2, "ros34pw2")->Unit(benchmark::kMillisecond);

// The friction laws (model/contact_law.hpp). A scene on Threlfall's law pays nothing for
// Stribeck's: the contact pass picks the law once per pass, outside the loop over pairs, so its
// inner loop is the one it was. Rows, in one run: the contact pass of the dry drive's running state
// through contact_pass (the law picked) and through contact_pass_with and Threlfall's law directly
// (the loop as it was before there was a choice), and the same pass, the right-hand side and 20 ms
// from rest under Stribeck's law (μ_s/μ_k = 1.3, v_s = 0.01 m/s, δ = 2, μ_v = 0).
const Scene& stribeck_scene() {
  static const Scene sc = [] {
    SceneDef d = presets::paper_dry();
    d.friction.law = FrictionKind::stribeck;
    return build_scene(d);
  }();
  return sc;
}

void BM_ContactPass(benchmark::State& state, int which) {
  const Scene& sc = which == 2 ? stribeck_scene() : scene();
  const Eigen::VectorXd y = running_state();
  const Model& m = sc.model;
  const double* q = y.data();
  const double* v = q + m.n_coord();
  ContactList pairs;
  for (auto _ : state) {
    if (which == 0) {
      contact_pass_with(m, sc.drive, 0.05, q, v, Span{0, m.n_el()}, pairs, Pairs::touching,
                        [dv = m.friction.dv](int, double mu_i, const NormalLaw& nl, const Vec2& V, double omega) {
                          return friction_law(mu_i, dv, nl, V, omega);
                        });
    } else {
      contact_pass(m, sc.drive, 0.05, q, v, nullptr, Span{0, m.n_el()}, pairs);
    }
    benchmark::DoNotOptimize(pairs.data());
  }
}
BENCHMARK_CAPTURE(BM_ContactPass, threlfall_direct, 0);
BENCHMARK_CAPTURE(BM_ContactPass, threlfall, 1);
BENCHMARK_CAPTURE(BM_ContactPass, stribeck, 2);

void BM_RhsStribeck(benchmark::State& state) {
  const Eigen::VectorXd y = running_state();
  Eigen::VectorXd dy(y.size());
  for (auto _ : state) {
    rhs(stribeck_scene().model, stribeck_scene().drive, 0.05, y.data(), dy.data());
    benchmark::DoNotOptimize(dy.data());
  }
}
BENCHMARK(BM_RhsStribeck);

void BM_Simulate20msStribeck(benchmark::State& state) {
  for (auto _ : state) {
    BeltSystem sys(stribeck_scene().model, stribeck_scene().drive);
    auto st = make_stepper("esdirk32");
    DriveOptions o;
    o.t_end = 0.02;
    o.sample_dt = 1e-3;
    o.events = stribeck_scene().drive.breakpoints();
    Eigen::VectorXd y = stribeck_scene().y0;
    const DriveResult r = drive(sys, *st, Tolerances{1e-5, -1}, o, y, [](double, const Eigen::VectorXd&) {});
    state.counters["steps"] = static_cast<double>(r.work.steps);
  }
}
BENCHMARK(BM_Simulate20msStribeck)->Unit(benchmark::kMillisecond);

// What a feature costs a scene that uses it, beside the same drive without it (one run, so the
// ratios hold on a noisy machine): a live simulation of 0.1 s from rest of the paper's dry drive as it is, with a spray
// zone off the belt's path that sprays throughout (the per-element μ records and the entry test
// run, no element is ever wet), and with the driven pulley's inertia split into a hub and a rotor
// behind a stiff two-way decoupler (two more coordinates in the ring solver's border).
const Scene& variant_scene(int which) {
  static const Scene plain = build_scene(presets::paper_dry());
  static const Scene spray = [] {
    SceneDef d = presets::paper_dry();
    SprayZone z;
    z.centre = Vec2(0.145, 1.0);  // a metre above the drive
    z.radius = 0.05, z.mu = 0.2, z.from = 0, z.to = 1e9, z.drying_length = 1;
    d.spray.push_back(z);
    return build_scene(d);
  }();
  static const Scene coupled = [] {
    SceneDef d = presets::paper_dry();
    CouplingDef c;
    c.inertia = 0.5 * d.pulleys[1].inertia, c.stiffness = 500, c.damping = 0.5;
    d.pulleys[1].inertia *= 0.5;
    d.pulleys[1].coupling = c;
    return build_scene(d);
  }();
  static const Scene lugre = [] {
    SceneDef d = presets::paper_dry();
    d.friction.law = FrictionKind::lugre;
    return build_scene(d);
  }();
  return which == 0 ? plain : which == 1 ? spray : which == 2 ? coupled : lugre;
}

void BM_Simulate100msWith(benchmark::State& state, int which) {
  const Scene& sc = variant_scene(which);
  const std::string out =
      (std::filesystem::temp_directory_path() / ("beltsim_bench_with_" + std::to_string(getpid()))).string();
  for (auto _ : state) {
    // a Simulation: its schedule holds the spray zones' entry test
    RunSettings rs;
    rs.integrator = "esdirk32";
    rs.rtol = 1e-5;
    rs.sample_dt = 1e-3;
    rs.out_dir = out;
    Simulation s(sc, rs);
    s.run_to(0.1);
    state.counters["steps"] = static_cast<double>(s.stats().steps);
    s.close();
  }
  std::filesystem::remove_all(out);
}
BENCHMARK_CAPTURE(BM_Simulate100msWith, nothing, 0)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Simulate100msWith, spray_off_path, 1)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Simulate100msWith, decoupler, 2)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_Simulate100msWith, lugre, 3)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace beltsim

BENCHMARK_MAIN();
