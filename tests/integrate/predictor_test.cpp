// kinematic_predict (Newton's starting point for an implicit stage, integrate/newton_aids.cpp)
// against the motions it is exact for: a wrap turning rigidly with its pulley is turned about the
// pulley's centre by Ω·dt (penetration, slip velocity and spin kept), a free element in uniform
// motion moves by V·dt, a pulley's angle by Ω·dt. The bounds are rounding (1e-12 of the sizes).
#include <gtest/gtest.h>

#include <cmath>

#include "integrate/newton_aids.hpp"
#include "model/contact_law.hpp"
#include "scene/presets.hpp"

namespace beltsim {
namespace {

TEST(KinematicPredictor, TurnsAWrapWithItsPulleyAndMovesSpansOn) {
  const Scene sc = build_scene(presets::paper_dry());
  const Model& m = sc.model;
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
  kinematic_predict(m, 0.5, dt, z.data(), z.data() + N);
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

}  // namespace
}  // namespace beltsim
