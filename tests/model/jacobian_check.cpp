// The checks and states the Jacobian tests share (jacobian_check.hpp).
#include "model/jacobian_check.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "model/contact_law.hpp"
#include "model/forces.hpp"
#include "model/rhs.hpp"

namespace beltsim::test {


// distance of the state from the nearest kink of the contact and friction laws
double kink_margin(const Model& m, const Drive& dr, double t, const Eigen::VectorXd& y) {
  const int N = m.n_coord();
  double margin = 1e300;
  for (int j = 0; j < m.n_p(); ++j)
    for (int i = 0; i < m.n_el(); ++i) {
      // relative to the pulley's centre, which moves on a tensioner arm
      const Vec2 centre = m.centre(j, y.data());
      const Vec2 P(y[3 * i], y[3 * i + 1]);
      const Vec2 V = Vec2(y[N + 3 * i], y[N + 3 * i + 1]) - m.centre_velocity(j, y.data(), y.data() + N);
      const Vec2 rv = P - centre;
      const double p = m.pulleys[j].radius - rv.norm();
      margin = std::min(margin, std::abs(p) / 1e-6);                       // contact onset
      if (p <= 0) continue;
      margin = std::min(margin, std::abs(p - m.contact.p_max) / 1e-6);     // full damping
      NormalLaw nl;
      normal_law(m.contact, P, V, centre, m.pulleys[j].radius, nl);
      const double raw = nl.N_el + nl.delta * m.contact.b * nl.pdot;
      margin = std::min(margin, std::abs(raw) / 1e-2);                     // N = 0
      const FrictionLaw fl = friction_law(dr.mu[i], m.friction.dv, nl, V, dr.omega(m, j, t, y.data() + N));
      margin = std::min(margin, std::abs(std::abs(fl.vT) - m.friction.dv) / 1e-7);  // stick/slip
    }
  return margin;
}

Coverage coverage(const Model& m, const Drive& dr, double t, const Eigen::VectorXd& y) {
  const int N = m.n_coord();
  Coverage c;
  for (int i = 0; i < m.n_el(); ++i) {
    bool touching = false;
    for (int j = 0; j < m.n_p(); ++j) {
      const Vec2 P(y[3 * i], y[3 * i + 1]);
      const Vec2 V = Vec2(y[N + 3 * i], y[N + 3 * i + 1]) - m.centre_velocity(j, y.data(), y.data() + N);
      NormalLaw nl;
      if (!normal_law(m.contact, P, V, m.centre(j, y.data()), m.pulleys[j].radius, nl)) continue;
      touching = true;
      (nl.p < m.contact.p_max ? c.ramp : c.deep)++;
      if (!nl.pushing) {
        c.clamped++;
        continue;
      }
      const FrictionLaw fl = friction_law(dr.mu[i], m.friction.dv, nl, V, dr.omega(m, j, t, y.data() + N));
      (std::abs(fl.vT) < m.friction.dv ? c.stick : c.slip)++;
    }
    if (!touching) c.free++;
  }
  return c;
}

// max over columns of (max |analytic - fd| / max |analytic|) for one matrix; a column's scale is
// at least `floor`
double column_error(const Eigen::MatrixXd& an, const Eigen::MatrixXd& fd, int* worst_col, double floor) {
  double worst = 0;
  for (int c = 0; c < an.cols(); ++c) {
    const double scale =
        std::max({an.col(c).cwiseAbs().maxCoeff(), fd.col(c).cwiseAbs().maxCoeff(), floor});
    if (scale == 0) continue;
    const double e = (an.col(c) - fd.col(c)).cwiseAbs().maxCoeff() / scale;
    if (e > worst) worst = e, *worst_col = c;
  }
  return worst;
}

void expect_jacobian_matches(const Model& m, const Drive& dr, double t, const Eigen::VectorXd& y) {
  ASSERT_GT(kink_margin(m, dr, t, y), 10.0) << "test state too close to a kink of the force laws";
  const int N = m.n_coord();
  Jacobian J;
  J.resize(m);
  jacobian(m, dr, t, y.data(), J);
  Eigen::MatrixXd Kfd(N, N), Cfd(N, N);
  Eigen::VectorXd fp(N), fm(N);
  for (int k = 0; k < 2 * N; ++k) {
    const bool vel = k >= N;
    // element spin enters only the (linear) SDE dampers: a large step avoids rounding
    const bool spin = vel && k - N < 3 * m.n_el() && (k - N) % 3 == 2;
    const double eps = spin ? 1e-4 : vel ? 1e-7 : 1e-8;
    Eigen::VectorXd yp = y, ym = y;
    yp[k] += eps;
    ym[k] -= eps;
    forces(m, dr, t, yp.data(), fp.data());
    forces(m, dr, t, ym.data(), fm.data());
    (vel ? Cfd.col(k - N) : Kfd.col(k)) = (fp - fm) / (2 * eps);
  }
  // kinematic pulleys: their state speed feeds nothing (the prescribed one is used)
  int col = -1;
  const double eK = column_error(J.K.to_dense(), Kfd, &col);
  EXPECT_LT(eK, 1e-6) << "dF/dq column " << col;
  const double eC = column_error(J.C.to_dense(), Cfd, &col);
  EXPECT_LT(eC, 1e-6) << "dF/dv column " << col;
  // ∂f/∂t
  const double dt = 1e-7;
  forces(m, dr, t + dt, y.data(), fp.data());
  forces(m, dr, t - dt, y.data(), fm.data());
  const Eigen::VectorXd ftfd = (fp - fm) / (2 * dt);
  const double scale = std::max(1.0, ftfd.cwiseAbs().maxCoeff());
  EXPECT_LT((J.f_t - ftfd).cwiseAbs().maxCoeff() / scale, 1e-6);
}

// A running state: pulleys turning, each element in contact given a chosen slip, a few elements
// pushed deep or pulled out fast, random velocities on the free spans; tensioner arms turning at
// arm_rate (slips and rates are relative to the moving centre).
Eigen::VectorXd running_state(const Scene& sc, double time, double omega_scale, unsigned seed, double arm_rate) {
  const Model& m = sc.model;
  const Drive& dr = sc.drive;
  const int N = m.n_coord();
  Eigen::VectorXd y = sc.y0;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int j = 0; j < m.n_p(); ++j) {
    const Pulley& p = m.pulleys[j];
    if (!dr.kinematic(j)) y[N + m.pulley_coord(j)] = omega_scale * 0.1 / p.radius * (1 + 0.01 * u(rng));
  }
  for (int a = 0; a < m.n_arm(); ++a) y[N + m.arm_coord(a)] = arm_rate;
  // slips chosen away from ±Δv: stick, stick, slip, slip
  const double slips[] = {3e-6, -6e-6, 4e-4, -2e-3};
  for (int i = 0; i < m.n_el(); ++i) {
    int touching = -1;
    for (int j = 0; j < m.n_p(); ++j)
      if ((Vec2(y[3 * i], y[3 * i + 1]) - m.centre(j, y.data())).norm() < m.pulleys[j].radius) touching = j;
    y[N + 3 * i + 2] = 5.0 * u(rng);
    if (touching < 0) {
      y[N + 3 * i] = 3.0 * u(rng);
      y[N + 3 * i + 1] = 3.0 * u(rng);
      continue;
    }
    const Pulley& p = m.pulleys[touching];
    const Vec2 centre = m.centre(touching, y.data());
    const Vec2 rv = Vec2(y[3 * i], y[3 * i + 1]) - centre;
    const Vec2 n = rv.normalized(), t = perp(n);
    const double omega = dr.omega(m, touching, time, y.data() + N);
    Vec2 V = omega * rv.norm() * t + slips[i % 4] * t + 1e-3 * u(rng) * n;  // small normal rate
    if (i % 7 == 3) {                                // deeper than p_max
      const Vec2 P = centre + (p.radius - 1.6e-3) * n;
      y[3 * i] = P.x(), y[3 * i + 1] = P.y();
    } else if (i % 11 == 5) {                        // in the ramp, leaving fast: N clamped at 0
      V += 20.0 * n;
    }
    V += m.centre_velocity(touching, y.data(), y.data() + N);
    y[N + 3 * i] = V.x();
    y[N + 3 * i + 1] = V.y();
  }
  return y;
}

}  // namespace beltsim::test
