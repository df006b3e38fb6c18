// The live view's cost (docs/live-view.md), side by side in one run, each case a fresh interpreter
// running the same batch run (the paper's dry drive, 60 elements, 2 s: several seconds of wall
// time, so that the renderer's start, about 0.1 s of CPU once per run, weighs as little as in the
// long runs a page watches; esdirk32 at rtol 1e-4, no frames to files); the three cases
// interleaved in every iteration, in an order rotated from one to the next:
//   plain       no --serve
//   served      --serve, no page open: the samples published at 20 a wall second, nothing drawn
//   watched     --serve and one client reading the stream and asking for the picture as a page
//               does (the next when one has arrived, 66 ms later): frames drawn at up to 15/s
//   stalled     --serve and a page that stopped reading: the stream and 200 picture requests asked
//               for on sockets with the smallest receive buffer, never read
// Counters: the mean wall seconds of each and served/plain, watched/plain, stalled/plain; the CPU seconds beltsim
// spent in each (every thread of the process but the client's own: the frame thread, Mesa's
// rasteriser threads and the server's count) and their ratios cpu_served/plain,
// cpu_watched/plain, which a loaded machine's noise disturbs far less than wall time (on a busy
// 2-core machine each CPU second of the live view is taken from the run).
#include <arpa/inet.h>
#include <benchmark/benchmark.h>
#include <httplib.h>
#include <netinet/in.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "script/interpreter.hpp"
#include "support/scenes.hpp"

namespace {

namespace fs = std::filesystem;

// the paper's drive at 60 elements (the tests' scene, tests/support/two_pulley.lua), 2 s of it
const std::string kServeScene = [] {
  beltsim::test::TwoPulley p;
  p.elements = 60;
  return beltsim::test::two_pulley(p);
}() + "s:run{ t_end = 2, progress = false }\n";

enum class Serve { no, served, watched, stalled };

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

// a page that stopped reading (see the top): its two sockets, closed by the caller
std::vector<int> stall(const std::string& url) {
  const std::string host_port = url.substr(0, url.find("/?token="));
  const std::string q = url.substr(url.find("?token="));
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(static_cast<uint16_t>(std::stoi(host_port.substr(host_port.find(':') + 1))));
  inet_pton(AF_INET, "127.0.0.1", &a.sin_addr);
  std::string frames;
  for (int k = 0; k < 200; ++k) frames += "GET /frame.jpg" + q + " HTTP/1.1\r\nHost: x\r\n\r\n";
  std::vector<int> fds;
  for (const std::string& request : {"GET /events" + q + " HTTP/1.1\r\nHost: x\r\n\r\n", frames}) {
    const int fd = socket(AF_INET, SOCK_STREAM, 0);
    const int small = 1024;
    setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &small, sizeof small);
    if (connect(fd, reinterpret_cast<const sockaddr*>(&a), sizeof a) == 0)
      (void)!send(fd, request.data(), request.size(), MSG_NOSIGNAL);
    fds.push_back(fd);
  }
  return fds;
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
  const std::vector<int> stalled = how == Serve::stalled ? stall(url.substr(7)) : std::vector<int>{};
  const double cpu0 = process_cpu();
  const auto t0 = std::chrono::steady_clock::now();
  lua.run_file(p.string());
  Cost c;
  c.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  c.cpu = process_cpu() - cpu0;
  done = true;
  if (client.joinable()) client.join();
  c.cpu -= client_cpu;  // (what the client used after the run is subtracted too: a small overstatement)
  for (int fd : stalled) close(fd);
  std::error_code ec;
  fs::remove_all(dir, ec);
  return c;
}

void BM_Serve(benchmark::State& state) {
  double plain = 0, served = 0, watched = 0, stalled = 0, cpu_plain = 0, cpu_served = 0, cpu_watched = 0,
         cpu_stalled = 0;
  long n = 0, frames = 0;
  // a first run, not counted, and the cases' order rotated from one iteration to the next: the
  // first run of a process and the first of each three cases were the slowest (on the quiet machine the
  // plain run, always first, took 11 % more CPU than the served one after it), and each case is
  // first equally often
  long unused = 0;
  run_served(Serve::no, &unused);
  const Serve order[4] = {Serve::no, Serve::served, Serve::watched, Serve::stalled};
  for (auto _ : state) {
    for (int k = 0; k < 4; ++k) {
      const Serve how = order[(k + n) % 4];
      const Cost c = run_served(how, &frames);
      if (how == Serve::no) plain += c.wall, cpu_plain += c.cpu;
      if (how == Serve::served) served += c.wall, cpu_served += c.cpu;
      if (how == Serve::watched) watched += c.wall, cpu_watched += c.cpu;
      if (how == Serve::stalled) stalled += c.wall, cpu_stalled += c.cpu;
    }
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
  state.counters["stalled/plain"] = stalled / plain;
  state.counters["cpu_stalled/plain"] = cpu_stalled / cpu_plain;
}
BENCHMARK(BM_Serve)->Unit(benchmark::kSecond)->Iterations(4);

}  // namespace
