// The switching functions (integrate/switches.cpp) against the laws they mark the kinks of
// (model/contact_law.hpp): over states that put element–pulley pairs on every piece (out of
// contact, p < p_max, p > p_max, clamped, in the friction band, slipping either way), each
// function's sign tells the piece the laws themselves report, and along a straight path in
// the state each function changes by no more than its slope times the path step (no jumps
// where the laws change piece, which CVODE's rootfinding needs).
#include "integrate/switches.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "model/contact_law.hpp"
#include "model/contacts.hpp"
#include "support/presets.hpp"

namespace beltsim {
namespace {

struct Pieces {
  bool contact = false, deep = false, pushing = false, band = false;
};

Pieces pieces(const Model& m, const Drive& dr, double t, const double* q, const double* v, int j, int i) {
  Pieces pc;
  const Pulley& pl = m.pulleys[j];
  const Vec2 P(q[3 * i], q[3 * i + 1]), V(v[3 * i], v[3 * i + 1]);
  NormalLaw nl;
  if (!normal_law(m.contact, P, V, pl.centre, pl.radius, nl)) return pc;
  pc.contact = true;
  pc.deep = nl.p > m.contact.p_max;
  pc.pushing = nl.pushing;
  if (nl.pushing)
    pc.band = std::abs(friction_law(dr.mu[i], m.friction.dv, nl, V, dr.omega(m, j, t, v)).vT) < m.friction.dv;
  return pc;
}

// each element is put on the pulley nearest it at a random depth p ∈ [-1, 2.5] mm (p_max = 1 mm),
// moving with the pulley's surface plus a random slip in [-3, 3]·Δv and a random radial speed
// ṗ in [-4, 0.5] m/s (an element separating faster than about 2 m/s is clamped)
Eigen::VectorXd random_state(const Model& m, const Eigen::VectorXd& y0, std::mt19937& rng) {
  std::uniform_real_distribution<double> depth(-1e-3, 2.5e-3), slip(-3, 3), radial(-4, 0.5);
  Eigen::VectorXd y = y0;
  const int N = m.n_coord();
  const double omega[2] = {-60.0, -59.5};
  for (int j = 0; j < m.n_p(); ++j) y[N + m.pulley_coord(j)] = omega[j];
  for (int i = 0; i < m.belt.n; ++i) {
    const Vec2 P(y[3 * i], y[3 * i + 1]);
    int j = 0;
    for (int k = 1; k < m.n_p(); ++k)
      if ((P - m.pulleys[k].centre).norm() - m.pulleys[k].radius <
          (P - m.pulleys[j].centre).norm() - m.pulleys[j].radius)
        j = k;
    const Pulley& pl = m.pulleys[j];
    const Vec2 n = (P - pl.centre).normalized(), t = perp(n);
    const double r = pl.radius - depth(rng);
    const Vec2 Pn = pl.centre + r * n;
    const Vec2 V = (omega[j] * r + slip(rng) * m.friction.dv) * t - radial(rng) * n;
    y[3 * i] = Pn.x(), y[3 * i + 1] = Pn.y();
    y[N + 3 * i] = V.x(), y[N + 3 * i + 1] = V.y();
  }
  return y;
}

TEST(ContactSwitches, TheirSignsAreTheLawsPieces) {
  const Scene sc = build_scene(presets::paper_dry());
  const Model& m = sc.model;
  const Drive& dr = sc.drive;
  const int N = m.n_coord(), n = m.belt.n;
  ASSERT_EQ(switch_count(m), kSwitchesPerPair * m.n_p() * n);
  std::mt19937 rng(11);
  std::vector<double> g(switch_count(m));
  int seen[5] = {0, 0, 0, 0, 0};  // out of contact, deep, clamped, in the band, slipping
  for (int trial = 0; trial < 40; ++trial) {
    const Eigen::VectorXd y = random_state(m, sc.y0, rng);
    const double t = 0.5;
    ContactRecords records;
    fill_contacts(m, sc.drive, t, y.data(), records, Pairs::all);
    contact_switches(m, records.pairs(), g.data());
    for (int j = 0; j < m.n_p(); ++j)
      for (int i = 0; i < n; ++i) {
        const double* gi = g.data() + kSwitchesPerPair * (j * n + i);
        const Pieces pc = pieces(m, dr, t, y.data(), y.data() + N, j, i);
        EXPECT_EQ(gi[0] > 0, pc.contact) << "pulley " << j << " element " << i;
        if (!pc.contact) {
          ++seen[0];
          continue;
        }
        EXPECT_EQ(gi[1] > 0, pc.deep) << "pulley " << j << " element " << i;
        EXPECT_EQ(gi[2] > 0, pc.pushing) << "pulley " << j << " element " << i;
        seen[1] += pc.deep, seen[2] += !pc.pushing;
        if (pc.pushing) {
          EXPECT_EQ(gi[3] < 0, pc.band) << "pulley " << j << " element " << i;
          ++seen[pc.band ? 3 : 4];
        }
      }
  }
  for (int k = 0; k < 5; ++k) EXPECT_GT(seen[k], 20) << "piece " << k << " was not met";
}

// g0..g2 along a straight path between two random states, in 20 000 steps: between neighbouring
// points each changes by less than 1e-3 of its range over the path (measured: below 1e-4; a jump
// where a law changes piece, such as g2 ≠ 0 at p = 0, is a finite part of the range)
TEST(ContactSwitches, AreContinuousInTheState) {
  const Scene sc = build_scene(presets::paper_dry());
  const Model& m = sc.model;
  const Drive& dr = sc.drive;
  const int count = switch_count(m);
  std::mt19937 rng(5);
  const Eigen::VectorXd a = random_state(m, sc.y0, rng), b = random_state(m, sc.y0, rng);
  constexpr int kSteps = 20000;
  std::vector<double> g(count), prev(count), lo(count, 1e300), hi(count, -1e300), jump(count, 0);
  for (int s = 0; s <= kSteps; ++s) {
    const Eigen::VectorXd y = a + (b - a) * (static_cast<double>(s) / kSteps);
    ContactRecords records;
    fill_contacts(m, dr, 0.5, y.data(), records, Pairs::all);
    contact_switches(m, records.pairs(), g.data());
    for (int k = 0; k < count; ++k) {
      lo[k] = std::min(lo[k], g[k]), hi[k] = std::max(hi[k], g[k]);
      if (s > 0) jump[k] = std::max(jump[k], std::abs(g[k] - prev[k]));
    }
    prev.swap(g);
  }
  for (int k = 0; k < count; ++k) {
    if (k % kSwitchesPerPair == 3) continue;  // g3 jumps where pushing starts, at a zero of g2
    EXPECT_LT(jump[k], 1e-3 * (hi[k] - lo[k]) + 1e-300) << "switch " << k;
  }
}

}  // namespace
}  // namespace beltsim
