// The belt's pitch-line route (scene/route.cpp) against known answers: the automotive drive's
// published wraps and length, and the two-pulley drive's exact geometry.
#include <gtest/gtest.h>

#include <cmath>

#include "scene/build.hpp"
#include "scene/validate.hpp"
#include "support/presets.hpp"

namespace beltsim {
namespace {

Route route_of(const SceneDef& d) {
  const build::RouteOrder order = build::route_order(d, build::make_pulleys(d));
  return make_route(order.circles, d.belt.loop_sense, order.names);
}

// Our layout (docs/model.md, Our choices) of the paper's automotive drive gives wraps of 183°, 51°, 137° and 91°
// (crankshaft, tensioner, alternator, pump), rounded to the degree: each wrap lies within half a
// degree of its figure. Its pitch length of 1.057 m is rounded to the millimetre and is the spans'
// length plus arcs of the rounded wraps: it may differ from the route's by the rounding (0.5 mm)
// plus Σ r_k·0.5° = 0.194 m · 8.7e-3 rad = 1.7 mm, 2.2 mm in all. Each span is the common tangent,
// sqrt(d² - (s2·r2 - s1·r1)²) long (d the distance of the centres, s the senses), to rounding.
TEST(Route, AutomotiveDriveHasThePublishedWrapsAndLength) {
  const SceneDef d = presets::automotive_wet();
  const build::RouteOrder order = build::route_order(d, build::make_pulleys(d));
  const Route r = make_route(order.circles, d.belt.loop_sense, order.names);
  ASSERT_EQ(order.names, (std::vector<std::string>{"crankshaft", "tensioner", "alternator", "pump"}));
  ASSERT_EQ(r.arcs.size(), 4u);
  const double published[] = {183, 51, 137, 91};
  double sum = 0;
  for (size_t k = 0; k < 4; ++k) {
    EXPECT_NEAR(r.arcs[k].angle * 180 / M_PI, published[k], 0.5) << order.names[k];
    const RouteCircle &a = order.circles[k], &b = order.circles[(k + 1) % 4];
    const double rho = b.sense * b.radius - a.sense * a.radius;
    EXPECT_NEAR(r.spans[k].length, std::sqrt((b.centre - a.centre).squaredNorm() - rho * rho), 1e-15) << k;
    sum += r.spans[k].length + r.arcs[k].length();
  }
  EXPECT_NEAR(r.length, 1.057, 0.0022);
  EXPECT_NEAR(r.length, sum, 1e-15);
}

// Two equal pulleys: each wrap is exactly half a turn, each span is parallel to the line of
// centres and as long as the centre distance, and the loop is 2·D + 2·π·r (to rounding).
TEST(Route, TwoEqualPulleysWrapHalfATurnWithSpansOfTheCentreDistance) {
  const SceneDef d = presets::paper_dry();
  const double D = 0.29, r = 0.1;
  const Route route = route_of(d);
  ASSERT_EQ(route.spans.size(), 2u);
  for (const Route::Arc& a : route.arcs) {
    EXPECT_NEAR(a.angle, M_PI, 1e-14);
    EXPECT_NEAR(a.radius, r, 0);
    EXPECT_EQ(a.sense, -1);  // the paper's belt travels clockwise
  }
  for (const Route::Span& s : route.spans) {
    EXPECT_NEAR(s.length, D, 1e-15);
    EXPECT_NEAR(std::abs(s.from.y()), r, 1e-15);
    EXPECT_NEAR(s.from.y(), s.to.y(), 1e-15);
  }
  // clockwise from the driver at the origin: over the top to the driven pulley
  EXPECT_NEAR(route.spans[0].from.y(), r, 1e-15);
  EXPECT_GT(route.spans[0].to.x(), route.spans[0].from.x());
  EXPECT_NEAR(route.length, 2 * D + 2 * M_PI * r, 1e-14);
  // eval: a point a quarter of the way round the driven pulley's wrap lies on its pitch circle
  Vec2 p, t;
  route.eval(D + 0.5 * M_PI * r, p, t);
  EXPECT_NEAR((p - Vec2(D, 0)).norm(), r, 1e-15);
  EXPECT_NEAR(p.x(), D + r, 1e-15);
  EXPECT_NEAR(t.y(), -1, 1e-15);  // going down the driven pulley's far side
}

// Two unequal pulleys: the open belt's wrap on the larger one is π + 2·asin((R - r)/D), on the
// smaller one π - 2·asin((R - r)/D), and each span is sqrt(D² - (R - r)²) long.
TEST(Route, UnequalPulleysWrapByTheOpenBeltFormula) {
  SceneDef d = presets::paper_dry();
  const double D = 0.29, R = 0.1, r = 0.05;
  d.pulleys[1].radius = r;
  const Route route = route_of(d);
  const double beta = std::asin((R - r) / D);
  EXPECT_NEAR(route.arcs[0].angle, M_PI + 2 * beta, 1e-14);
  EXPECT_NEAR(route.arcs[1].angle, M_PI - 2 * beta, 1e-14);
  for (const Route::Span& s : route.spans) EXPECT_NEAR(s.length, std::sqrt(D * D - (R - r) * (R - r)), 1e-15);
}

// A route whose circles are too close for a tangent is refused with the names and the distance.
TEST(Route, CirclesTooCloseForASpanAreRefused) {
  const std::vector<RouteCircle> c = {{{0, 0}, 0.1, -1}, {{0.15, 0}, 0.1, 1}};
  try {
    make_route(c, -1, {"a", "b"});
    FAIL() << "no error";
  } catch (const ParameterError& e) {
    EXPECT_NE(std::string(e.what()).find("no belt span can join 'a' to 'b'"), std::string::npos) << e.what();
  }
}

// a misspelt name in belt.route is refused with the pulley it was probably meant to be
TEST(Route, AnUnknownPulleyInTheRouteGetsASuggestion) {
  SceneDef d = presets::paper_dry();
  d.belt.route = {"driver", "drivn"};
  try {
    validate(d);
    FAIL() << "an unknown pulley in the route was accepted";
  } catch (const ParameterError& e) {
    EXPECT_STREQ(e.what(), "belt.route names an unknown pulley 'drivn' (did you mean 'driven'?)");
  }
}

// a μ list of the wrong length says how many values it needs
TEST(Validate, AMuListOfTheWrongLengthSaysHowManyItNeeds) {
  SceneDef d = presets::paper_dry();
  d.belt.mu_per_element = {1, 1, 1, 1};
  try {
    validate(d);
    FAIL() << "a mu list of 4 values for " << d.belt.elements << " elements was accepted";
  } catch (const ParameterError& e) {
    EXPECT_STREQ(e.what(), ("belt.mu per element needs one value per element (" + std::to_string(d.belt.elements) +
                            ") (got 4 values)")
                               .c_str());
  }
}

}  // namespace
}  // namespace beltsim
