// kinematic_predict and convective_predict (Newton's starting points for an implicit stage,
// integrate/newton_aids.cpp) against the motions they are exact for. kinematic_predict: a wrap
// turning rigidly with its pulley is turned about the pulley's centre by Ω·dt (penetration, slip
// velocity and spin kept), a free element in uniform motion moves by V·dt, a pulley's angle by
// Ω·dt. convective_predict: a belt running steadily, whose state is stationary in space, with a
// slip velocity that grows linearly along each wrap (as over a slip arc): each element that travels
// half a pitch or more takes the state found where it lands. The bounds are rounding (1e-12 of the
// sizes).
#include <gtest/gtest.h>

#include <cmath>

#include "integrate/newton_aids.hpp"
#include "model/contact_law.hpp"
#include "model/forces.hpp"
#include "scene/presets.hpp"

namespace beltsim {
namespace {

TEST(KinematicPredictor, TurnsAWrapWithItsPulleyAndMovesSpansOn) {
  const Scene sc = build_scene(presets::paper_dry());
  const Model& m = sc.model;
  const Drive& dr = sc.drive;
  const int n = m.n_el(), N = m.n_coord();
  Eigen::VectorXd y = sc.y0;
  const double Omega[2] = {-60.0, -59.0}, dt = 3e-4;
  const Vec2 span_velocity(2.5, -1.0);
  std::vector<int> on(n, -1);
  for (int i = 0; i < n; ++i) {
    const Vec2 P(y[3 * i], y[3 * i + 1]);
    for (int j = 0; j < m.n_p(); ++j) {
      NormalLaw nl;
      if (normal_law(m.contact, P, Vec2::Zero(), m.pulleys[j].centre, m.pulleys[j].radius, nl) && nl.pushing) on[i] = j;
    }
    if (on[i] >= 0) {
      const Vec2 d = P - m.pulleys[on[i]].centre;
      const Vec2 V = Omega[on[i]] * Vec2(-d.y(), d.x());  // rigid rotation: Ω × d
      y[N + 3 * i] = V.x(), y[N + 3 * i + 1] = V.y(), y[N + 3 * i + 2] = Omega[on[i]];
    } else {
      y[N + 3 * i] = span_velocity.x(), y[N + 3 * i + 1] = span_velocity.y(), y[N + 3 * i + 2] = 3.0;
    }
  }
  for (int j = 0; j < m.n_p(); ++j) y[N + m.pulley_coord(j)] = Omega[j], y[m.pulley_coord(j)] = 0.4;
  int wrapped = 0, free = 0;
  for (int i = 0; i < n; ++i) (on[i] >= 0 ? wrapped : free)++;
  ASSERT_GT(wrapped, 10);
  ASSERT_GT(free, 10);

  Eigen::VectorXd z = y;
  PredictScratch w;
  kinematic_predict(m, dr, 0.5, dt, z.data(), z.data() + N, w);
  for (int i = 0; i < n; ++i) {
    const Vec2 P(y[3 * i], y[3 * i + 1]), P1(z[3 * i], z[3 * i + 1]);
    const Vec2 V(y[N + 3 * i], y[N + 3 * i + 1]), V1(z[N + 3 * i], z[N + 3 * i + 1]);
    if (on[i] < 0) {
      EXPECT_LT((P1 - (P + dt * span_velocity)).norm(), 1e-12) << "element " << i;
      EXPECT_NEAR(z[3 * i + 2], y[3 * i + 2] + 3.0 * dt, 1e-12) << "element " << i;
      EXPECT_EQ(V1, V) << "element " << i;
      continue;
    }
    const Vec2 C = m.pulleys[on[i]].centre, d = P - C;
    const double th = Omega[on[i]] * dt, c = std::cos(th), s = std::sin(th);
    const Vec2 expected = C + Vec2(c * d.x() - s * d.y(), s * d.x() + c * d.y());
    EXPECT_LT((P1 - expected).norm(), 1e-12) << "element " << i;
    EXPECT_NEAR((P1 - C).norm(), d.norm(), 1e-12) << "element " << i << ": the penetration is kept";
    EXPECT_NEAR(z[3 * i + 2], y[3 * i + 2] + th, 1e-12) << "element " << i;
    // still turning rigidly with the pulley: no slip at the new place
    const Vec2 d1 = P1 - C;
    EXPECT_LT((V1 - Omega[on[i]] * Vec2(-d1.y(), d1.x())).norm(), 1e-12) << "element " << i;
  }
  for (int j = 0; j < m.n_p(); ++j) EXPECT_NEAR(z[m.pulley_coord(j)], 0.4 + Omega[j] * dt, 1e-15);
  // velocities are not part of the motion's prediction beyond their turning: the speeds stay
  EXPECT_NEAR(z.segment(N, N).norm(), y.segment(N, N).norm(), 1e-9);
}

// The paper's belt set running steadily at V0 along its route: every element of a wrap at the
// wrap's mean radius r0, angle φ = θ + const, spin Ω = V0/r0, and a slip velocity a·(θ - θ_first)
// along the wrap on top of the rigid turning; the spans' elements moving along the span at V0.
// The state at any place is then a function of the place alone (between elements, linear in θ),
// so an element that lands between two elements of a wrap finds there exactly what a steady run
// has there.
TEST(ConvectivePredictor, GivesAnElementTheSteadyStateOfThePlaceItTravelsTo) {
  const Scene sc = build_scene(presets::paper_dry());
  const Model& m = sc.model;
  const Drive& dr = sc.drive;
  const int n = m.n_el(), N = m.n_coord();
  Eigen::VectorXd y = sc.y0;
  auto P = [&](int k) { return Vec2(y[3 * k], y[3 * k + 1]); };
  std::vector<int> on(n, -1);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m.n_p(); ++j) {
      NormalLaw nl;
      if (normal_law(m.contact, P(i), Vec2::Zero(), m.pulleys[j].centre, m.pulleys[j].radius, nl) && nl.pushing)
        on[i] = j;
    }
  const double V0 = 2.0, a = 0.05;  // belt speed [m/s], slip velocity per radian of wrap [m/s]
  const int np = m.n_p();
  std::vector<double> r0(np, 0), sense(np, 0), first(np, 0);
  std::vector<int> count(np, 0);
  for (int i = 0; i < n; ++i)
    if (on[i] >= 0) {
      const Vec2 d = P(i) - m.pulleys[on[i]].centre;
      r0[on[i]] += d.norm(), count[on[i]]++;
      // +1 when the route's order runs anticlockwise about the centre
      sense[on[i]] = d.x() * (P((i + 1) % n) - P(i)).y() - d.y() * (P((i + 1) % n) - P(i)).x() > 0 ? 1 : -1;
      if (on[(i + n - 1) % n] != on[i]) first[on[i]] = std::atan2(d.y(), d.x());
    }
  for (int j = 0; j < np; ++j) {
    ASSERT_GT(count[j], 5);
    r0[j] /= count[j];
  }
  // the angle travelled along the wrap from its first element, and the slip velocity there
  // (a wrap may exceed π: taken in [-0.5, 2π - 0.5) rad)
  auto along = [&](int j, double th) {
    const double x = sense[j] * (th - first[j]);
    return x - 2 * M_PI * std::floor((x + 0.5) / (2 * M_PI));
  };
  // each span made straight: its elements put onto the line through its two end elements, all
  // moving along it at V0
  for (int i = 0; i < n; ++i) {
    if (on[i] >= 0 || on[(i + n - 1) % n] < 0) continue;  // i: a span's first element
    int last = i;
    while (on[(last + 1) % n] < 0) last = (last + 1) % n;
    const Vec2 A = P(i), e = (P(last) - A).normalized();
    for (int k = i;; k = (k + 1) % n) {
      const Vec2 Pk = A + (P(k) - A).dot(e) * e;
      y[3 * k] = Pk.x(), y[3 * k + 1] = Pk.y();
      y[N + 3 * k] = V0 * e.x(), y[N + 3 * k + 1] = V0 * e.y(), y[N + 3 * k + 2] = 0;
      if (k == last) break;
    }
  }
  for (int i = 0; i < n; ++i) {
    const int j = on[i];
    if (j < 0) continue;
    const Vec2 C = m.pulleys[j].centre, d = P(i) - C;
    const double th = std::atan2(d.y(), d.x());
    const Vec2 e(std::cos(th), std::sin(th)), tang = sense[j] * Vec2(-e.y(), e.x());
    y[3 * i] = C.x() + r0[j] * e.x(), y[3 * i + 1] = C.y() + r0[j] * e.y();
    y[3 * i + 2] = th + sense[j] * M_PI / 2;
    const Vec2 V = (V0 + a * along(j, th)) * tang;
    y[N + 3 * i] = V.x(), y[N + 3 * i + 1] = V.y(), y[N + 3 * i + 2] = sense[j] * V0 / r0[j];
  }
  for (int j = 0; j < np; ++j) y[N + m.pulley_coord(j)] = sense[j] * V0 / m.pulleys[j].radius;
  // a stage in which every element travels about 0.7 pitches (convective_predict takes over at 0.5)
  const double pitch = m.belt.pitch, dt = 0.7 * pitch / V0;
  Eigen::VectorXd z = y;
  PredictScratch w;
  convective_predict(m, dr, 0.5, dt, z.data(), z.data() + N, w);
  int checked_wrap = 0, checked_span = 0, moved = 0;
  for (int i = 0; i < n; ++i) {
    const Vec2 V(y[N + 3 * i], y[N + 3 * i + 1]), P1(z[3 * i], z[3 * i + 1]), V1(z[N + 3 * i], z[N + 3 * i + 1]);
    const double travel = V.norm() * dt;
    ASSERT_GE(travel, 0.5 * pitch) << "element " << i;
    if ((P1 - P(i)).norm() > 0.5 * pitch) ++moved;
    const int j = on[i], next = (i + 1) % n, after = (i + 2) % n;
    if (j >= 0 && on[next] == j && on[after] == j) {  // lands inside the same wrap
      const Vec2 C = m.pulleys[j].centre, d = P(i) - C;
      const double th1 = std::atan2(d.y(), d.x()) + sense[j] * travel / r0[j];
      const Vec2 e(std::cos(th1), std::sin(th1)), tang = sense[j] * Vec2(-e.y(), e.x());
      EXPECT_LT((P1 - (C + r0[j] * e)).norm(), 1e-12) << "element " << i;
      EXPECT_LT((V1 - (V0 + a * along(j, th1)) * tang).norm(), 1e-12) << "element " << i << ": the slip found there";
      EXPECT_NEAR(wrap_angle(z[3 * i + 2] - (th1 + sense[j] * M_PI / 2)), 0, 1e-12) << "element " << i;
      EXPECT_NEAR(z[3 * i + 2], y[3 * i + 2], 0.5) << "element " << i << ": φ stays on its branch of 2π";
      EXPECT_NEAR(z[N + 3 * i + 2], sense[j] * V0 / r0[j], 1e-12) << "element " << i;
      ++checked_wrap;
    } else if (j < 0 && on[(i + n - 1) % n] < 0 && on[next] < 0 && on[after] < 0) {  // inside a straight span
      EXPECT_LT((P1 - (P(i) + dt * V)).norm(), 1e-12) << "element " << i;
      EXPECT_LT((V1 - V).norm(), 1e-12) << "element " << i;
      ++checked_span;
    }
  }
  EXPECT_GT(checked_wrap, 10);
  EXPECT_GT(checked_span, 10);
  EXPECT_EQ(moved, n);
  for (int j = 0; j < np; ++j)
    EXPECT_NEAR(z[m.pulley_coord(j)], y[m.pulley_coord(j)] + y[N + m.pulley_coord(j)] * dt, 1e-15);

  // elements that travel less than half a pitch keep the kinematic prediction, bit for bit
  Eigen::VectorXd k1 = y, k2 = y;
  kinematic_predict(m, dr, 0.5, 0.3 * pitch / V0, k1.data(), k1.data() + N, w);
  convective_predict(m, dr, 0.5, 0.3 * pitch / V0, k2.data(), k2.data() + N, w);
  EXPECT_EQ(k1, k2);
}

}  // namespace
}  // namespace beltsim
