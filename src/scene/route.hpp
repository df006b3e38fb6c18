// Belt routing: the pitch line of a closed belt around pulleys visited in order.
//
// Travelling along the belt, a pulley is wrapped clockwise or anticlockwise (sense s = -1 or +1):
// pulleys inside the loop are wrapped in the loop's own sense, back-side pulleys (idlers on the
// belt's back) in the opposite one. The span from circle 1 (c1, r1, s1) to circle 2 (c2, r2, s2)
// is the common tangent with direction u whose normal w = perp(u) satisfies
//   w·(c2 - c1) = s2·r2 - s1·r1,   and (c2 - c1)·u > 0,
// i.e. w at angle ψ + acos((s2·r2 - s1·r1)/|c2 - c1|), ψ the angle of c2 - c1; the belt leaves
// circle 1 at c1 - s1·r1·w and meets circle 2 at c2 - s2·r2·w.
#pragma once

#include <string>
#include <vector>

#include "model/model.hpp"

namespace beltsim {

struct RouteCircle {
  Vec2 centre;
  double radius;
  int sense;     // +1: the belt goes round it anticlockwise, -1: clockwise
};

struct Route {
  struct Span { Vec2 from, to; double length; };
  struct Arc { Vec2 centre; double radius; int sense; double start_angle, angle; double length() const { return radius * angle; } };
  std::vector<Span> spans;   // span k leaves circle k and arrives on circle k+1 (mod count)
  std::vector<Arc> arcs;     // arc k: on circle k, from the arrival of span k-1 to the start of span k
  double length = 0;         // total length of the closed path [m]

  // point and unit tangent (direction of travel) at arc length s from the start of span 0
  void eval(double s, Vec2& point, Vec2& tangent) const;
  // the middle of each span, in span order (where a span's tension is read: span_sde)
  std::vector<Vec2> span_middles() const {
    std::vector<Vec2> out;
    for (const Span& sp : spans) out.push_back(0.5 * (sp.from + sp.to));
    return out;
  }
};

// Throws ParameterError (scene/parameter_error.hpp) when a span has no tangent (circles too close) or the
// route does not close into a simple loop turning once in the loop's sense.
Route make_route(const std::vector<RouteCircle>& circles, int loop_sense, const std::vector<std::string>& names);

}  // namespace beltsim
