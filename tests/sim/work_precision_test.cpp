// `beltsim wp`: the study runs every integrator and tolerance against one reference, records
// the work, and its errors shrink as the tolerance tightens; a run over its wall-time limit is
// recorded as unfinished; the CSV and the PNG are written.
#include "sim/work_precision.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "plot/wp_plot.hpp"
#include "support/presets.hpp"
#include "support/scratch.hpp"
#include "support/warning_guard.hpp"

namespace beltsim {
namespace {

namespace fs = std::filesystem;

fs::path out_dir(const char* name) {
  return beltsim::test::scratch_dir("beltsim_wp_test") / name;
}

// The first 0.1 s of the dry drive. esdirk32 is third order, so a hundredfold tighter tolerance
// must cut the error by far more than 2x (measured: 1e-2 → 1e-4 cuts the speed error 10x); the
// bound 2x leaves room for the error control's irregularity.
TEST(WorkPrecision, ErrorsShrinkWithTheToleranceAndFilesAreWritten) {
  // the paper's dry drive has failed implicit steps (esdirk32 from 0.036 s; loose tolerances sooner)
  // and CVODE convergence failures
  test::expect_warnings({WarningKind::failed_step, WarningKind::cvode_convergence});
  const Scene sc = build_scene(presets::paper_dry());
  WpSettings ws;
  ws.integrators = {"esdirk32", "trbdf2"};
  ws.rtols = {1e-2, 1e-4};
  ws.ref_rtol = 1e-7;
  ws.base.t_end = 0.1;
  ws.base.out_dir = out_dir("study").string();
  const WpResult r = work_precision(sc, ws);
  ASSERT_EQ(r.rows.size(), 4u);
  EXPECT_TRUE(r.reference.finished);
  for (const WpRow& row : r.rows) {
    EXPECT_TRUE(row.finished) << row.integrator << " " << row.rtol;
    EXPECT_GT(row.work.steps, 0);
    EXPECT_GT(row.work.jacobians, 0);
    EXPECT_GT(row.err_speed, 0);    // not the reference itself
    EXPECT_LT(row.err_speed, 0.5);  // a run that went wrong is off by the order of the speed itself
  }
  EXPECT_LT(2 * r.rows[1].err_speed, r.rows[0].err_speed);  // esdirk32 1e-4 against 1e-2
  EXPECT_LT(2 * r.rows[3].err_speed, r.rows[2].err_speed);  // trbdf2
  // the CSV: a header and one line per run plus the reference
  std::ifstream csv(r.csv_path);
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line.rfind("integrator,rtol,finished,t_reached_s,wall_s,steps,rejected,rhs,jacobians", 0), 0u);
  EXPECT_NE(line.find(",within_contract,note"), std::string::npos) << line;
  int lines = 0;
  while (std::getline(csv, line)) {
    // each run's within_contract (the second column from the end, before an empty note) is the row's
    if (lines > 0) {
      const WpRow& row = r.rows[lines - 1];
      EXPECT_EQ(line.substr(line.size() - 3), within_contract(row) ? ",1," : ",0,") << line;
    } else {
      EXPECT_EQ(line.substr(line.size() - 2), ",,") << line;  // the reference: its own errors, 0
    }
    ++lines;
  }
  EXPECT_EQ(lines, 5);
  // the plot (drawn by beltsim_plot from the result, as `beltsim wp` does) is a PNG
  EXPECT_EQ(r.integrators, ws.integrators);
  const std::string png_path = (fs::path(ws.base.out_dir) / "wp.png").string();
  plot::plot_wp_png(r, png_path);
  std::ifstream png(png_path, std::ios::binary);
  char magic[8] = {};
  png.read(magic, 8);
  EXPECT_EQ(std::string(magic + 1, 3), "PNG");
}

// the contract's bounds (docs/accuracy.md): speeds within 3·rtol and span tensions within 10·rtol,
// both; an unfinished run keeps nothing
TEST(WorkPrecision, WithinContractTakesBothBounds) {
  WpRow r;
  r.finished = true, r.rtol = 1e-3, r.err_speed = 3e-3, r.err_tension = 1e-2;
  EXPECT_TRUE(within_contract(r));
  r.err_speed = 3.1e-3;
  EXPECT_FALSE(within_contract(r));
  r.err_speed = 1e-4, r.err_tension = 1.1e-2;
  EXPECT_FALSE(within_contract(r));
  r.err_tension = 1e-4, r.finished = false;
  EXPECT_FALSE(within_contract(r));
}

// The runs' clock is the test's (RunSettings::wall_clock): 1 ms per look, so that the 0.2 s limit
// stops the rkf45 run at its 201st look whatever the machine's speed, and the reference (no
// limit) finishes
TEST(WorkPrecision, ARunOverItsWallLimitIsUnfinished) {
  const Scene sc = build_scene(presets::paper_dry());
  WpSettings ws;
  ws.integrators = {"rkf45"};
  ws.rtols = {1e-3};
  ws.ref_rtol = 1e-5;
  ws.wall_limit = 0.2;
  ws.base.t_end = 0.02;
  ws.base.out_dir = out_dir("limit").string();
  long looks = 0;
  ws.base.wall_clock = [&] { return 1e-3 * static_cast<double>(looks++); };
  const WpResult r = work_precision(sc, ws);
  ASSERT_EQ(r.rows.size(), 1u);
  EXPECT_TRUE(r.reference.finished);
  EXPECT_FALSE(r.rows[0].finished);
  EXPECT_GT(r.rows[0].t_reached, 0.0);
  EXPECT_LT(r.rows[0].t_reached, 0.02);
  // stopped at the look past the limit (0.201 s), with one more look for the total
  EXPECT_GT(r.rows[0].wall, 0.2);
  EXPECT_LE(r.rows[0].wall, 0.2025);
  EXPECT_EQ(r.rows[0].note, "wall-time limit");
}

// --metric: a column's relative error at t_end, in wp.csv; an unknown column fails before any run
TEST(WorkPrecision, AMetricIsComparedAtTheEnd) {
  test::expect_warnings({WarningKind::failed_step});
  const Scene sc = build_scene(presets::paper_dry());
  WpSettings ws;
  ws.integrators = {"esdirk32"};
  ws.rtols = {1e-2, 1e-4};
  ws.ref_rtol = 1e-6;
  ws.base.t_end = 0.05;
  ws.base.out_dir = out_dir("metric").string();
  fs::remove_all(ws.base.out_dir);
  ws.metric = "drivn.omega";
  try {
    work_precision(sc, ws);
    ADD_FAILURE() << "an unknown metric column was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("no column 'drivn.omega' (did you mean 'driven.omega'?)"), std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(fs::exists(fs::path(ws.base.out_dir) / "wp.csv"));  // nothing ran
  ws.metric = "driven.omega";
  const WpResult r = work_precision(sc, ws);
  EXPECT_EQ(r.metric, "driven.omega");
  ASSERT_EQ(r.rows.size(), 2u);
  ASSERT_NE(r.reference.metric, 0);
  for (const WpRow& row : r.rows) {
    ASSERT_TRUE(row.finished);
    EXPECT_DOUBLE_EQ(row.err_metric, std::abs(row.metric - r.reference.metric) / std::abs(r.reference.metric));
    EXPECT_GT(row.err_metric, 0);
    // one speed at the end: within the largest end error of the speeds, relative to the run's
    // largest speed (0.05 s into a ramp: the end speed is the largest)
    EXPECT_LE(row.err_metric, row.err_speed_end * 1.000001);
  }
  std::ifstream csv(r.csv_path);
  std::string header;
  std::getline(csv, header);
  EXPECT_NE(header.find(",err_tension,metric,err_metric,within_contract,note"), std::string::npos) << header;
}

// a finished run whose error passes 10 % is named with the errors that do
TEST(WorkPrecision, LargeErrorsAreNamed) {
  WpRow row;
  row.finished = true;
  row.err_speed = 0.05, row.err_tension = 0.099, row.err_metric = 0.5;
  EXPECT_EQ(large_errors(row, ""), "");
  EXPECT_EQ(large_errors(row, "driven.creep"), "driven.creep error 50 %");
  row.err_speed = 0.132;
  EXPECT_EQ(large_errors(row, ""), "speed error 13.2 %");
}

}  // namespace
}  // namespace beltsim
