#include "scene/route.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "io/number_text.hpp"
#include "scene/parameter_error.hpp"

namespace beltsim {

namespace {
Vec2 perp2(const Vec2& a) { return {-a.y(), a.x()}; }
double angle_of(const Vec2& a) { return std::atan2(a.y(), a.x()); }
// angle in [0, 2π)
double positive_angle(double a) {
  a = std::fmod(a, 2 * M_PI);
  return a < 0 ? a + 2 * M_PI : a;
}
}  // namespace

Route make_route(const std::vector<RouteCircle>& c, int loop_sense, const std::vector<std::string>& names) {
  const size_t m = c.size();
  Route r;
  r.spans.resize(m);
  r.arcs.resize(m);
  for (size_t k = 0; k < m; ++k) {
    const RouteCircle& a = c[k];
    const RouteCircle& b = c[(k + 1) % m];
    const Vec2 D = b.centre - a.centre;
    const double d = D.norm();
    const double rho = b.sense * b.radius - a.sense * a.radius;
    if (!(d > std::abs(rho))) {
      throw ParameterError("route", "no belt span can join '" + names[k] + "' to '" + names[(k + 1) % m] +
                                        "': their centres are " + rounded_text(d, 6) +
                                        " m apart, too close for radii " + rounded_text(a.radius, 6) + " m and " +
                                        rounded_text(b.radius, 6) + " m with these wrap sides");
    }
    const double omega = angle_of(D) + std::acos(rho / d);
    const Vec2 w(std::cos(omega), std::sin(omega));
    Route::Span& sp = r.spans[k];
    sp.from = a.centre - a.sense * a.radius * w;
    sp.to = b.centre - b.sense * b.radius * w;
    sp.length = (sp.to - sp.from).norm();
  }
  // arcs: from the arrival of span k-1 to the departure of span k, turning in the circle's sense
  double turning = 0;
  for (size_t k = 0; k < m; ++k) {
    const RouteCircle& a = c[k];
    const Vec2 in = r.spans[(k + m - 1) % m].to - a.centre;
    const Vec2 out = r.spans[k].from - a.centre;
    Route::Arc& arc = r.arcs[k];
    arc.centre = a.centre;
    arc.radius = a.radius;
    arc.sense = a.sense;
    arc.start_angle = angle_of(in);
    arc.angle = positive_angle(a.sense * (angle_of(out) - angle_of(in)));
    turning += a.sense * arc.angle;
  }
  // a simple closed loop turns exactly once, in the loop's sense
  if (std::abs(turning - loop_sense * 2 * M_PI) > 1e-6) {
    std::string around = "the belt path around";
    for (const auto& nm : names) around.append(" '").append(nm).append("'");
    throw ParameterError("route", around + " does not close into a simple loop (it turns " +
                                      rounded_text(turning * 180 / M_PI, 6) + " deg instead of " +
                                      std::to_string(loop_sense * 360) +
                                      " deg); check the order of the pulleys and which side each is wrapped on");
  }
  // the spans must not cross each other, nor cut through a pulley they do not leave or meet
  auto cross2 = [](const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); };
  auto segments_cross = [&](const Route::Span& p, const Route::Span& q) {
    const Vec2 d1 = p.to - p.from, d2 = q.to - q.from;
    const double den = cross2(d1, d2);
    if (std::abs(den) < 1e-15) return false;
    const double u = cross2(q.from - p.from, d2) / den, v = cross2(q.from - p.from, d1) / den;
    return u > 1e-9 && u < 1 - 1e-9 && v > 1e-9 && v < 1 - 1e-9;
  };
  for (size_t a = 0; a < m; ++a) {
    for (size_t b = a + 1; b < m; ++b)
      if (segments_cross(r.spans[a], r.spans[b]))
        throw ParameterError("route", "the belt would cross itself (span '" + names[a] + "' to '" + names[(a + 1) % m] +
                                          "' crosses span '" + names[b] + "' to '" + names[(b + 1) % m] +
                                          "'); check the order of the pulleys and their wrap sides");
    for (size_t k = 0; k < m; ++k) {
      if (k == a || k == (a + 1) % m) continue;
      const Route::Span& sp = r.spans[a];
      const Vec2 d = sp.to - sp.from;
      const double u = std::clamp((c[k].centre - sp.from).dot(d) / d.squaredNorm(), 0.0, 1.0);
      if ((sp.from + u * d - c[k].centre).norm() < c[k].radius)
        throw ParameterError("route", "the span from '" + names[a] + "' to '" + names[(a + 1) % m] +
                                          "' would cut through pulley '" + names[k] +
                                          "'; check the order of the pulleys and their wrap sides");
    }
  }
  r.length = 0;
  for (size_t k = 0; k < m; ++k) r.length += r.spans[k].length + r.arcs[(k + 1) % m].length();
  return r;
}

void Route::eval(double s, Vec2& point, Vec2& tangent) const {
  s = std::fmod(s, length);
  if (s < 0) s += length;
  const size_t m = spans.size();
  for (size_t k = 0;; k = (k + 1) % m) {
    const Span& sp = spans[k];
    if (s <= sp.length) {
      tangent = (sp.to - sp.from) / sp.length;
      point = sp.from + s * tangent;
      return;
    }
    s -= sp.length;
    const Arc& arc = arcs[(k + 1) % m];
    if (s <= arc.length() || k + 1 == m) {
      const double a = arc.start_angle + arc.sense * std::min(s, arc.length()) / arc.radius;
      const Vec2 n(std::cos(a), std::sin(a));
      point = arc.centre + arc.radius * n;
      tangent = arc.sense * perp2(n);
      return;
    }
    s -= arc.length();
  }
}

}  // namespace beltsim
