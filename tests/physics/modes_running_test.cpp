// Modes of a RUNNING drive whose belt slips (sim/modes.hpp, sim/mode_check.hpp, docs/modes.md,
// "A running drive"): the paper's dry drive at 0.5 s (6.83 m/s, slip arcs on both pulleys), its
// modes checked in time, each pushed along and the drive run on.
#include <gtest/gtest.h>

#include <cstdio>

#include "physics/helpers.hpp"
#include "sim/mode_check.hpp"
#include "sim/modes.hpp"
#include "support/presets.hpp"
#include "support/warning_guard.hpp"

namespace beltsim {
namespace {

double share(const ModeAnalysis& a, const Mode& m, const std::string& prefix) {
  double s = 0;
  for (size_t g = 0; g < a.groups.size(); ++g)
    if (a.groups[g].rfind(prefix, 0) == 0) s += m.participation[g];
  return s;
}

// On the slipping drive the linearization lists 30 modes under 2 kHz, none of a kind checked at
// speed (mode_checked). Pushed (1e-8 m) and run on (six periods), the difference against the
// predicted motion over the first period (RMS), measured:
// - the two pulleys turning against each other: 102.11 Hz, ζ 0.083 in the list; in time (the
//   driver's angle) 99.29 Hz, ζ 0.116, off by 0.14: agrees;
// - the tight span (858 N) 168.58 Hz, ζ 0.221; in time 174.5 Hz, ζ 0.127 (Prony on the span's
//   middle, rippled by the element passing), off by 0.08: agrees (Wickert & Mote give 162 to 174 Hz
//   for ends at the tangent points or a pitch inside; the paper's bending damper damps it);
// - the growing modes, 53.33 Hz ζ −0.034 and 68.95 Hz ζ −0.051: off by 1.35 and 0.81; the run
//   shows 91 Hz, ζ 0.18 and 0.12: they do not exist (a run pushed by twisting the pulleys grows
//   nothing over 0.3 s either: it rings at 98.6 Hz, ζ 0.117).
// Bound: agrees at a misfit of at most 0.25 (ModeCheckSettings::max_misfit).
TEST(ModesRunning, TheSlippingDrivesModesCheckedInTime) {
  test::expect_warnings({WarningKind::failed_step});
  const Scene sc = build_scene(presets::paper_dry());
  const double t0 = 0.5;
  const auto r = testing::simulate(sc.model, sc.drive, sc.y0, t0, t0, "esdirk32", 1e-6);
  const Eigen::VectorXd& y = r.y.back();
  const ModeAnalysis a = analyze_modes(sc, sc.drive, t0, y);
  ASSERT_EQ(a.slip_arc.size(), 2u);
  EXPECT_GT(a.slip_arc[0], 0);
  EXPECT_GT(a.slip_arc[1], 0);
  size_t torsion = a.modes.size(), tight = a.modes.size();
  std::vector<size_t> growing;
  for (size_t k = 0; k < a.modes.size(); ++k) {
    const Mode& m = a.modes[k];
    EXPECT_FALSE(mode_checked(a, m)) << m.frequency << " Hz";
    if (m.damping < 0) growing.push_back(k);
    if (share(a, m, "pulley_") > 0.9 && m.damping > 0 && m.damping < 0.2 &&
        (torsion == a.modes.size() || m.damping > a.modes[torsion].damping))
      torsion = k;
    if (share(a, m, "span_driven_driver") > 0.9 && tight == a.modes.size()) tight = k;
  }
  ASSERT_LT(torsion, a.modes.size());
  ASSERT_LT(tight, a.modes.size());
  ASSERT_GE(growing.size(), 1u);
  for (size_t k : {torsion, tight}) {
    const ModeCheck c = check_mode(sc, sc.drive, t0, y, a, k);
    std::printf("mode %.2f Hz zeta %.4f: in time at %s %.2f Hz zeta %.4f, misfit %.2f\n", a.modes[k].frequency,
                a.modes[k].damping, c.where.c_str(), c.frequency, c.damping, c.misfit);
    EXPECT_TRUE(c.agrees);
  }
  for (size_t k : growing) {
    const ModeCheck c = check_mode(sc, sc.drive, t0, y, a, k);
    std::printf("growing mode %.2f Hz zeta %.4f: in time at %s %.2f Hz zeta %.4f, misfit %.2f\n", a.modes[k].frequency,
                a.modes[k].damping, c.where.c_str(), c.frequency, c.damping, c.misfit);
    EXPECT_FALSE(c.agrees);
  }
}

}  // namespace
}  // namespace beltsim
