// The accuracy matrix (docs/accuracy.md, "The accuracy contract"): every row of
// bench/accuracy_matrix.csv (a script, its --set parameters and a window of simulated time) run as
// `beltsim wp` runs it, with the default integrator at rtol 1e-2, 1e-3 and 1e-4 against esdirk32
// at rtol 1e-7 on the same samples; for each: the largest relative error of the pulley speeds and
// of the span tensions (sim/work_precision.hpp), the steps and the wall time, and whether the row
// meets the contract (rtol <= 1e-3: speeds within 3·rtol, span tensions within 10·rtol). Prints the
// table to stderr. Any row reruns with `beltsim wp SCRIPT --set ... --t-end T --integrators
// trbdf2 --rtols 1e-2,1e-3,1e-4`.
// Environment: BELTSIM_MATRIX_ROWS (names separated by commas; default every row),
// BELTSIM_MATRIX_INTEGRATOR (default the run default), BELTSIM_MATRIX_RTOLS (default 1e-2,1e-3,1e-4).
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "capture.hpp"
#include "script/interpreter.hpp"
#include "script/script_args.hpp"
#include "sim/work_precision.hpp"

namespace beltsim {
namespace {

struct Row {
  std::string name, script, sets, meaning;
  double t_end = 0;
  bool test = false;
};

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, sep);) out.push_back(item);
  return out;
}

std::vector<Row> matrix_rows() {
  std::ifstream in(BELTSIM_SOURCE_DIR "/bench/accuracy_matrix.csv");
  if (!in) throw std::runtime_error("cannot read bench/accuracy_matrix.csv");
  std::vector<Row> rows;
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    const std::vector<std::string> f = split(line, ',');
    if (f.size() < 6) continue;
    rows.push_back({f[0], f[1], f[2], f[5], std::stod(f[3]), f[4] == "1"});
  }
  return rows;
}

bool wanted(const std::string& name) {
  const char* v = std::getenv("BELTSIM_MATRIX_ROWS");
  if (!v) return true;
  for (const std::string& r : split(v, ','))
    if (r == name) return true;
  return false;
}

WpResult run_row(const Row& row, const std::string& integrator, const std::vector<double>& rtols) {
  script::Overrides o;
  o.run.t_end = row.t_end, o.give("t_end");
  o.set = script::parse_sets(split(row.sets, ' '));
  const script::Captured cap = capture_run(row.script, o);
  WpSettings wps;
  wps.integrators = {integrator};
  wps.rtols = rtols;
  wps.wall_limit = 600;
  // the matrix's reference (docs/accuracy.md): its own error, 1.6e-5 of the span tensions on the
  // paper's dry second, is under 2 % of the contract's bounds at rtol 1e-4
  wps.ref_integrator = "esdirk32";
  wps.base = cap.settings;
  wps.base.out_dir = "out/accuracy_matrix/" + row.name;
  return work_precision(*cap.scene, wps);
}

void BM_AccuracyMatrix(benchmark::State& state) {
  const char* integ = std::getenv("BELTSIM_MATRIX_INTEGRATOR");
  const std::string integrator = integ ? integ : RunSettings{}.integrator;
  const char* rt = std::getenv("BELTSIM_MATRIX_RTOLS");
  std::vector<double> rtols;
  for (const std::string& r : split(rt ? rt : "1e-2,1e-3,1e-4", ',')) rtols.push_back(std::stod(r));
  for (auto _ : state) {
    std::fprintf(stderr, "%-15s %-9s %7s %10s %10s %8s %8s  %s\n", "row", "integr.", "rtol", "err_speed", "err_tension",
                 "steps", "wall_s", "contract");
    int broken = 0;
    for (const Row& row : matrix_rows()) {
      if (!wanted(row.name)) continue;
      const WpResult r = run_row(row, integrator, rtols);
      for (const WpRow& w : r.rows) {
        const bool bound = w.rtol <= 1e-3;
        const bool holds = w.finished && w.err_speed <= 3 * w.rtol && w.err_tension <= 10 * w.rtol;
        if (bound && !holds) ++broken;
        std::fprintf(stderr, "%-15s %-9s %7.0e %10.2e %10.2e %8ld %8.2f  %s\n", row.name.c_str(), w.integrator.c_str(),
                     w.rtol, w.err_speed, w.err_tension, w.work.steps, w.wall,
                     !bound ? "-" : holds ? "holds" : "BROKEN");
      }
      std::fprintf(stderr, "%-15s reference esdirk32 at %.0e: %ld steps, %.2f s\n", row.name.c_str(), r.reference.rtol,
                   r.reference.work.steps, r.reference.wall);
    }
    state.counters["rows_breaking_the_contract"] = broken;
  }
}
BENCHMARK(BM_AccuracyMatrix)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace beltsim
