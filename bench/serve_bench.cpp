// The live view's cost (docs/live-view.md), side by side in one run, each case a fresh interpreter
// running the same batch run (the paper's dry drive, 60 elements; trbdf2 at rtol 1e-4, no frames
// to files), the cases run in rounds: each case once a round, in an order rotated from one round to
// the next:
//   plain       no --serve
//   again       no --serve, the plain run again: the ratio of two identical runs, what the machine
//               resolves
//   served      --serve, no page open: the samples published at 20 a wall second, nothing drawn
//   watched     --serve and one client reading the stream and asking for the picture as a page
//               does (the next when one has arrived, 66 ms later): frames drawn at up to 15/s
//   stalled     --serve and a page that stopped reading: the stream and 200 picture requests asked
//               for on sockets with the smallest receive buffer, never read
// The server is started, and has answered a request, before a run's clock starts: its start (about
// 2 ms of CPU once, whatever the run's length) is reported apart (start_cpu_ms, the last case's).
// BM_ServeIdle: plain, again, served; 0.3 s simulated (about 0.3 s of CPU, of which the script's
// set-up, the same in each case, takes 30 ms), 100 rounds: one run's CPU time differs from the next
// one's by some 4 % on a shared machine, whatever the run's length, and many short rounds narrow
// the median's interval most for the CPU spent.
// BM_Serve: plain, watched, stalled; 2 s simulated (the renderer's start, about 0.1 s of CPU once
// per run, weighs as little as in the long runs a page watches), 4 rounds.
// Counters: the plain run's median wall and CPU seconds; for each other case the median over the
// rounds of its wall time over the plain run's of the same round (served/plain, ...), and of its CPU
// time (cpu_served/plain: every thread of the process but the client's own, the frame thread,
// Mesa's rasteriser threads and the server's included), with that median's 95 % confidence
// interval (cpu_served/plain_lo95, _hi95). That CPU time split: the thread that runs the script
// against the plain run's (run_served/plain), and every other thread's over the plain run's CPU
// (view_served/plain, with _hi95): the live view's own work, which the machine's load moves far
// less than the 4-7 % by which one run's CPU differs from the next one's. On a busy 2-core machine
// each CPU second of the live view is taken from the run, and wall time is mostly the other users'
// load.
#include <arpa/inet.h>
#include <benchmark/benchmark.h>
#include <httplib.h>
#include <netinet/in.h>
#include <sys/resource.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "script/interpreter.hpp"
#include "support/scenes.hpp"

namespace {

namespace fs = std::filesystem;

// the paper's drive at 60 elements (the tests' scene, tests/support/two_pulley.lua); each case
// appends its own run
const std::string kServeScene = [] {
  beltsim::test::TwoPulley p;
  p.elements = 60;
  return beltsim::test::two_pulley(p);
}();

enum class Serve { no, again, served, watched, stalled };

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
  double wall = 0, cpu = 0;  // [s] the run's
  double run_cpu = 0;        // [s] of CPU: the thread that runs the script alone (the run's own)
  double start = 0;          // [s] of CPU: the server's start (served cases)
};

Cost run_served(Serve how, double t_end, long* frames) {
  const fs::path dir = fs::temp_directory_path() / ("beltsim_serve_bench_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const fs::path p = dir / "serve.lua";
  std::ofstream(p) << kServeScene << "s:run{ t_end = " << t_end << ", progress = false }\n";
  beltsim::script::Interpreter lua;
  beltsim::script::Overrides o;
  o.run.out_dir = (dir / "out").string(), o.give("out");
  lua.set_overrides(o);
  std::string url;
  Cost c;
  if (how == Serve::served || how == Serve::watched || how == Serve::stalled) {
    // the server started and answering (cpp-httplib's workers made) before the run's clock starts:
    // its start, once per run whatever the run's length, is reported apart
    const double cpu = process_cpu();
    url = lua.serve(0);
    httplib::Client(url.substr(7, url.find("/?token=") - 7)).Get("/");  // 403: no token, no client
    c.start = process_cpu() - cpu;
  }
  std::atomic<bool> done{false};
  std::atomic<double> client_cpu{0};
  std::thread client;
  if (how == Serve::watched) client = std::thread([&] { watch(url.substr(7), done, frames, &client_cpu); });
  const std::vector<int> stalled = how == Serve::stalled ? stall(url.substr(7)) : std::vector<int>{};
  const double cpu0 = process_cpu(), run0 = thread_cpu();
  const auto t0 = std::chrono::steady_clock::now();
  lua.run_file(p.string());
  c.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  c.run_cpu = thread_cpu() - run0;
  c.cpu = process_cpu() - cpu0;
  done = true;
  if (client.joinable()) client.join();
  c.cpu -= client_cpu;  // (what the client used after the run is subtracted too: a small overstatement)
  for (int fd : stalled) close(fd);
  std::error_code ec;
  fs::remove_all(dir, ec);
  return c;
}

// the median of x and the 95 % confidence interval of it (distribution-free: the order statistics
// of ranks n/2 -+ 0.98 sqrt(n), the normal approximation of the binomial; [min, max] for a few)
struct Median {
  double mid = 0, lo = 0, hi = 0;
};
Median median(std::vector<double> x) {
  std::sort(x.begin(), x.end());
  const size_t n = x.size();
  const double half = 0.98 * std::sqrt(static_cast<double>(n));
  Median m;
  m.mid = n % 2 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
  m.lo = x[static_cast<size_t>(std::max(0.0, std::floor(0.5 * n - half) - 1))];
  m.hi = x[std::min(n - 1, static_cast<size_t>(std::ceil(0.5 * n + 1 + half) - 1))];
  return m;
}

// state.range(0): the runs' simulated time [ms]; the cases compared with the plain run
void serve_rounds(benchmark::State& state, const std::vector<std::pair<Serve, const char*>>& cases) {
  const double t_end = 1e-3 * static_cast<double>(state.range(0));
  const size_t n = cases.size();
  std::vector<std::vector<Cost>> runs(n);  // runs[case][round]
  long frames = 0, unused = 0;
  double watched_wall = 0;
  // a first run, not counted, and the cases' order rotated from one round to the next: the first
  // run of a process and the first of each round were the slowest (on the quiet machine the plain
  // run, always first, took 11 % more CPU than the served one after it), and each case is first
  // equally often
  run_served(Serve::no, t_end, &unused);
  long round = 0;
  for (auto _ : state) {
    for (size_t k = 0; k < n; ++k) {
      const size_t i = (k + static_cast<size_t>(round)) % n;
      const Cost c = run_served(cases[i].first, t_end, &frames);
      runs[i].push_back(c);
      if (cases[i].first == Serve::watched) watched_wall += c.wall;
    }
    round++;
  }
  // each case against the plain run of the same round: the median of those ratios and its 95 %
  // confidence interval, which says what this machine resolves now
  const auto of = [&](size_t i, double Cost::*m) {
    std::vector<double> x;
    for (const Cost& c : runs[i]) x.push_back(c.*m);
    return median(x).mid;
  };
  state.counters["plain_s"] = of(0, &Cost::wall);
  state.counters["cpu_plain_s"] = of(0, &Cost::cpu);
  state.counters["start_cpu_ms"] = 1e3 * of(n - 1, &Cost::start);
  for (size_t i = 1; i < n; ++i) {
    std::vector<double> wall, cpu, view, own;
    for (size_t r = 0; r < runs[i].size(); ++r) {
      wall.push_back(runs[i][r].wall / runs[0][r].wall);
      cpu.push_back(runs[i][r].cpu / runs[0][r].cpu);
      view.push_back((runs[i][r].cpu - runs[i][r].run_cpu) / runs[0][r].cpu);
      own.push_back(runs[i][r].run_cpu / runs[0][r].run_cpu);
    }
    const std::string name = cases[i].second;
    const Median c = median(cpu), v = median(view);
    state.counters[name + "/plain"] = median(wall).mid;
    // the CPU of every thread but the run's (server, frame thread, Mesa's) over the plain run's:
    // the live view's own work, apart from the run's, which the machine's load moves by 4-7 %
    state.counters["view_" + name + "/plain"] = v.mid;
    state.counters["view_" + name + "/plain_hi95"] = v.hi;
    state.counters["run_" + name + "/plain"] = median(own).mid;  // the run's thread against the plain run's
    state.counters["cpu_" + name + "/plain"] = c.mid;
    state.counters["cpu_" + name + "/plain_lo95"] = c.lo;
    state.counters["cpu_" + name + "/plain_hi95"] = c.hi;
  }
  if (watched_wall > 0) state.counters["frames_per_s"] = static_cast<double>(frames) / watched_wall;
}

// with no page open: the served run against the plain one, and the plain run again (what the
// ratio of two identical runs shows: the resolution), short runs in many rounds (see the top)
void BM_ServeIdle(benchmark::State& state) {
  serve_rounds(state, {{Serve::no, "plain"}, {Serve::again, "again"}, {Serve::served, "served"}});
}
BENCHMARK(BM_ServeIdle)->Unit(benchmark::kSecond)->Arg(300)->Iterations(100);

// a page open: long runs (the renderer's start, once per run, weighs as in the long runs a page
// watches)
void BM_Serve(benchmark::State& state) {
  serve_rounds(state, {{Serve::no, "plain"}, {Serve::watched, "watched"}, {Serve::stalled, "stalled"}});
}
BENCHMARK(BM_Serve)->Unit(benchmark::kSecond)->Arg(2000)->Iterations(4);

}  // namespace
