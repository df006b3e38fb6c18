#include "sim/work_precision.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <sstream>

#include "integrate/stepper.hpp"
#include "io/row_file.hpp"
#include "io/number_text.hpp"

namespace beltsim {

namespace {

namespace fs = std::filesystem;

std::string tol_name(double r) {
  char b[32];
  std::snprintf(b, sizeof b, "%g", r);
  return b;
}

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

// max over channels and samples of |x - x_ref| / max |x_ref| (per channel)
double rel_error(const std::vector<std::vector<double>>& run, const std::vector<std::vector<double>>& ref,
                 const std::vector<int>& cols, bool end_only) {
  const size_t n = std::min(run.size(), ref.size());
  double worst = 0;
  for (int c : cols) {
    double scale = 0;
    for (const auto& r : ref) scale = std::max(scale, std::abs(r[c]));
    if (scale == 0) scale = 1;
    for (size_t k = end_only ? n - 1 : 0; k < n; ++k) worst = std::max(worst, std::abs(run[k][c] - ref[k][c]) / scale);
  }
  return worst;
}

void write_csv(const WpResult& res, const std::string& path) {
  std::ostringstream f;  // the table whole, then renamed over the last one: a kill never leaves part of it
  f << "integrator,rtol,finished,t_reached_s,wall_s,steps,rejected,rhs,jacobians,factorizations,solves,"
       "err_speed,err_speed_end,err_tension\n";
  const auto num = [](double v) { return number_text(v); };
  auto row = [&](const WpRow& r) {
    f << r.integrator << ',' << num(r.rtol) << ',' << (r.finished ? 1 : 0) << ',' << num(r.t_reached) << ','
      << num(r.wall) << ','
      << r.work.steps << ',' << r.work.rejected << ',' << r.work.rhs << ',' << r.work.jacobians << ','
      << r.work.factorizations << ',' << r.work.solves << ',';
    if (r.finished)
      f << num(r.err_speed) << ',' << num(r.err_speed_end) << ',' << num(r.err_tension) << '\n';
    else
      f << ",,\n";
  };
  row(res.reference);
  for (const WpRow& r : res.rows) row(r);
  write_file_whole(path, f.str());
}

}  // namespace

WpResult work_precision(const Scene& sc, const WpSettings& ws, const std::atomic<bool>* stop) {
  std::vector<std::string> names = ws.integrators.empty() ? integrator_names() : ws.integrators;
  for (const std::string& n : names) check_integrator(n);  // unknown names fail before anything runs
  fs::create_directories(ws.base.out_dir);
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
    rs.out_dir = (fs::path(ws.base.out_dir) / (integrator + "-" + tol_name(rtol))).string();
    std::fprintf(stderr, "beltsim wp: %-9s rtol %-6s ", integrator.c_str(), tol_name(rtol).c_str());
    RunResult rr;
    WpRow row;
    row.integrator = integrator;
    row.rtol = rtol;
    try {
      rr = run(sc, rs, stop);
      row.finished = !rr.interrupted && !rr.over_wall_limit;
    } catch (const std::exception& e) {  // divergence: recorded as unfinished
      std::fprintf(stderr, "failed: %s\n", e.what());
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
  std::vector<int> speed, tension;
  channels(sc, speed, tension);

  for (const std::string& name : names) {
    for (double rtol : ws.rtols) {
      if (stop && stop->load()) break;
      auto [row, rr] = one(name, rtol, ws.wall_limit);
      if (row.finished) {
        row.err_speed = rel_error(rr.samples, ref_run.samples, speed, false);
        row.err_speed_end = rel_error(rr.samples, ref_run.samples, speed, true);
        row.err_tension = rel_error(rr.samples, ref_run.samples, tension, false);
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
  return res;
}

}  // namespace beltsim
