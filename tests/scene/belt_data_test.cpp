// Belt data as a datasheet gives it (issue 10 §1): the rigidities refer to an element's rest
// length, the tension at rest may be given as a pretension, a rest length or a strain, and the
// contact law and the bending damping may be given per length so that the physics does not change
// when the belt is divided finer.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/scene.hpp"
#include "scene/validate.hpp"
#include "support/parameter_error.hpp"
#include "support/presets.hpp"
#include "support/warning_guard.hpp"

namespace beltsim {
namespace {

// k·l0 = EA and the like, with l0 the rest length of an element (its rod): before, k = EA/l with
// l the stretched pitch, 0.33 % softer at the paper's 500 N (5 % at a 5 % mounting strain)
TEST(BeltData, RigiditiesReferToTheRestLength) {
  SceneDef d = presets::paper_dry();
  d.belt.bending_viscosity = 1e-3;
  const Scene sc = build_scene(d);
  const Belt& b = sc.model.belt;
  const double l0 = b.rigid_length;
  EXPECT_LT(l0, b.pitch);
  EXPECT_NEAR(b.k * l0 / d.belt.EA, 1, 1e-14);
  EXPECT_NEAR(b.kt * l0 / d.belt.EI, 1, 1e-14);
  EXPECT_NEAR(b.c * l0 / d.belt.axial_damping, 1, 1e-14);
  EXPECT_NEAR(b.ct * l0 / *d.belt.bending_viscosity, 1, 1e-14);
  EXPECT_NEAR(b.mass / (d.belt.mass_per_length * l0), 1, 1e-14);
}

// A belt built from the pretension, then from the rest length that gave and from the strain that
// gave, is one belt: the same tension at rest. Not to rounding: the static solves start from
// different placements and a polygon belt has a family of equilibria along its path (which
// element straddles a tangent point). Measured over 60–240 elements at 500 and 700 N, the span
// tensions differ by at most 0.40 % (60 elements, 500 N; 0.14 % at 700 N, 1e-9 at 120), so 0.5 %
// is allowed.
TEST(BeltData, PretensionRestLengthAndStrainAgree) {
  for (int n : {60, 150}) {
    SceneDef d = presets::paper_dry();
    d.belt.elements = n;
    d.belt.pretension = 700;
    const Scene a = build_scene(d);
    const double L0 = a.model.belt.rigid_length * n;

    SceneDef r = d;
    r.belt.tensioning = Tensioning::rest_length;
    r.belt.rest_length = L0;
    const Scene by_length = build_scene(r);
    EXPECT_NEAR(by_length.static_tension / 700, 1, 5e-3) << n << " elements";
    EXPECT_NEAR(by_length.model.belt.rigid_length * n / L0, 1, 1e-14);

    SceneDef e = d;
    e.belt.tensioning = Tensioning::strain;
    e.belt.strain = a.route.length / L0 - 1;
    const Scene by_strain = build_scene(e);
    EXPECT_NEAR(by_strain.static_tension / 700, 1, 5e-3) << n << " elements";
  }
}

// A larger mounting strain stretches the belt more, but not by EA·Δε: the contact on the wraps is
// a spring in series. More tension presses each element deeper (dp0/dT = 2·sin(α/2) /
// (2·c1·p0 + c2), α = l/R the angle of a pitch), which shortens the path round the wraps by
// Σθ·dp0. So dT/dε = EA / (1 + EA·Σθ·(dp0/dT)/L) with L the route's length: 0.905·EA at 500 N
// on the paper's drive. Checked within 1 %, the size of the chords' share (α²/24 of the wraps).
TEST(BeltData, TensionFollowsTheStrainThroughBeltAndContactInSeries) {
  const SceneDef paper = presets::paper_dry();
  auto build = [&](double strain) {
    SceneDef d = paper;
    d.belt.tensioning = Tensioning::strain;
    d.belt.strain = strain;
    return build_scene(d);
  };
  const Scene lo = build(0.004), mid = build(0.005), hi = build(0.006);
  const double slope = (hi.static_tension - lo.static_tension) / 0.002;
  const Contact& c = paper.contact;
  const double R = 0.1, T = mid.static_tension, alpha = mid.model.belt.pitch / R;
  const double N = 2 * T * std::sin(alpha / 2);
  const double p0 = (-c.c2 + std::sqrt(c.c2 * c.c2 + 4 * c.c1 * N)) / (2 * c.c1);
  const double dp_dT = 2 * std::sin(alpha / 2) / (2 * c.c1 * p0 + c.c2);
  const double EA = paper.belt.EA;
  const double expected = EA / (1 + EA * 2 * M_PI * dp_dT / mid.route.length);
  EXPECT_NEAR(slope / expected, 1, 0.01) << slope << " against " << expected;
  EXPECT_LT(slope, 0.95 * EA);  // the contact's share is there
}

TEST(BeltData, BadTensioningIsRefusedWithTheValue) {
  SceneDef d = presets::paper_dry();
  d.belt.tensioning = Tensioning::rest_length;
  d.belt.rest_length = 1.3;  // longer than the 1.21 m route
  try {
    build_scene(d);
    FAIL() << "a slack belt was accepted";
  } catch (const ParameterError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("belt.rest_length"), std::string::npos) << m;
    EXPECT_NE(m.find("slack"), std::string::npos) << m;
  }
  d.belt.tensioning = Tensioning::strain;
  d.belt.strain = -0.01;
  EXPECT_THROW(build_scene(d), ParameterError);
  d.belt.strain = 1.5;  // stretches an SDE by more than half a pitch
  EXPECT_THROW(build_scene(d), ParameterError);
}

// A tension at rest no belt takes (a strain of kStrainMax = 50 % or more) is refused with the way
// to change it: a rest length far too short is raised (it said "lower it" before), with the
// route's length and the strain it gives; a strain written as a percentage (0.9 for 0.9 %) is told
// that strain is a fraction; a pretension of more than half of EA is lowered.
TEST(BeltData, AStrainNoBeltTakesIsRefusedSayingWhichWay) {
  SceneDef d = presets::paper_dry();  // its route: 1.20832 m
  d.belt.tensioning = Tensioning::rest_length;
  d.belt.rest_length = 0.5;
  std::string m = test::error_of([&] { build_scene(d); });
  EXPECT_EQ(m.rfind("belt.rest_length is too short for the route: the route is 1.20832 m; 0.5 m is a strain of 142 % "
                    "(route / rest length - 1), where 50 % or more is refused: raise it towards the route's length "
                    "(1.20231 m is a strain of 0.5 %)",
                    0),
            0u)
      << m;
  EXPECT_EQ(m.find("lower it"), std::string::npos) << m;
  EXPECT_NE(m.find("(got 0.5 m)"), std::string::npos) << m;
  d.belt.rest_length = 0.75;  // 61 %: past kStrainMax, short of the half pitch
  m = test::error_of([&] { build_scene(d); });
  EXPECT_NE(m.find("0.75 m is a strain of 61.1 %"), std::string::npos) << m;

  d.belt.tensioning = Tensioning::strain;
  d.belt.strain = 0.9;  // 0.9 % meant
  m = test::error_of([&] { build_scene(d); });
  EXPECT_EQ(m, "belt.strain " + std::string(rule_text(Rule::strain)) + " (got 0.9)");
  EXPECT_NE(m.find("strain is a fraction: 0.009 = 0.9 %"), std::string::npos) << m;

  d.belt.tensioning = Tensioning::pretension;
  d.belt.pretension = 1e5;  // on EA = 1.52e5 N
  m = test::error_of([&] { build_scene(d); });
  EXPECT_EQ(m.rfind("belt.pretension is 65.8 % of the belt's EA (152000 N), a strain at rest of 65.8 %, where 50 % or "
                    "more is refused: lower it (it is in N), or give the belt's own EA",
                    0),
            0u)
      << m;
}

// A strain at rest past kStrainWarn (10 %) builds, with a warning on the run's first lines that
// names how the tension was given, its value, the strain and the tension (for a pretension, its
// share of EA); the paper's 500 N (0.33 %) gets none. Before, 90 % (131 898 N on the spans) ran
// without a word.
TEST(BeltData, AStrainPastABeltsIsWarned) {
  // the stretched belts' static start needs its trust-region retry (docs/model.md, Initial state)
  test::expect_warnings({WarningKind::static_retry});
  auto warning = [](SceneDef d) { return strain_warning(build_scene(d)); };
  SceneDef d = presets::paper_dry();
  EXPECT_EQ(warning(d), "");
  d.belt.pretension = 5e4;
  std::string w = warning(d);
  EXPECT_EQ(w.rfind("belt.pretension = 50000 N is 32.9 % of the belt's EA (152000 N): it stretches the belt ", 0), 0u)
      << w;
  EXPECT_NE(w.find("check the pretension (in N) and EA"), std::string::npos) << w;

  d = presets::paper_dry();
  d.belt.tensioning = Tensioning::strain;
  d.belt.strain = 0.3;  // 0.3 % meant
  w = warning(d);
  EXPECT_EQ(
      w.rfind("belt.strain = 0.3 stretches the belt 30 % at rest (route / rest length - 1), the spans carrying ", 0),
      0u)
      << w;
  EXPECT_NE(w.find("if 0.3 % was meant, strain is a fraction: 0.003 = 0.3 %"), std::string::npos) << w;
  d.belt.strain = 0.005;
  EXPECT_EQ(warning(d), "");

  d.belt.tensioning = Tensioning::rest_length;
  d.belt.rest_length = 1.15;  // 5.07 %: an elastic belt's
  EXPECT_EQ(warning(d), "");
  d.belt.rest_length = 1.08;
  w = warning(d);
  EXPECT_EQ(w.rfind("belt.rest_length = 1.08 m on the 1.20832 m route stretches the belt 11.9 % at rest", 0), 0u) << w;
  // among the scene's warnings, first
  const std::vector<std::string> all = scene_warnings(build_scene(d));
  ASSERT_FALSE(all.empty());
  EXPECT_EQ(all.front(), w);
}

// mean depth of the elements riding the driver, away from where the belt meets and leaves it
double wrap_penetration(const Scene& sc) {
  const Model& m = sc.model;
  const Pulley& p = m.pulleys[sc.find_pulley("driver")];
  double sum = 0;
  int count = 0;
  for (int i = 0; i < m.n_el(); ++i) {
    const Vec2 c(sc.y0[3 * i], sc.y0[3 * i + 1]);
    // the left half of the driver's wrap, 45° either side of its middle (the drive is symmetric
    // about x: the wrap spans the left half-circle)
    const Vec2 r = c - p.centre;
    if (r.x() < -std::abs(r.y())) {
      sum += p.radius - r.norm();
      count++;
    }
  }
  return sum / count;
}

// Per-length contact constants give the same contact pressure whatever the element count: the
// depth on a wrap solves c1'·p² + c2'·p = T/R (a belt of tension T on a pulley of radius R presses
// with T/R per metre), so it holds still as elements are added. With the paper's per-element
// constants each element carries half the force when the elements double, and the depth falls by
// 1.7–1.8 (c1·p² + c2·p = F: between √2 and 2). The
// 3 % tolerance covers the polygon (an element's chord carries 2T·sin(α/2) over a pitch, α = l/R,
// against T/R: 0.2 % at 60 elements) and the bending moment's end effects.
TEST(BeltData, PerLengthContactHoldsThePressureAsElementsAreAdded) {
  // the static start needs its trust-region retry at 120 and 240 elements (docs/model.md, Initial state)
  test::expect_warnings({WarningKind::static_retry});
  const SceneDef paper = presets::paper_dry();
  const double pitch60 = build_scene(paper).model.belt.pitch;
  double per_element_prev = 0;
  for (int n : {60, 120, 240}) {
    SceneDef d = paper;
    d.belt.elements = n;
    d.contact_per_length.c1 = paper.contact.c1 / pitch60;
    d.contact_per_length.c2 = paper.contact.c2 / pitch60;
    d.contact_per_length.b = paper.contact.b / pitch60;
    const Scene sc = build_scene(d);
    EXPECT_NEAR(sc.model.contact.c2 / (*d.contact_per_length.c2 * sc.model.belt.pitch), 1, 1e-14);
    const double T = sc.static_tension, R = 0.1;
    const double c1 = *d.contact_per_length.c1, c2 = *d.contact_per_length.c2;
    const double expected = (-c2 + std::sqrt(c2 * c2 + 4 * c1 * T / R)) / (2 * c1);
    EXPECT_NEAR(wrap_penetration(sc) / expected, 1, 0.03) << n << " elements";

    SceneDef e = paper;  // the paper's constants, per element
    e.belt.elements = n;
    const double per_element = wrap_penetration(build_scene(e));
    if (per_element_prev > 0) {
      EXPECT_GT(per_element_prev / per_element, 1.6) << n << " elements";
    }
    per_element_prev = per_element;
  }
}

}  // namespace
}  // namespace beltsim
