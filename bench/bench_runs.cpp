// Whole-run benchmarks, each measuring its comparisons side by side in one run (the machines
// are noisy, so ratios come from the same minutes):
//   Seconds/<scenario>   wall time per simulated second of the paper's dry and half-wet drives
//                        over their first BELTSIM_BENCH_T seconds (default 0.1: CVODE takes
//                        minutes for the whole second, docs/performance.md) for each integrator=rtol of
//                        BELTSIM_BENCH_RTOLS, each run's speed error against esdirk32 at rtol
//                        1e-8, and the time ratios to esdirk32; the label names CVODE's settings
//   CvodeGrid            CVODE's configurations side by side (the search for its best settings)
//   Scaling              cost per simulated second at 60, 150, 600 and 2400 elements, over a
//                        window of the running drive, and that cost per element relative to 60
//   StepLoopAllocations  heap allocations per accepted step inside the driver's loop
// Environment: BELTSIM_BENCH_RTOL (Scaling, default 1e-3), BELTSIM_BENCH_WINDOW (Scaling, 0.02 s).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "integrate/belt_system.hpp"
#include "integrate/cvode.hpp"
#include "integrate/driver.hpp"
#include "integrate/stepper.hpp"
#include "support/presets.hpp"

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
// (docs/integration.md, "CVODE"): esdirk32 at 1e-5 stays within 2.5e-4 of the reference in the
// speeds, CVODE in its best configuration (CvodeSettings: BDF order <= 2, Jacobian every 10
// steps, setup every 5) at 1e-5 within 6.4e-4, its best time at that error in BM_CvodeGrid.
// cvode-fd (coloured difference quotients, KLU) is not in the default list (each Jacobian takes
// as many right-hand sides as there are state components, docs/integration.md); add "cvode-fd=1e-5" to
// include it. Each run's own error is reported next to its time.
std::vector<std::pair<std::string, double>> bench_integrators() {
  const char* v = std::getenv("BELTSIM_BENCH_RTOLS");
  std::stringstream ss(v ? v : "esdirk32=1e-5,cvode=1e-5");
  std::vector<std::pair<std::string, double>> out;
  for (std::string item; std::getline(ss, item, ',');) {
    const size_t eq = item.find('=');
    if (eq != std::string::npos) out.emplace_back(std::string(item.begin(), item.begin() + static_cast<long>(eq)), std::atof(item.c_str() + eq + 1));
  }
  return out;
}

DriveResult simulate(const Model& m, const Drive& dr, Eigen::VectorXd& y, double t0, double t_end, const std::string& method,
                     double rtol, std::vector<Eigen::VectorXd>* samples = nullptr, const CvodeSettings& cv = {},
                     double wall_limit = 0, double atol = -1) {
  BeltSystem sys(m, dr);
  DriveOptions o;
  o.t0 = t0;
  o.t_end = t_end;
  o.sample_dt = 1e-3;
  o.events = dr.breakpoints();
  const auto keep = [&](double, const Eigen::VectorXd& yy) {
    if (samples) samples->push_back(yy);
  };
  std::atomic<bool> stop{false};
  const auto start = std::chrono::steady_clock::now();
  ProgressFn watch;
  if (wall_limit > 0) {
    o.stop = &stop;
    watch = [&](double, const WorkCounters&) {
      if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > wall_limit) stop = true;
    };
  }
  if (is_cvode(method)) return drive_cvode(sys, method, Tolerances{rtol, atol}, o, y, keep, watch, cv);
  auto st = make_stepper(method);
  return drive(sys, *st, Tolerances{rtol, atol}, o, y, keep, watch);
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
    simulate(sc.model, sc.drive, y, 0, T, "esdirk32", 1e-8, &ref);
    double base = 0;
    for (const auto& [name, rtol] : bench_integrators()) {
      std::vector<Eigen::VectorXd> samples;
      y = sc.y0;
      const DriveResult r = simulate(sc.model, sc.drive, y, 0, T, name, rtol, &samples);
      const double per_s = r.wall_seconds / T;
      if (name == "esdirk32") base = per_s;
      state.counters[name + "_wall_per_sim_s"] = per_s;
      state.counters[name + "_speed_error"] = speed_error(sc.model, samples, ref);
      state.counters[name + "_steps"] = static_cast<double>(r.work.steps);
      if (base > 0 && name != "esdirk32") state.counters[name + "_over_esdirk32"] = per_s / base;
    }
  }
  state.SetLabel("cvode: " + describe(CvodeSettings{}));
}
BENCHMARK_CAPTURE(BM_Seconds, dry, &presets::paper_dry)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(BM_Seconds, half_wet, &presets::paper_wet)->Unit(benchmark::kSecond)->Iterations(1);

// CVODE's settings: a grid of configurations of the cvode integrator (our Jacobian, KLU), each at
// each tolerance over the dry drive's first BELTSIM_GRID_T seconds (default 0.1), a run stopped
// after BELTSIM_GRID_WALL seconds of wall time (default 20) counting as unfinished; the speed
// error as `beltsim wp` measures it (largest deviation of a pulley speed over the run relative to
// its largest value) against esdirk32 at rtol 1e-8. A configuration is written as letters and
// values: o max order, c nonlinear convergence coefficient, j steps between Jacobians, s steps
// between linear-solver setups, d stability limit detection (0/1), i Newton iterations per step,
// w the stall window in steps (0: no restarts after stalls), x the stall step [s] (a restart when
// the window's steps advance less than w·x seconds), a the absolute tolerance per unit of each
// component's natural size (Tolerances::atol; left out: the rtol), k the kink gap in steps (0: no
// restarts at kinks), v the error cap as a fraction of the resolution (CvodeSettings; a letter left out
// keeps the default); "o2@1e-5" runs that configuration at
// that rtol only, "fd:o2" with cvode-fd. BELTSIM_GRID_CONFIGS (separated by
// spaces), BELTSIM_GRID_RTOLS (by commas), BELTSIM_GRID_METHOD (cvode or cvode-fd) override.
// Prints a table to stderr: configuration, rtol, wall, CPU time of the process during the run
// (std::clock: on a loaded machine the wall time includes other jobs' turns), steps, Jacobians,
// restarts at kinks, speed error.
CvodeSettings parse_settings(const std::string& spec, double* atol = nullptr) {
  CvodeSettings s;
  for (size_t k = 0; k < spec.size();) {
    const char key = spec[k++];
    size_t used = 0;
    const double v = std::stod(spec.substr(k), &used);
    k += used;
    switch (key) {
      case 'o': s.max_order = static_cast<int>(v); break;
      case 'c': s.nonlin_conv_coef = v; break;
      case 'j': s.jac_eval_frequency = static_cast<long>(v); break;
      case 's': s.lsetup_frequency = static_cast<long>(v); break;
      case 'd': s.stab_lim_det = v != 0; break;
      case 'i': s.max_nonlin_iters = static_cast<int>(v); break;
      case 'w': s.stall_window = static_cast<long>(v); break;
      case 'x': s.stall_step = v; break;
      case 'k': s.kink_gap = static_cast<long>(v); break;
      case 'v': s.resolve = v; break;
      case 'a':
        if (atol) *atol = v;
        break;
      default: throw std::invalid_argument("BELTSIM_GRID_CONFIGS: unknown key in " + spec);
    }
  }
  return s;
}

void BM_CvodeGrid(benchmark::State& state) {
  const Scene sc = build_scene(presets::paper_dry());
  const double T = env_number("BELTSIM_GRID_T", 0.1), wall = env_number("BELTSIM_GRID_WALL", 20);
  const char* cfg = std::getenv("BELTSIM_GRID_CONFIGS");
  const char* rt = std::getenv("BELTSIM_GRID_RTOLS");
  const char* me = std::getenv("BELTSIM_GRID_METHOD");
  const std::string method = me ? me : "cvode";
  std::vector<std::string> configs;
  std::stringstream cs(cfg ? cfg : "o5 o5d1 o2 o3 o2c0.01 o2c0.3 o2i5 o2j1s1 o2j10s5 o2j200s50");
  for (std::string c; cs >> c;) configs.push_back(c);
  std::vector<double> rtols;
  std::stringstream rs(rt ? rt : "1e-4,1e-5,1e-6,1e-7");
  for (std::string r; std::getline(rs, r, ',');) rtols.push_back(std::atof(r.c_str()));
  for (auto _ : state) {
    std::vector<Eigen::VectorXd> ref;
    Eigen::VectorXd y = sc.y0;
    simulate(sc.model, sc.drive, y, 0, T, "esdirk32", 1e-8, &ref);
    std::fprintf(stderr, "| %s configuration | rtol | wall for %g s [s] | CPU [s] | steps | Jacobians | kink restarts | speed error |\n",
                 method.c_str(), T);
    std::fprintf(stderr, "|---|---|---|---|---|---|---|---|\n");
    for (const std::string& spec : configs) {
      const size_t at = spec.find('@');
      const bool fd = spec.rfind("fd:", 0) == 0;
      const std::string c = spec.substr(fd ? 3 : 0, at == std::string::npos ? std::string::npos : at - (fd ? 3 : 0));
      const std::string run_method = fd ? "cvode-fd" : method;
      const std::vector<double> own = at == std::string::npos ? rtols : std::vector<double>{std::atof(spec.c_str() + at + 1)};
      for (double rtol : own) {
        std::vector<Eigen::VectorXd> samples;
        y = sc.y0;
        DriveResult r;
        std::string failure;
        const std::clock_t cpu0 = std::clock();
        try {
          double atol = -1;
          const CvodeSettings settings = parse_settings(c, &atol);
          r = simulate(sc.model, sc.drive, y, 0, T, run_method, rtol, &samples, settings, wall, atol);
        } catch (const std::exception& e) {
          failure = e.what();
        }
        const double cpu = static_cast<double>(std::clock() - cpu0) / CLOCKS_PER_SEC;
        const std::string tag = (fd ? "fd_" : "") + c + "_r" + std::to_string(static_cast<int>(std::lround(-std::log10(rtol))));
        const bool done = failure.empty() && !r.interrupted;
        const double err = done ? speed_error(sc.model, samples, ref) : -1;
        state.counters[tag + "_wall"] = done ? r.wall_seconds : -1;
        state.counters[tag + "_err"] = err;
        if (done)
          std::fprintf(stderr, "| %s | %g | %.3g | %.3g | %ld | %ld | %ld | %.2g |\n", spec.c_str(), rtol, r.wall_seconds,
                       cpu, r.work.steps, r.work.jacobians, r.work.kink_restarts, err);
        else if (failure.empty())
          std::fprintf(stderr, "| %s | %g | stopped at %g s wall, t = %.4g s | %.3g | %ld | %ld | %ld | - |\n", spec.c_str(),
                       rtol, wall, r.t_reached, cpu, r.work.steps, r.work.jacobians, r.work.kink_restarts);
        else
          std::fprintf(stderr, "| %s | %g | failed: %s | %.3g | | | | - |\n", spec.c_str(), rtol, failure.c_str(), cpu);
      }
    }
  }
}
BENCHMARK(BM_CvodeGrid)->Unit(benchmark::kSecond)->Iterations(1);

// cost per simulated second over [0.3, 0.3 + W] s of the dry drive (running at ≈ 57 rad/s, the
// ramp just ended) for 60..2400 elements; the state at 0.3 s comes from a run at rtol 1e-2. The
// window is run BELTSIM_BENCH_REPEATS times (default 5) from that state and the median wall time
// is reported: the runs take the same steps, and a 60-element window of 0.05 s is 15–20 ms of
// work, whose single runs spread by ±20 % on a shared machine. The repetitions go round the four
// lengths (60, 150, 600, 2400, 60, ...), so that a drift of the machine's speed within the run
// reaches every length alike instead of the one measured while it lasted.
// Both forms of the drive: the paper's per-element constants (BM_Scaling), or the contact and
// the bending damping given per length and equal to the paper's at 60 elements (BM_PerLengthScaling;
// scripts/refine_dry.lua's "per length", the form whose answers converge as the belt is divided).
void run_scaling(benchmark::State& state, bool per_length) {
  const double W = env_number("BELTSIM_BENCH_WINDOW", 0.02), rtol = env_number("BELTSIM_BENCH_RTOL", 1e-3);
  const int repeats = std::max(1, static_cast<int>(env_number("BELTSIM_BENCH_REPEATS", 5)));
  const int lengths[] = {60, 150, 600, 2400};
  for (auto _ : state) {
    std::vector<Scene> scenes;
    std::vector<Eigen::VectorXd> starts;
    for (int n : lengths) {
      SceneDef d = presets::paper_dry();
      if (per_length) {
        // the paper's element pitch [m]: its pitch-line route (two spans and a full turn, the radii equal) over 60
        const double pitch60 =
            (2 * (d.pulleys[1].centre - d.pulleys[0].centre).norm() + 2 * M_PI * d.pulleys[0].radius) / 60;
        d.contact_per_length.c1 = d.contact.c1 / pitch60;
        d.contact_per_length.c2 = d.contact.c2 / pitch60;
        d.contact_per_length.b = d.contact.b / pitch60;
        d.belt.bending_viscosity = d.belt.bending_damping * pitch60;
      }
      d.belt.elements = n;
      scenes.push_back(build_scene(d));
      starts.push_back(scenes.back().y0);
      simulate(scenes.back().model, scenes.back().drive, starts.back(), 0, 0.3, "esdirk32", 1e-2);
    }
    std::vector<std::vector<double>> walls(scenes.size());
    std::vector<DriveResult> results(scenes.size());
    for (int k = 0; k < repeats; ++k)
      for (size_t c = 0; c < scenes.size(); ++c) {
        Eigen::VectorXd y = starts[c];
        results[c] = simulate(scenes[c].model, scenes[c].drive, y, 0.3, 0.3 + W, "esdirk32", rtol);
        walls[c].push_back(results[c].wall_seconds);
      }
    double base = 0;
    for (size_t c = 0; c < scenes.size(); ++c) {
      const int n = lengths[c];
      const DriveResult& r = results[c];
      std::sort(walls[c].begin(), walls[c].end());
      const double per_s = walls[c][walls[c].size() / 2] / W;
      std::string tag = std::to_string(n);
      tag.insert(tag.begin(), 'n');
      state.counters[tag + "_wall_per_sim_s"] = per_s;
      state.counters[tag + "_steps_per_sim_s"] = static_cast<double>(r.work.steps) / W;
      state.counters[tag + "_jacobians_per_step"] =
          static_cast<double>(r.work.jacobians) / static_cast<double>(r.work.steps + r.work.rejected);
      state.counters[tag + "_rejected_per_sim_s"] = static_cast<double>(r.work.rejected) / W;
      state.counters[tag + "_failed_per_sim_s"] =
          static_cast<double>(r.work.warnings[WarningKind::failed_step].count) / W;
      if (n == 60) base = per_s;
      state.counters[tag + "_cost_vs_n60"] = per_s / base;  // targets: <= 10 at 600 elements, <= 40 at 2 400 (docs/performance.md)
      state.counters[tag + "_cost_per_element_vs_n60"] = (per_s / n) / (base / 60);
    }
  }
}
void BM_Scaling(benchmark::State& state) { run_scaling(state, false); }
BENCHMARK(BM_Scaling)->Unit(benchmark::kSecond)->Iterations(1);
void BM_PerLengthScaling(benchmark::State& state) { run_scaling(state, true); }
BENCHMARK(BM_PerLengthScaling)->Unit(benchmark::kSecond)->Iterations(1);

// allocations inside the step loop: two runs from the same running state that differ only in
// length; the difference in allocations over the difference in steps (set-up cancels)
void BM_StepLoopAllocations(benchmark::State& state) {
  const Scene sc = build_scene(presets::paper_dry());
  Eigen::VectorXd y0 = sc.y0;
  simulate(sc.model, sc.drive, y0, 0, 0.3, "esdirk32", 1e-2);
  for (auto _ : state) {
    long steps[2], allocs[2];
    int k = 0;
    for (double W : {0.005, 0.015}) {
      Eigen::VectorXd y = y0;
      BeltSystem sys(sc.model, sc.drive);
      auto st = make_stepper("esdirk32");
      DriveOptions o;
      o.t0 = 0.3;
      o.t_end = 0.3 + W;
      o.sample_dt = 1e-3;
      o.events = sc.drive.breakpoints();
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
