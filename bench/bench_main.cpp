// Benchmarks (their own target, not part of the test run): the cost of the pieces of one
// implicit step on the paper's dry drive, and of a short simulated interval per integrator.
//   build/bench/beltsim_bench [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include "integrate/belt_system.hpp"
#include "integrate/driver.hpp"
#include "integrate/stepper.hpp"
#include "model/rhs.hpp"
#include "scene/presets.hpp"

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

}  // namespace
}  // namespace beltsim

BENCHMARK_MAIN();
