// kinematic_predict and convective_predict (Newton's starting points for an implicit stage,
// integrate/newton_aids.cpp) against the motions they are exact for. kinematic_predict: a wrap
// turning rigidly with its pulley is turned about the pulley's centre by Ω·dt (penetration, slip
// velocity and spin kept), a free element in uniform motion moves by V·dt, a pulley's angle by
// Ω·dt. convective_predict: a belt running steadily, whose state is stationary in space, with a
// slip velocity that grows linearly along each wrap (as over a slip arc): each element that travels
// half a pitch or more takes the state found where it lands. The bounds are rounding (1e-12 of the
// sizes).
#include "integrate/newton_aids.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "model/contact_law.hpp"
#include "model/contacts.hpp"
#include "model/forces.hpp"
#include "model/workspace.hpp"
#include "support/presets.hpp"

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
  ContactRecords at_y;
  fill_contacts(m, dr, 0.5, y.data(), at_y);
  kinematic_predict(m, dr, 0.5, dt, at_y.pairs(), z.data(), z.data() + N, w);
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

// A wrap turning rigidly with a pulley on a tensioner arm that swings: relative to the pulley's
// centre c and its velocity V_c = g·ψ̇ each pressing element moves as Ω × (P - c). The prediction
// turns the arm by ψ̇·dt and each element about the moving centre by Ω·dt: it keeps the element's
// radius about the centre (its penetration) and its velocity relative to the centre's motion (its
// slip velocity). A rotation about the centre as it was, with the element's absolute velocity,
// misses by V_c·dt in place and by about |V_c|/r·dt in angle.
TEST(KinematicPredictor, TurnsAWrapAboutTheMovingCentreOfATensionerArm) {
  const Scene sc = build_scene(presets::automotive_tensioner());
  const Model& m = sc.model;
  const Drive& dr = sc.drive;
  const int N = m.n_coord();
  ASSERT_EQ(m.n_arm(), 1);
  int jt = -1;
  for (int j = 0; j < m.n_p(); ++j)
    if (m.pulleys[j].arm >= 0) jt = j;
  ASSERT_GE(jt, 0);
  Eigen::VectorXd y = sc.y0;
  const int ka = m.arm_coord(m.pulleys[jt].arm);
  const double Omega = 150.0, psi_rate = 0.7, dt = 2e-5;
  y[N + ka] = psi_rate;
  y[N + m.pulley_coord(jt)] = Omega;
  const Vec2 c0 = m.centre(jt, y.data()), vc0 = m.centre_velocity(jt, y.data(), y.data() + N);
  ASSERT_GT(vc0.norm(), 0.03);  // the arm's 63 mm at 0.7 rad/s
  ContactRecords at_y;
  fill_contacts(m, dr, 0.5, y.data(), at_y);
  std::vector<int> on;
  int wrapped = 0;
  for (const ContactPair& c : at_y.pairs())
    if (c.j == jt && c.touching && c.nl.pushing) {
      const Vec2 d = Vec2(y[c.i * 3], y[c.i * 3 + 1]) - c0, V = vc0 + Omega * Vec2(-d.y(), d.x());
      y[N + 3 * c.i] = V.x(), y[N + 3 * c.i + 1] = V.y();
      on.push_back(c.i), ++wrapped;
    }
  ASSERT_GE(wrapped, 2);
  fill_contacts(m, dr, 0.5, y.data(), at_y);  // the velocities changed: the records again
  Eigen::VectorXd z = y;
  PredictScratch w;
  kinematic_predict(m, dr, 0.5, dt, at_y.pairs(), z.data(), z.data() + N, w);
  EXPECT_NEAR(z[ka], y[ka] + psi_rate * dt, 1e-15);
  const Vec2 c1 = m.centre(jt, z.data()), vc1 = m.centre_velocity(jt, z.data(), z.data() + N);
  EXPECT_GT((c1 - c0).norm(), 0.9 * vc0.norm() * dt);
  for (int i : on) {
    const Vec2 d = Vec2(y[3 * i], y[3 * i + 1]) - c0, d1 = Vec2(z[3 * i], z[3 * i + 1]) - c1;
    const double th = Omega * dt, c = std::cos(th), s = std::sin(th);
    EXPECT_LT((d1 - Vec2(c * d.x() - s * d.y(), s * d.x() + c * d.y())).norm(), 1e-12) << "element " << i;
    EXPECT_NEAR(d1.norm(), d.norm(), 1e-12) << "element " << i << ": the penetration is kept";
    EXPECT_NEAR(z[3 * i + 2], y[3 * i + 2] + th, 1e-12) << "element " << i;
    const Vec2 V1(z[N + 3 * i], z[N + 3 * i + 1]);
    EXPECT_LT((V1 - vc1 - Omega * Vec2(-d1.y(), d1.x())).norm(), 1e-12) << "element " << i << ": no slip";
  }
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
  ContactRecords at_y;
  fill_contacts(m, dr, 0.5, y.data(), at_y);
  convective_predict(m, dr, 0.5, dt, at_y.pairs(), z.data(), z.data() + N, w);
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
  kinematic_predict(m, dr, 0.5, 0.3 * pitch / V0, at_y.pairs(), k1.data(), k1.data() + N, w);
  convective_predict(m, dr, 0.5, 0.3 * pitch / V0, at_y.pairs(), k2.data(), k2.data() + N, w);
  EXPECT_EQ(k1, k2);
}

}  // namespace
}  // namespace beltsim

namespace beltsim {
namespace {

// friction_local_solve against the equations it solves (newton_aids.cpp): for every element
// pressing on a pulley, the tangential velocity change w_k (its position moving by w_k/s along
// the tangent too) and the pulley's speed change ω must zero
//   g0_k + (1 + 2λ)·w_k - λ·Σ_{neighbours j on the same pulley} (t_k·t_j)·w_j + B_k·(sat(x_k) - sat(x0_k)),
//   g0_Ω + ω - Σ_k r_k·m·B_k·(sat(x_k) - sat(x0_k))/J,
//   λ = (c + k/s)/(m·s),  B_k = μ_k·N_k/(m·s),  x = (u0 + w - r·ω)/Δv.
// with u0 = (V - V_C)·t - Ω·r the slip relative to the pulley's centre, which moves on a tensioner
// arm (the arm's angle is held). The state is the scene's static one with slip velocities spread
// across the band and beyond it, and a residual whose tangential parts push runs of elements
// either way, so the solution has sticking and slipping elements side by side in each wrap: the
// paper's dry drive at 60 and 600 elements, and the automotive drive with its idler's arm turning
// at 2 rad/s, the idler's wrap moving with it (the centre at 0.13 m/s, 13 000 band widths). That
// wrap, pushed by a tenth of its friction limit and its pulley by nothing, sticks; a slip taken
// against the fixed centre would put it on a slipping piece. Bound: rounding of the equation's
// largest term (1e-9 of it; Thomas' algorithm on a diagonally dominant chain).
TEST(FrictionLocalSolve, ZeroesTheTangentialResidualOfWholeWraps) {
  SceneDef fine = presets::paper_dry();
  fine.belt.elements = 600;
  const std::pair<SceneDef, double> cases[] = {
      {presets::paper_dry(), 0.0}, {fine, 0.0}, {presets::automotive_tensioner(), 2.0}};
  for (const auto& [def, arm_rate] : cases) {
    const Scene sc = build_scene(def);
    const Model& m = sc.model;
    const Drive& dr = sc.drive;
    const int N = m.n_coord(), n = m.n_el();
    Eigen::VectorXd y = sc.y0;
    for (int a = 0; a < m.n_arm(); ++a) y[N + m.arm_coord(a)] = arm_rate;
    const double band = m.friction.dv, s = 1 / (0.43 * 2e-4);
    // the contact records as the right-hand side leaves them (the long belt's in two halves)
    Workspace ws(m);
    fill_contacts(m, dr, 0, y.data(), ws);
    const ContactView pairs = ws.contacts.pairs();
    // slip velocities of a few band widths either way (half a band width on an arm's pulley),
    // varying along the belt, on a wrap that moves with its pulley's centre
    for (const ContactPair& c : pairs) {
      if (!c.touching || !c.nl.pushing) continue;
      const double u = (m.pulleys[c.j].arm < 0 ? 3 : 0.5) * band * std::sin(0.37 * c.i);
      const Vec2 Vc = m.centre_velocity(c.j, y.data(), y.data() + N);
      y[N + 3 * c.i] += u * c.nl.t.x() + Vc.x(), y[N + 3 * c.i + 1] += u * c.nl.t.y() + Vc.y();
    }
    fill_contacts(m, dr, 0, y.data(), ws);
    Eigen::VectorXd g = Eigen::VectorXd::Zero(N);
    // rad/s; none on an arm's pulley, whose wrap of a few elements then sticks
    for (int j = 0; j < m.n_p(); ++j) g[m.pulley_coord(j)] = m.pulleys[j].arm < 0 ? 0.3 * (j + 1) : 0.0;
    double B_max = 0;
    for (const ContactPair& c : pairs)
      if (c.touching && c.nl.pushing) {
        const double B = dr.mu[c.i] * c.nl.N / (s * m.belt.mass);
        B_max = std::max(B_max, B);
        // a tangential residual of up to 1.5 friction limits (0.1 on an arm's pulley)
        const double gt = (m.pulleys[c.j].arm < 0 ? 1.5 : 0.1) * B * std::cos(0.11 * c.i);
        g[3 * c.i] = gt * c.nl.t.x(), g[3 * c.i + 1] = gt * c.nl.t.y();
      }
    Eigen::VectorXd z = y;
    LocalSolveScratch w;
    const int moved = friction_local_solve(m, dr, pairs, s, z.data(), z.data() + N, g.data(), w);
    ASSERT_GT(moved, 10) << n << " elements";

    const double lam = (m.belt.c + m.belt.k / s) / (m.belt.mass * s);
    auto sat = [](double x) { return std::clamp(x, -1.0, 1.0); };
    std::vector<double> wk(m.n_el(), 0.0);
    std::vector<int> on(m.n_el(), -1);
    std::vector<Vec2> tang(m.n_el(), Vec2::Zero());
    for (const ContactPair& c : pairs)
      if (c.touching && c.nl.pushing && on[c.i] < 0) {
        on[c.i] = c.j, tang[c.i] = c.nl.t;
        wk[c.i] =
            (z[N + 3 * c.i] - y[N + 3 * c.i]) * c.nl.t.x() + (z[N + 3 * c.i + 1] - y[N + 3 * c.i + 1]) * c.nl.t.y();
        // the position moved with the velocity, by w/s along the tangent
        EXPECT_NEAR(z[3 * c.i] - y[3 * c.i], wk[c.i] / s * c.nl.t.x(), 1e-15);
      }
    std::vector<double> om(m.n_p()), pulley_res(m.n_p());
    for (int j = 0; j < m.n_p(); ++j) {
      const int pc = m.pulley_coord(j);
      om[j] = z[N + pc] - y[N + pc];
      EXPECT_NEAR(z[pc] - y[pc], om[j] / s, 1e-15);
      pulley_res[j] = g[pc] + om[j];
    }
    int sticking = 0, slipping = 0, arm_sticking = 0;
    for (const ContactPair& c : pairs) {
      if (!c.touching || !c.nl.pushing || on[c.i] != c.j) continue;
      const int i = c.i, nel = m.n_el();
      const Vec2 Vc = m.centre_velocity(c.j, y.data(), y.data() + N);
      const double u0 = (y.segment<2>(N + 3 * i) - Vc).dot(c.nl.t) - c.omega * c.nl.r;
      const double B = dr.mu[i] * c.nl.N / (s * m.belt.mass);
      const double dsat = sat((u0 + wk[i] - c.nl.r * om[c.j]) / band) - sat(u0 / band);
      double res = g.segment<2>(3 * i).dot(c.nl.t) + (1 + 2 * lam) * wk[i] + B * dsat;
      pulley_res[c.j] -= c.nl.r * m.belt.mass * B * dsat / dr.mass(m, m.pulley_coord(c.j));
      for (int j : {(i + nel - 1) % nel, (i + 1) % nel})
        if (on[j] == c.j && std::abs(j - i) == 1) res -= lam * tang[i].dot(tang[j]) * wk[j];
      EXPECT_LT(std::abs(res), 1e-9 * B_max * (1 + 4 * lam)) << n << " elements, element " << i;
      (std::abs(u0 + wk[i] - c.nl.r * om[c.j]) < band ? sticking : slipping)++;
      if (m.pulleys[c.j].arm >= 0 && std::abs(u0 + wk[i] - c.nl.r * om[c.j]) < band) ++arm_sticking;
    }
    for (int j = 0; j < m.n_p(); ++j) {
      if (dr.kinematic(j)) {
        EXPECT_EQ(om[j], 0.0) << "pulley " << j << " is kinematic";
      } else {
        EXPECT_NE(om[j], 0.0) << "pulley " << j << " is free: its speed takes part";
      }
      EXPECT_LT(std::abs(pulley_res[j]), 1e-9 * (1 + std::abs(g[m.pulley_coord(j)]))) << n << " elements, pulley " << j;
    }
    EXPECT_GT(sticking, 5) << n << " elements";
    EXPECT_GT(slipping, 5) << n << " elements";
    if (m.n_arm() > 0) {
      EXPECT_GT(arm_sticking, 1) << "the arm's wrap sticks to its moving pulley";
    }
  }
}

}  // namespace
}  // namespace beltsim
