// The bending dampers' power estimated before a run (scene/bending_loss.hpp) against the power a
// run measures (the energy channel of the torsional SDE dampers, energy.dissipated_bending).
#include "scene/bending_loss.hpp"

#include <gtest/gtest.h>

#include "helpers.hpp"
#include "scene/belt_presets.hpp"
#include "support/presets.hpp"
#include "support/warning_guard.hpp"

namespace beltsim {
namespace {

// The accessory drive at 800 rpm (its ramp over by 0.05 s): the bending dampers' mean power over
// 0.1–0.15 s, the slope of their energy channel. The estimate is within 30 % of it: the study of
// docs/model.md (bending loss, scripts/bending_loss_study.lua) found estimate/measured from 0.99
// to 1.28 over ten runs of this drive (two element counts, two speeds, dampings from the preset's
// to the paper's), 1.194 with the paper's damping and 0.987 with the preset's on these very runs.
double measured_bending_power(const Scene& sc) {
  // the start from rest retries a few implicit steps (as the scripts' runs do)
  test::expect_warnings({WarningKind::failed_step});
  const auto s = testing::simulate(sc.model, sc.drive, sc.y0, 0.15, 0.05, "esdirk32", 1e-4);
  const int n = sc.model.n_coord();
  EXPECT_EQ(s.t.size(), 4u);
  const double e1 = s.y[2][2 * n + kDissSdeBending], e2 = s.y[3][2 * n + kDissSdeBending];
  return (e2 - e1) / (s.t[3] - s.t[2]);
}

TEST(BendingLossEstimate, AgreesWithTheRunWithThePapersDamping) {
  SceneDef d = presets::automotive_accessories();
  d.track_energy = true;
  const Scene sc = build_scene(d);
  const double estimate = estimate_bending_loss(sc)->dissipated, measured = measured_bending_power(sc);
  RecordProperty("estimate_over_measured", std::to_string(estimate / measured));
  EXPECT_NEAR(estimate / measured, 1, 0.3) << "estimate " << estimate << " W, measured " << measured << " W";
}

TEST(BendingLossEstimate, AgreesWithTheRunWithA6PKPreset) {
  // the preset's softer bending: the static start's retry (bending_loss_test.cpp)
  test::expect_warnings({WarningKind::static_retry});
  SceneDef d = presets::automotive_accessories();
  apply_belt_preset(*find_belt_preset("6PK"), d, [](const std::string&) { return false; });
  d.track_energy = true;
  const Scene sc = build_scene(d);
  const double estimate = estimate_bending_loss(sc)->dissipated, measured = measured_bending_power(sc);
  RecordProperty("estimate_over_measured", std::to_string(estimate / measured));
  EXPECT_NEAR(estimate / measured, 1, 0.3) << "estimate " << estimate << " W, measured " << measured << " W";
}

}  // namespace
}  // namespace beltsim
