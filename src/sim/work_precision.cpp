#include "sim/work_precision.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <sstream>

#include "integrate/stepper.hpp"
#include "io/csv_writer.hpp"
#include "io/number_text.hpp"
#include "io/output_dir.hpp"
#include "io/row_file.hpp"
#include "io/suggest.hpp"
#include "sim/run_check.hpp"
#include "sim/run_error.hpp"

namespace beltsim {

namespace {

namespace fs = std::filesystem;

// an rtol as the user gave it (1e-4 reads 0.0001, as %g writes it)
std::string tol_name(double r) { return rounded_text(r, 6); }

// columns of the CSV rows that hold pulley speeds and span tensions
void channels(const Scene& sc, std::vector<int>& speed, std::vector<int>& tension) {
  const std::vector<std::string> cols = timeseries_columns(sc);
  for (size_t k = 0; k < cols.size(); ++k) {
    const std::string& c = cols[k];
    auto ends = [&](const std::string& s) { return c.size() >= s.size() && c.compare(c.size() - s.size(), s.size(), s) == 0; };
    if (ends(".omega")) speed.push_back(static_cast<int>(k));
    if (c.rfind("span_", 0) == 0 && ends(".tension")) tension.push_back(static_cast<int>(k));
  }
}

// the run's error on those columns against the reference, sample by sample (sim/run_error.hpp)
ErrorMeter meter(const std::vector<std::vector<double>>& run, const std::vector<std::vector<double>>& ref,
                 const std::vector<int>& cols) {
  ErrorMeter m(cols.size());
  std::vector<double> x(cols.size()), r(cols.size());
  for (size_t k = 0; k < std::min(run.size(), ref.size()); ++k) {
    for (size_t c = 0; c < cols.size(); ++c) x[c] = run[k][cols[c]], r[c] = ref[k][cols[c]];
    m.add(x.data(), r.data());
  }
  return m;
}

void write_csv(const WpResult& res, const std::string& path) {
  std::ostringstream f;  // the table whole, then renamed over the last one: a kill never leaves part of it
  f << "integrator,rtol,finished,t_reached_s,wall_s,steps,rejected,rhs,jacobians,factorizations,solves,"
       "err_speed,err_speed_end,err_tension,metric,err_metric,within_contract,note\n";
  const auto num = [](double v) { return number_text(v); };
  auto row = [&](const WpRow& r, bool reference) {
    f << r.integrator << ',' << num(r.rtol) << ',' << (r.finished ? 1 : 0) << ',' << num(r.t_reached) << ','
      << num(r.wall) << ','
      << r.work.steps << ',' << r.work.rejected << ',' << r.work.rhs << ',' << r.work.jacobians << ','
      << r.work.factorizations << ',' << r.work.solves << ',';
    if (r.finished)
      f << num(r.err_speed) << ',' << num(r.err_speed_end) << ',' << num(r.err_tension) << ',' << num(r.metric) << ','
        << num(r.err_metric) << ','
        << (reference            ? ""
            : within_contract(r) ? "1"
                                 : "0");
    else
      f << ",,,,,";
    f << ',' << csv_text(r.note) << '\n';
  };
  row(res.reference, true);
  for (const WpRow& r : res.rows) row(r, false);
  write_file_whole(path, f.str());
}

}  // namespace

bool within_contract(const WpRow& r) {
  return r.finished && r.err_speed <= kCheckSpeedLimit * r.rtol && r.err_tension <= kCheckTensionLimit * r.rtol;
}

std::string large_errors(const WpRow& r, const std::string& metric) {
  std::string s;
  auto check = [&](const std::string& what, double e) {
    if (!(e > kWpErrorWarning)) return;
    char b[96];
    std::snprintf(b, sizeof b, "%s%s error %.3g %%", s.empty() ? "" : ", ", what.c_str(), 100 * e);
    s += b;
  };
  check("speed", r.err_speed);
  check("tension", r.err_tension);
  if (!metric.empty()) check(metric, r.err_metric);
  return s;
}

const std::vector<std::string>& default_wp_integrators() {
  static const std::vector<std::string> names{"esdirk32", "trbdf2", "cvode"};
  return names;
}

WpResult work_precision(const Scene& sc, const WpSettings& ws, const std::atomic<bool>* stop) {
  std::vector<std::string> names = ws.integrators.empty() ? default_wp_integrators() : ws.integrators;
  for (const std::string& n : names) check_integrator(n);  // unknown names fail before anything runs
  int metric = -1;
  if (!ws.metric.empty()) {
    const std::vector<std::string> cols = timeseries_columns(sc, ws.base.probes.size());
    const auto it = std::find(cols.begin(), cols.end(), ws.metric);
    if (it == cols.end()) {
      std::string list;
      for (const std::string& c : cols) list += (list.empty() ? "" : ", ") + c;
      throw std::invalid_argument("wp: --metric: no column '" + ws.metric + "'" + did_you_mean(ws.metric, cols) +
                                  "; columns: " + list);
    }
    metric = static_cast<int>(it - cols.begin());
  }
  const OutputDir top(ws.base.out_dir);  // made, never through a link (io/output_dir.hpp)
  WpResult res;
  res.csv_path = (fs::path(ws.base.out_dir) / "wp.csv").string();

  auto one = [&](const std::string& integrator, double rtol, double limit) {
    RunSettings rs = ws.base;
    rs.integrator = integrator;
    rs.rtol = rtol;
    rs.atol = -1;
    rs.wall_limit = limit;
    rs.keep_samples = true;
    rs.frames.reset();  // the study times the integration only
    rs.keep_states = false;
    rs.check = false;         // each run is measured against the reference here,
    rs.on_warning = nullptr;  // and what it would warn of at its start (contract_miss) is what wp.csv shows
    rs.out_dir = (fs::path(ws.base.out_dir) / (integrator + "-" + tol_name(rtol))).string();
    std::fprintf(stderr, "beltsim wp: %-9s rtol %-6s ", integrator.c_str(), tol_name(rtol).c_str());
    RunResult rr;
    WpRow row;
    row.integrator = integrator;
    row.rtol = rtol;
    const auto started = std::chrono::steady_clock::now();
    try {
      rr = run(sc, rs, stop);
      row.finished = !rr.interrupted && !rr.over_wall_limit;
      if (!row.finished) row.note = rr.over_wall_limit ? "wall-time limit" : "interrupted";
    } catch (const std::exception& e) {  // divergence: recorded as unfinished
      std::fprintf(stderr, "failed: %s\n", e.what());
      row.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
      const DivergenceError* d = dynamic_cast<const DivergenceError*>(&e);
      row.t_reached = d ? d->t : 0;
      row.note = std::string("failed: ") + e.what();
      return std::make_pair(row, rr);
    }
    row.t_reached = rr.t_reached;
    row.wall = rr.wall_seconds;
    row.work = rr.work;
    std::fprintf(stderr, "%8.2f s wall, %ld steps%s\n", rr.wall_seconds, rr.work.steps,
                 row.finished ? "" : rr.over_wall_limit ? " (stopped at the wall-time limit)" : " (interrupted)");
    return std::make_pair(row, rr);
  };

  auto [ref_row, ref_run] = one(ws.ref_integrator, ws.ref_rtol, 0);
  if (!ref_row.finished) throw std::runtime_error("wp: the reference run did not finish");
  res.reference = ref_row;
  res.reference.integrator = "reference:" + ws.ref_integrator;
  res.reference.metric = metric >= 0 && !ref_run.samples.empty() ? ref_run.samples.back()[metric]
                                                                  : std::numeric_limits<double>::quiet_NaN();
  res.reference.err_metric = metric >= 0 ? 0 : std::numeric_limits<double>::quiet_NaN();
  std::vector<int> speed, tension;
  channels(sc, speed, tension);

  for (const std::string& name : names) {
    for (double rtol : ws.rtols) {
      if (stop && stop->load()) break;
      auto [row, rr] = one(name, rtol, ws.wall_limit);
      if (row.finished) {
        const ErrorMeter es = meter(rr.samples, ref_run.samples, speed);
        row.err_speed = es.error();
        row.err_speed_end = es.error_last();
        row.err_tension = meter(rr.samples, ref_run.samples, tension).error();
        const bool speeds_past = row.err_speed > kCheckSpeedLimit * rtol,
                   tensions_past = row.err_tension > kCheckTensionLimit * rtol;
        std::fprintf(
            stderr, "beltsim wp:   errors: speeds %.2g, span tensions %.2g: %s%s\n", row.err_speed, row.err_tension,
            !speeds_past && !tensions_past ? "within the contract's 3·rtol and 10·rtol"
            : speeds_past && tensions_past ? "both past the contract's 3·rtol and 10·rtol"
            : speeds_past                  ? "the speeds past the contract's 3·rtol"
                                           : "the span tensions past the contract's 10·rtol",
            rtol > kContractRtol ? " (promised at rtol 1e-3 and below)" : "");
        row.metric = row.err_metric = std::numeric_limits<double>::quiet_NaN();
        if (metric >= 0 && !rr.samples.empty() && !ref_run.samples.empty()) {
          const double m = rr.samples.back()[metric], m_ref = ref_run.samples.back()[metric];
          row.metric = m;
          row.err_metric = std::abs(m - m_ref) / (m_ref != 0 ? std::abs(m_ref) : 1.0);
        }
        if (const std::string e = large_errors(row, ws.metric); !e.empty())
          std::fprintf(stderr, "beltsim wp: warning: %s at rtol %s finished with %s (over %g %%): do not trust its answer\n",
                       name.c_str(), tol_name(rtol).c_str(), e.c_str(), 100 * kWpErrorWarning);
      }
      res.rows.push_back(row);
      write_csv(res, res.csv_path);  // after every run: an interrupted study keeps what it has
    }
  }
  write_csv(res, res.csv_path);
  // the picture is drawn by the caller (plot/wp_plot.hpp): the engine launches no process
  std::ostringstream title;
  title << "error against run time: " << sc.model.n_el() << " elements, t_end = " << ws.base.t_end
        << " s, reference " << ws.ref_integrator << " at rtol " << tol_name(ws.ref_rtol);
  res.title = title.str();
  res.integrators = names;
  res.metric = ws.metric;
  return res;
}

}  // namespace beltsim
