// The speed goals of the accuracy work (docs/accuracy.md, "The accuracy contract"), each a run a
// user makes, in CPU seconds per simulated second. Quote BM_Rhs beside them (run with
// --benchmark_filter='^BM_Rhs$|BM_Serpentine|BM_DrySecond'): the machine's speed varies 2x from
// hour to hour.
//   BM_SerpentineAtSpeed/R  scripts/serpentine.lua (200 elements, six pulleys, a tensioner arm and
//                           a decoupler) at rtol 10^-R: the run-up to 0.2 s untimed, then
//                           0.2 s .. 0.2 s + BELTSIM_SERPENTINE_T (default 0.05 s) timed. Goal: a
//                           simulated second in at most 10 s.
//   BM_DrySecond            scripts/paper_dry.lua's second at rtol 4e-3 (where its pulley speeds
//                           first come within 0.1 %), its errors against trbdf2 at rtol 1e-6 as
//                           `beltsim wp` measures them. Goal: within 0.1 % in at most 0.1 s.
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <ctime>
#include <string>

#include "capture.hpp"
#include "sim/simulation.hpp"
#include "sim/work_precision.hpp"

namespace beltsim {
namespace {

// CPU seconds of the process so far (std::clock, as bench_runs.cpp: on a shared machine the wall
// time includes other jobs' turns)
double cpu_seconds() {
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

void BM_SerpentineAtSpeed(benchmark::State& state) {
  const double rtol = std::pow(10.0, -static_cast<double>(state.range(0)));
  const char* tv = std::getenv("BELTSIM_SERPENTINE_T");
  const double window = tv ? std::atof(tv) : 0.05, t0 = 0.2;
  const script::Captured cap = capture_run("scripts/serpentine.lua");
  for (auto _ : state) {
    RunSettings s = cap.settings;
    s.rtol = rtol;
    s.progress = false;
    s.out_dir = "out/goals_bench/serpentine_" + std::to_string(state.range(0));
    Simulation sim(*cap.scene, s);
    sim.run_to(t0);
    const WorkCounters a = sim.stats();
    const double c0 = cpu_seconds();
    sim.run_to(t0 + window);
    const double cpu = cpu_seconds() - c0;
    const WorkCounters b = sim.stats();
    const double attempts = static_cast<double>(b.steps - a.steps + b.rejected - a.rejected);
    state.counters["cpu_per_sim_s"] = cpu / window;
    state.counters["steps_per_sim_s"] = static_cast<double>(b.steps - a.steps) / window;
    state.counters["rejected_share"] = static_cast<double>(b.rejected - a.rejected) / attempts;
    state.counters["rhs_per_attempt"] = static_cast<double>(b.rhs - a.rhs) / attempts;
    state.counters["jacobians_per_attempt"] = static_cast<double>(b.jacobians - a.jacobians) / attempts;
    state.counters["goal_s"] = 10;
  }
}
BENCHMARK(BM_SerpentineAtSpeed)->Arg(3)->Arg(4)->Unit(benchmark::kSecond)->Iterations(1);

void BM_DrySecond(benchmark::State& state) {
  const script::Captured cap = capture_run("scripts/paper_dry.lua");
  for (auto _ : state) {
    WpSettings wps;
    wps.integrators = {"trbdf2"};
    wps.rtols = {4e-3};
    wps.ref_rtol = 1e-6;  // trbdf2's own error there, 7.0e-6 (work_precision.hpp), under 1 % of the goal's 0.1 %
    wps.base = cap.settings;
    wps.base.t_end = 1;
    wps.base.progress = false;
    wps.base.out_dir = "out/goals_bench/dry_second";
    const double c0 = cpu_seconds();
    const WpResult r = work_precision(*cap.scene, wps);
    const double total = cpu_seconds() - c0;
    const WpRow& w = r.rows.at(0);
    state.counters["wall_per_sim_s"] = w.wall / w.t_reached;
    state.counters["err_speed"] = w.err_speed;
    state.counters["err_tension"] = w.err_tension;
    state.counters["steps"] = static_cast<double>(w.work.steps);
    state.counters["reference_and_run_cpu_s"] = total;
    state.counters["goal_s"] = 0.1;
  }
}
BENCHMARK(BM_DrySecond)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace beltsim
