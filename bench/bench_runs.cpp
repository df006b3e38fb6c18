// Whole-run benchmarks, each measuring its comparisons side by side in one run (the machines
// are noisy, so ratios come from the same minutes):
//   Seconds/<scenario>   wall time per simulated second of the paper's dry and half-wet drives
//                        over their first BELTSIM_BENCH_T seconds (default 0.1: CVODE stalls
//                        later, README) for each integrator=rtol of BELTSIM_BENCH_RTOLS, each
//                        run's speed error against esdirk32 at rtol 1e-8, and the time ratios
//                        to esdirk32
//   Scaling              cost per simulated second at 60, 150, 600 and 2400 elements, over a
//                        window of the running drive, and that cost per element relative to 60
//   StepLoopAllocations  heap allocations per accepted step inside the driver's loop
// Environment: BELTSIM_BENCH_RTOL (Scaling, default 1e-3), BELTSIM_BENCH_WINDOW (Scaling, 0.02 s).
#include <benchmark/benchmark.h>

#include <atomic>
#include <cstdlib>
#include <sstream>

#include "integrate/belt_system.hpp"
#include "integrate/cvode.hpp"
#include "integrate/driver.hpp"
#include "integrate/stepper.hpp"
#include "scene/presets.hpp"

// every heap allocation of the process is counted: malloc itself is interposed (Eigen allocates
// with malloc directly; operator new goes through it too), forwarding to glibc's own
extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
}
namespace {
std::atomic<long> g_allocations{0};
}
extern "C" void* malloc(std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_malloc(n);
}
extern "C" void* calloc(std::size_t n, std::size_t k) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_calloc(n, k);
}
extern "C" void* realloc(void* p, std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  return __libc_realloc(p, n);
}

namespace beltsim {
namespace {

double env_number(const char* name, double fallback) {
  const char* v = std::getenv(name);
  return v ? std::atof(v) : fallback;
}

// integrator=rtol pairs. The defaults give comparable errors over the dry drive's first 0.1 s
// (`beltsim wp --t-end 0.1`, README): esdirk32 at 1e-5 stays within 2.5e-4 of the reference in
// the speeds, CVODE at 1e-7 within 4.8e-4 (CVODE at 1e-3 … 1e-6 did not get through the 0.1 s in
// 120 s, or diverged at 1e-4). cvode-fd is not in the default list (it did not get through the
// 0.1 s in 120 s at any tolerance); add "cvode-fd=1e-7" to include it. Each run's own error is
// reported next to its time.
std::vector<std::pair<std::string, double>> bench_integrators() {
  const char* v = std::getenv("BELTSIM_BENCH_RTOLS");
  std::stringstream ss(v ? v : "esdirk32=1e-5,cvode=1e-7");
  std::vector<std::pair<std::string, double>> out;
  for (std::string item; std::getline(ss, item, ',');) {
    const size_t eq = item.find('=');
    if (eq != std::string::npos) out.emplace_back(std::string(item.begin(), item.begin() + static_cast<long>(eq)), std::atof(item.c_str() + eq + 1));
  }
  return out;
}

DriveResult simulate(const Model& m, Eigen::VectorXd& y, double t0, double t_end, const std::string& method,
                     double rtol, std::vector<Eigen::VectorXd>* samples = nullptr) {
  BeltSystem sys(m);
  DriveOptions o;
  o.t0 = t0;
  o.t_end = t_end;
  o.sample_dt = 1e-3;
  o.events = m.breakpoints();
  const auto keep = [&](double, const Eigen::VectorXd& yy) {
    if (samples) samples->push_back(yy);
  };
  if (is_cvode(method)) return drive_cvode(sys, method, Tolerances{rtol, -1}, o, y, keep);
  auto st = make_stepper(method);
  return drive(sys, *st, Tolerances{rtol, -1}, o, y, keep);
}

// largest deviation of a pulley speed over the samples, relative to the reference's largest speed
double speed_error(const Model& m, const std::vector<Eigen::VectorXd>& run, const std::vector<Eigen::VectorXd>& ref) {
  const int base = m.n_coord() + 3 * m.n_el();
  double err = 0, scale = 0;
  for (size_t k = 0; k < std::min(run.size(), ref.size()); ++k)
    for (int j = 0; j < m.n_p(); ++j) {
      err = std::max(err, std::abs(run[k][base + j] - ref[k][base + j]));
      scale = std::max(scale, std::abs(ref[k][base + j]));
    }
  return err / scale;
}

void BM_Seconds(benchmark::State& state, SceneDef (*preset)()) {
  const Scene sc = build_scene(preset());
  const double T = env_number("BELTSIM_BENCH_T", 0.1);
  for (auto _ : state) {
    std::vector<Eigen::VectorXd> ref;
    Eigen::VectorXd y = sc.y0;
    simulate(sc.model, y, 0, T, "esdirk32", 1e-8, &ref);
    double base = 0;
    for (const auto& [name, rtol] : bench_integrators()) {
      std::vector<Eigen::VectorXd> samples;
      y = sc.y0;
      const DriveResult r = simulate(sc.model, y, 0, T, name, rtol, &samples);
      const double per_s = r.wall_seconds / T;
      if (name == "esdirk32") base = per_s;
      state.counters[name + "_wall_per_sim_s"] = per_s;
      state.counters[name + "_speed_error"] = speed_error(sc.model, samples, ref);
      state.counters[name + "_steps"] = static_cast<double>(r.work.steps);
      if (base > 0 && name != "esdirk32") state.counters[name + "_over_esdirk32"] = per_s / base;
    }
  }
}
BENCHMARK_CAPTURE(BM_Seconds, dry, &presets::paper_dry)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_Seconds, half_wet, &presets::paper_wet)->Unit(benchmark::kSecond)->Iterations(1);

// cost per simulated second over [0.3, 0.3 + W] s of the dry drive (running at ≈ 57 rad/s, the
// ramp just ended) for 60..2400 elements; the state at 0.3 s comes from a run at rtol 1e-2
void BM_Scaling(benchmark::State& state) {
  const double W = env_number("BELTSIM_BENCH_WINDOW", 0.02), rtol = env_number("BELTSIM_BENCH_RTOL", 1e-3);
  for (auto _ : state) {
    double base = 0;
    for (int n : {60, 150, 600, 2400}) {
      SceneDef d = presets::paper_dry();
      d.belt.elements = n;
      const Scene sc = build_scene(d);
      Eigen::VectorXd y = sc.y0;
      simulate(sc.model, y, 0, 0.3, "esdirk32", 1e-2);
      const DriveResult r = simulate(sc.model, y, 0.3, 0.3 + W, "esdirk32", rtol);
      const double per_s = r.wall_seconds / W;
      std::string tag = std::to_string(n);
      tag.insert(tag.begin(), 'n');
      state.counters[tag + "_wall_per_sim_s"] = per_s;
      state.counters[tag + "_steps_per_sim_s"] = static_cast<double>(r.work.steps) / W;
      if (n == 60) base = per_s;
      state.counters[tag + "_cost_per_element_vs_n60"] = (per_s / n) / (base / 60);
    }
  }
}
BENCHMARK(BM_Scaling)->Unit(benchmark::kSecond)->Iterations(1);

// allocations inside the step loop: two runs from the same running state that differ only in
// length; the difference in allocations over the difference in steps (set-up cancels)
void BM_StepLoopAllocations(benchmark::State& state) {
  const Scene sc = build_scene(presets::paper_dry());
  Eigen::VectorXd y0 = sc.y0;
  simulate(sc.model, y0, 0, 0.3, "esdirk32", 1e-2);
  for (auto _ : state) {
    long steps[2], allocs[2];
    int k = 0;
    for (double W : {0.005, 0.015}) {
      Eigen::VectorXd y = y0;
      BeltSystem sys(sc.model);
      auto st = make_stepper("esdirk32");
      DriveOptions o;
      o.t0 = 0.3;
      o.t_end = 0.3 + W;
      o.sample_dt = 1e-3;
      o.events = sc.model.breakpoints();
      const long a0 = g_allocations.load();
      const DriveResult r = drive(sys, *st, Tolerances{1e-3, -1}, o, y, [](double, const Eigen::VectorXd&) {});
      allocs[k] = g_allocations.load() - a0;
      steps[k] = r.work.steps + r.work.rejected;
      ++k;
    }
    state.counters["allocations_per_step"] =
        static_cast<double>(allocs[1] - allocs[0]) / static_cast<double>(steps[1] - steps[0]);
    state.counters["steps"] = static_cast<double>(steps[1] - steps[0]);
  }
}
BENCHMARK(BM_StepLoopAllocations)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
}  // namespace beltsim
