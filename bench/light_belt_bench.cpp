// The light undamped belt of scripts/light_belt.lua (a datasheet belt with no bending damping on two
// small pulleys, 2.45 s of start-up and steady drive) at 60 and 240 elements, side by side, with the
// run default integrator and tolerance: the steps and the wall time of each and their ratios
// (240 over 60). The goal (docs/accuracy.md, "The accuracy contract"): the 240-element run
// within 1.5 times the 60-element run's steps, in at most 30 s on the 2-core machine. Quote
// BM_Rhs beside the wall times: the machine's speed varies from hour to hour.
// Environment: BELTSIM_LIGHT_BELT_T (the window, default the script's 2.45 s).
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <string>

#include "capture.hpp"
#include "script/interpreter.hpp"
#include "script/script_args.hpp"
#include "sim/simulation.hpp"

namespace beltsim {
namespace {

RunResult run_light_belt(int elements) {
  script::Overrides o;
  if (const char* t = std::getenv("BELTSIM_LIGHT_BELT_T")) o.run.t_end = std::atof(t), o.give("t_end");
  o.set = script::parse_sets({"n=" + std::to_string(elements)});
  const script::Captured cap = capture_run("scripts/light_belt.lua", o);
  RunSettings s = cap.settings;
  s.out_dir = "out/light_belt_bench/n" + std::to_string(elements);
  return run(*cap.scene, s);
}

void BM_LightBelt(benchmark::State& state) {
  for (auto _ : state) {
    const RunResult a = run_light_belt(60), b = run_light_belt(240);
    state.counters["t_end_s"] = b.t_reached;
    state.counters["steps_60"] = static_cast<double>(a.work.steps);
    state.counters["steps_240"] = static_cast<double>(b.work.steps);
    state.counters["steps_240_over_60"] = static_cast<double>(b.work.steps) / static_cast<double>(a.work.steps);
    state.counters["wall_60_s"] = a.wall_seconds;
    state.counters["wall_240_s"] = b.wall_seconds;
    state.counters["wall_240_over_60"] = b.wall_seconds / a.wall_seconds;
  }
}
BENCHMARK(BM_LightBelt)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace beltsim
