// The live view's cost (docs/live-view.md), side by side in one run, each case a fresh interpreter
// running the same batch run (the paper's dry drive, 60 elements, 0.5 s, esdirk32 at rtol 1e-4,
// no frames to files); the three cases interleaved in every iteration:
//   plain       no --serve
//   served      --serve, no page open: the samples published at 20 a wall second, nothing drawn
//   watched     --serve and one client reading the stream and asking for the picture as a page
//               does (the next when one has arrived, 66 ms later): frames drawn at up to 15/s
// Counters: the mean wall seconds of each and served/plain, watched/plain.
#include <benchmark/benchmark.h>
#include <httplib.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "script/interpreter.hpp"

namespace {

namespace fs = std::filesystem;

const char* kServeScene =
    "local s = beltsim.scene { pulleys = {\n"
    "  { name = 'driver', centre = {0, 0}, radius = 0.1, torque = beltsim.ramp(0.3, -70) },\n"
    "  { name = 'driven', centre = {0.29, 0}, radius = 0.1, torque = { per_speed = -70 / beltsim.rpm(700) } } },\n"
    "  belt = { elements = 60, pretension = 500, direction = 'cw' } }\n"
    "s:run{ t_end = 0.5, progress = false }\n";

enum class Serve { no, served, watched };

// a page's traffic: the stream read, the picture asked for again 66 ms after each arrives
void watch(const std::string& url, const std::atomic<bool>& done, long* frames) {
  const std::string host_port = url.substr(0, url.find("/?token="));
  const std::string q = url.substr(url.find("?token="));
  std::thread stream([&] {
    httplib::Client c(host_port);
    c.Get(("/events" + q).c_str(), [&](const char*, size_t) { return !done.load(); });
  });
  httplib::Client c(host_port);
  while (!done.load()) {
    if (auto r = c.Get(("/frame.png" + q).c_str()); r && r->status == 200) ++*frames;
    std::this_thread::sleep_for(std::chrono::milliseconds(66));
  }
  stream.join();
}

double run_served(Serve how, long* frames) {
  const fs::path dir = fs::temp_directory_path() / ("beltsim_serve_bench_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const fs::path p = dir / "serve.lua";
  std::ofstream(p) << kServeScene;
  beltsim::script::Interpreter lua;
  beltsim::script::Overrides o;
  o.run.out_dir = (dir / "out").string(), o.give("out");
  lua.set_overrides(o);
  std::string url;
  if (how != Serve::no) url = lua.serve(0);
  std::atomic<bool> done{false};
  std::thread client;
  if (how == Serve::watched) client = std::thread([&] { watch(url.substr(7), done, frames); });
  const auto t0 = std::chrono::steady_clock::now();
  lua.run_file(p.string());
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  done = true;
  if (client.joinable()) client.join();
  return wall;
}

void BM_Serve(benchmark::State& state) {
  double plain = 0, served = 0, watched = 0;
  long n = 0, frames = 0;
  for (auto _ : state) {
    plain += run_served(Serve::no, &frames);
    served += run_served(Serve::served, &frames);
    watched += run_served(Serve::watched, &frames);
    n++;
  }
  state.counters["plain_s"] = plain / n;
  state.counters["served_s"] = served / n;
  state.counters["watched_s"] = watched / n;
  state.counters["served/plain"] = served / plain;
  state.counters["watched/plain"] = watched / plain;
  state.counters["frames_per_s"] = frames / watched;
}
BENCHMARK(BM_Serve)->Unit(benchmark::kSecond)->Iterations(5);

}  // namespace
