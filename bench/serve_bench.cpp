// The live view's cost (docs/live-view.md), side by side in one run, each case a fresh interpreter
// running the same batch run (the paper's dry drive, 60 elements, 2 s: several seconds of wall
// time, so that the renderer's start, about 0.1 s of CPU once per run, weighs as little as in the
// long runs a page watches; esdirk32 at rtol 1e-4, no frames to files); the three cases
// interleaved in every iteration:
//   plain       no --serve
//   served      --serve, no page open: the samples published at 20 a wall second, nothing drawn
//   watched     --serve and one client reading the stream and asking for the picture as a page
//               does (the next when one has arrived, 66 ms later): frames drawn at up to 15/s
// Counters: the mean wall seconds of each and served/plain, watched/plain; the CPU seconds beltsim
// spent in each (every thread of the process but the client's own: the frame thread, Mesa's
// rasteriser threads and the server's count) and their ratios cpu_served/plain,
// cpu_watched/plain, which a loaded machine's noise disturbs far less than wall time (on a busy
// 2-core machine each CPU second of the live view is taken from the run).
#include <benchmark/benchmark.h>
#include <httplib.h>
#include <sys/resource.h>
#include <time.h>
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
    "s:run{ t_end = 2, progress = false }\n";

enum class Serve { no, served, watched };

// [s] of CPU this thread has used
double thread_cpu() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// [s] of CPU the process has used (all its threads)
double process_cpu() {
  rusage u;
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// a page's traffic: the stream read, the picture asked for again 66 ms after each arrives;
// client_cpu: the CPU its two threads used
void watch(const std::string& url, const std::atomic<bool>& done, long* frames, std::atomic<double>* client_cpu) {
  const std::string host_port = url.substr(0, url.find("/?token="));
  const std::string q = url.substr(url.find("?token="));
  std::thread stream([&] {
    httplib::Client c(host_port);
    c.Get(("/events" + q).c_str(), [&](const char*, size_t) { return !done.load(); });
    *client_cpu = *client_cpu + thread_cpu();
  });
  httplib::Client c(host_port);
  while (!done.load()) {
    if (auto r = c.Get(("/frame.jpg" + q).c_str()); r && r->status == 200) ++*frames;
    std::this_thread::sleep_for(std::chrono::milliseconds(66));
  }
  stream.join();
  *client_cpu = *client_cpu + thread_cpu();
}

struct Cost {
  double wall = 0, cpu = 0;  // [s]
};

Cost run_served(Serve how, long* frames) {
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
  std::atomic<double> client_cpu{0};
  std::thread client;
  if (how == Serve::watched) client = std::thread([&] { watch(url.substr(7), done, frames, &client_cpu); });
  const double cpu0 = process_cpu();
  const auto t0 = std::chrono::steady_clock::now();
  lua.run_file(p.string());
  Cost c;
  c.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  c.cpu = process_cpu() - cpu0;
  done = true;
  if (client.joinable()) client.join();
  c.cpu -= client_cpu;  // (what the client used after the run is subtracted too: a small overstatement)
  return c;
}

void BM_Serve(benchmark::State& state) {
  double plain = 0, served = 0, watched = 0, cpu_plain = 0, cpu_served = 0, cpu_watched = 0;
  long n = 0, frames = 0;
  for (auto _ : state) {
    Cost c = run_served(Serve::no, &frames);
    plain += c.wall, cpu_plain += c.cpu;
    c = run_served(Serve::served, &frames);
    served += c.wall, cpu_served += c.cpu;
    c = run_served(Serve::watched, &frames);
    watched += c.wall, cpu_watched += c.cpu;
    n++;
  }
  state.counters["cpu_plain_s"] = cpu_plain / n;
  state.counters["cpu_served/plain"] = cpu_served / cpu_plain;
  state.counters["cpu_watched/plain"] = cpu_watched / cpu_plain;
  state.counters["plain_s"] = plain / n;
  state.counters["served_s"] = served / n;
  state.counters["watched_s"] = watched / n;
  state.counters["served/plain"] = served / plain;
  state.counters["watched/plain"] = watched / plain;
  state.counters["frames_per_s"] = frames / watched;
}
BENCHMARK(BM_Serve)->Unit(benchmark::kSecond)->Iterations(5);

}  // namespace
