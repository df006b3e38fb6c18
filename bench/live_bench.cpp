// Live simulation overhead, measured side by side in one run (ratios to the batch run):
//   Live/batch      scene:run{ t_end } (start + run_to + close in C++), no callbacks
//   Live/paused     the same run as 200 sim:advance calls from Lua (pausing reads the dense
//                   output; the integrator's steps are the same)
//   Live/every_lua  the batch run plus a Lua sim:every(1e-3) callback that changes nothing:
//                   what one Lua call per millisecond of simulated time costs
// A simulation without callbacks runs no Lua while integrating, so batch and paused should
// cost the same. Scene: the paper's dry drive, 0.1 s, esdirk32 at rtol 1e-4, no frames.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "script/interpreter.hpp"
#include "support/scenes.hpp"

namespace {

namespace fs = std::filesystem;

// the paper's drive at 60 elements (the tests' scene, tests/support/two_pulley.lua)
const std::string kScene = [] {
  beltsim::test::TwoPulley p;
  p.elements = 60;
  return beltsim::test::two_pulley(p);
}();

double run_script(const std::string& body) {
  const fs::path dir = fs::temp_directory_path() / ("beltsim_live_bench_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const fs::path p = dir / "live.lua";
  std::ofstream(p) << kScene << body;
  beltsim::script::Interpreter lua;
  beltsim::script::Overrides o;
  o.run.out_dir = (dir / "out").string(), o.give("out");
  lua.set_overrides(o);
  const auto t0 = std::chrono::steady_clock::now();
  lua.run_file(p.string());
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

const char* kBatch = "s:run{ t_end = 0.1, progress = false }\n";
const char* kPaused =
    "local sim = s:start{ progress = false }\n"
    "for i = 1, 200 do sim:advance(0.0005) end\n"
    "sim:close()\n";
const char* kEvery =
    "local sim = s:start{ progress = false }\n"
    "local n = 0\n"
    "sim:every(1e-3, function(sim) n = n + 1 end)\n"
    "sim:run_to(0.1)\n"
    "sim:close()\n";

void BM_Live(benchmark::State& state) {
  double batch = 0, paused = 0, every = 0;
  long n = 0;
  for (auto _ : state) {
    batch += run_script(kBatch);
    paused += run_script(kPaused);
    every += run_script(kEvery);
    n++;
  }
  state.counters["batch_s"] = batch / n;
  state.counters["paused_s"] = paused / n;
  state.counters["every_lua_s"] = every / n;
  state.counters["paused/batch"] = paused / batch;
  state.counters["every_lua/batch"] = every / batch;
}
BENCHMARK(BM_Live)->Unit(benchmark::kSecond)->Iterations(3);

}  // namespace
