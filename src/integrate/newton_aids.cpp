// Newton aids for the friction band and the contact branches (declared in newton_aids.hpp).
// Slip velocity v_T, the band Δv and sat() are those of the friction law (model/friction.cpp).
//
// Newton across the band (friction_reseat): at a slipping iterate (|v_T| >= Δv) the friction
// force is locally constant, so a Newton step cannot see the band; when the step would carry
// v_T from one side of the band right across to the other, the solution is almost always
// sticking (|v_T| < Δv). friction_reseat then puts the element into the band (v_T = 0), in one of
// two places: where the correction takes it (Reseat::correction: its velocity correction along
// the tangent t̂ there changes, against the corrected pulley speed, and the rest of the
// correction is kept) or at the iterate as it is (Reseat::iterate: its velocity along t̂ changes,
// and the iteration starts again from there). The next Newton step sees the band's slope and
// lands on the sticking solution, or leaves the band again if the element truly slips. Which of
// the two, and what each gave, is at the esdirk stepper's Newton iteration (esdirk.cpp).
//
// Local solve (friction_local_solve): an implicit stage solves G(Z) = Z - ψ - F(Z)/s = 0. For
// one element in contact, move its velocity by w·t̂ (and its position by w·t̂/s, which keeps the
// position rows G_q = Z_q - ψ_q - Z_v/s at zero and leaves the penetration unchanged to first
// order) with everything else held. Its tangential residual is then
//   g(w) = g0 + A·w + B·(sat((u0 + w)/Δv) - sat(u0/Δv)),
//   A = 1 + (2c + 2k/s)/(m·s)   (the two SDEs' dampers and springs resisting the move),
//   B = μ_i·N/(m·s)             (friction, saturated outside the band),
// with u0 the slip velocity and g0 = t̂·G_v at the iterate. g is increasing and piecewise linear
// in w, so g(w) = 0 is solved exactly by trying the three pieces (slip forwards, slip backwards,
// stick: w = -(g0 + B·(u0/Δv - sat0))/(A + B/Δv)).
//
// Kinematic predictor (kinematic_predict): an implicit stage at t + dt starts Newton from the
// previous stage's value, taken at t. An element wrapped on a pulley moves round it by
// |v|·dt ≈ 1.2 mm in a stage at rtol 1e-3 (3.4 m/s, dt ≈ 0.35 ms), so left where it was it is
// 1.2 mm behind, its velocity turned by |v|·dt/R ≈ 0.012 rad from the tangent it will have: the
// first Newton correction, linear, moves it along the chord, off the circle by (|v|·dt)²/2R ≈ 7 µm
// (7 % of the static penetration) and with a slip velocity of |v|·0.012 ≈ 4 cm/s, 4 000 times
// the friction band, so whole wraps left the band and were put back by the next iterations. The
// predictor moves each pressing element as the wrap moves it: a rotation about the pulley centre
// C by θ = ((P - C) × V)/|P - C|²·dt, applied to P - C, to V and (as +θ) to the element angle, which
// keeps its penetration, slip velocity and spin as they are; a free element moves by V·dt (its
// angle by φ̇·dt), exact for a span in uniform motion; a pulley's angle by Ω·dt.
//
// Convective predictor (convective_predict): the kinematic predictor carries each element's
// own state along its motion, so whatever it was (sticking, out of contact) it stays. But in a drive
// that runs steadily the state is stationary in space, not in the belt: an element that reaches
// the edge of a slip arc starts to slip, one that reaches the end of a wrap leaves the pulley. On
// a fine belt an element passes several pitches in a stage (2 400 elements on the paper's drive:
// a pitch of 0.50 mm; 3.4 m/s over a stage of 0.35 ms is 1.2 mm, 2.4 pitches), so many elements
// start Newton on the branch of the place they left, and at the edge of each slip arc Newton
// moves the edge by one element per iteration. For each element that travels at least half a pitch,
// d = |V|·dt ≥ l/2, this predictor walks d along the belt as it was at t, in the direction of the
// element's motion (element to element, along the arc r̄·|Δθ| between two elements on one pulley,
// along the chord otherwise), and gives the element the state found there: interpolated between
// the two elements it lands between, about the pulley's centre (radius, angle, radial and tangential
// velocity) when both press on the same pulley, linearly otherwise; the angle φ by its wrapped
// difference, kept on the element's own branch of 2π. This is exact for a steady state whose fields are
// linear between elements, and for a wrap turning rigidly at a constant radius
// (tests/integrate/predictor_test.cpp). On a coarse belt the interpolation across a pitch is the
// larger error (20 mm pitches at 60 elements, the wrap ends' chords), so elements that travel
// less than half a pitch keep the kinematic prediction.
//
// Branches (contact_branches): the Jacobian and its factorisation are reused within a step while
// every pair stays on the same smooth piece of the contact and friction laws; the hash names
// that piece for every pair (out of contact, clamped, p < p_max, sticking or slipping either way).
#include "integrate/newton_aids.hpp"

#include <algorithm>
#include <cmath>

#include "model/contact_law.hpp"
#include "model/forces.hpp"

namespace beltsim {

int friction_local_solve(const Model& m, const Drive& d, const ContactList& pairs, double s, double* q, double* v,
                         const double* g) {
  const double band = m.friction.dv;
  const Belt& bl = m.belt;
  // the element's own linear resistance to a tangential velocity change w inside one stage: its
  // two SDEs' dampers (2c) and, through the position change w/s, springs (2k), per unit mass
  const double lam = (2 * bl.c + 2 * bl.k / s) / (bl.mass * s);
  const double A = 1 + lam;
  int moved = 0;
  for (const ContactPair& c : pairs) {
    if (!c.touching || !c.nl.pushing) continue;
    const int i = c.i;
    const NormalLaw& nl = c.nl;
    const Vec2 V = Vec2(v[3 * i], v[3 * i + 1]) - m.centre_velocity(c.j, q, v);  // relative to a moving centre
    const double u0 = V.dot(nl.t) - c.omega * nl.r;
    const double x0 = std::clamp(u0 / band, -1.0, 1.0);
    const double g0 = g[3 * i] * nl.t.x() + g[3 * i + 1] * nl.t.y();
    const double B = d.mu[i] * nl.N / (s * bl.mass);
    double w = -(g0 + B * (1 - x0)) / A;  // slipping forwards
    if (u0 + w < band) {
      w = -(g0 + B * (-1 - x0)) / A;  // backwards
      if (u0 + w > -band) w = -(g0 + B * (u0 / band - x0)) / (A + B / band);  // sticking
    }
    if (w == 0) continue;
    v[3 * i] += w * nl.t.x();
    v[3 * i + 1] += w * nl.t.y();
    q[3 * i] += w / s * nl.t.x();
    q[3 * i + 1] += w / s * nl.t.y();
    ++moved;
  }
  return moved;
}

int friction_reseat(const Model& m, const Drive& d, const ContactList& pairs, const double* q, double* v,
                    const double* dq, double* dv, Reseat where) {
  const double band = m.friction.dv;
  int moved = 0;
  for (const ContactPair& c : pairs) {
    if (!c.touching || !c.nl.pushing) continue;
    const int i = c.i, j = c.j;
    const Pulley& pl = m.pulleys[j];
    const NormalLaw& a = c.nl;
    const double omega0 = c.omega;
    const double omega1 = d.kinematic(j) ? omega0 : omega0 + dv[m.pulley_coord(j)];
    // velocities relative to the pulley's centre (it moves on a tensioner arm)
    const Vec2 P0(q[3 * i], q[3 * i + 1]), V0 = Vec2(v[3 * i], v[3 * i + 1]) - m.centre_velocity(j, q, v);
    const double vt0 = V0.dot(a.t) - omega0 * a.r;
    if (std::abs(vt0) < band) continue;
    // the same pair where the correction takes it
    Vec2 C1 = pl.centre, VC1 = Vec2::Zero();
    if (pl.arm >= 0) {
      const Arm& arm = m.arms[pl.arm];
      const int k = m.arm_coord(pl.arm);
      const Vec2 e(std::cos(q[k] + dq[k]), std::sin(q[k] + dq[k]));
      C1 = arm.pivot + arm.length * e;
      VC1 = arm.length * (v[k] + dv[k]) * perp(e) - m.centre_velocity(j, q, v);
    }
    const Vec2 P1 = P0 + Vec2(dq[3 * i], dq[3 * i + 1]), V1 = V0 + Vec2(dv[3 * i], dv[3 * i + 1]) - VC1;
    NormalLaw b;
    if (!normal_law(m.contact, P1, V1, C1, pl.radius, b)) continue;
    const double vt1 = V1.dot(b.t) - omega1 * b.r;
    if (std::abs(vt1) < band || (vt1 > 0) == (vt0 > 0)) continue;
    if (where == Reseat::correction) {
      dv[3 * i] -= vt1 * b.t.x();
      dv[3 * i + 1] -= vt1 * b.t.y();
    } else {
      v[3 * i] -= vt0 * a.t.x();
      v[3 * i + 1] -= vt0 * a.t.y();
    }
    ++moved;
  }
  return moved;
}

void pressed_pulleys(const Model& m, const ContactList& pairs, std::vector<int>& on) {
  on.assign(m.belt.n, -1);
  for (const ContactPair& c : pairs)  // pulley by pulley: the first pulley an element presses on
    if (c.touching && c.nl.pushing && on[c.i] < 0) on[c.i] = c.j;
}

namespace {
// element i moved by kinematic_predict, given the pulley it presses on (-1: none)
void kinematic_move(const Model& m, int on, double dt, int i, double* q, double* v) {
  const Vec2 P(q[3 * i], q[3 * i + 1]), V(v[3 * i], v[3 * i + 1]);
  if (on < 0) {
    q[3 * i] += dt * V.x(), q[3 * i + 1] += dt * V.y(), q[3 * i + 2] += dt * v[3 * i + 2];
    return;
  }
  const Vec2 C = m.centre(on, q), d = P - C;
  const double th = (d.x() * V.y() - d.y() * V.x()) / d.squaredNorm() * dt;
  const double c = std::cos(th), s = std::sin(th);
  q[3 * i] = C.x() + c * d.x() - s * d.y();
  q[3 * i + 1] = C.y() + s * d.x() + c * d.y();
  q[3 * i + 2] += th;
  v[3 * i] = c * V.x() - s * V.y();
  v[3 * i + 1] = s * V.x() + c * V.y();
}

void advance_pulleys(const Model& m, const Drive& d, double t, double dt, double* q, const double* v) {
  for (int j = 0; j < m.n_p(); ++j) q[m.pulley_coord(j)] += dt * d.omega(m, j, t, v);
}
}  // namespace

void kinematic_predict(const Model& m, const Drive& d, double t, double dt, double* q, double* v, PredictScratch& w) {
  contact_pass(m, d, t, q, v, Span{0, m.belt.n}, w.pairs);
  pressed_pulleys(m, w.pairs, w.on);
  for (int i = 0; i < m.belt.n; ++i) kinematic_move(m, w.on[i], dt, i, q, v);
  advance_pulleys(m, d, t, dt, q, v);
}

void convective_predict(const Model& m, const Drive& d, double t, double dt, double* q, double* v, PredictScratch& w) {
  constexpr double kTravel = 0.5;  // pitches an element travels in dt before it takes the state found there
  const int n = m.belt.n;
  const double reach = kTravel * m.belt.pitch;
  bool any = false;
  for (int i = 0; i < n && !any; ++i) any = std::hypot(v[3 * i], v[3 * i + 1]) * std::abs(dt) >= reach;
  if (!any) {
    kinematic_predict(m, d, t, dt, q, v, w);
    return;
  }
  w.q0.assign(q, q + 3 * n);
  w.v0.assign(v, v + 3 * n);
  const double* q0 = w.q0.data();
  const double* v0 = w.v0.data();
  contact_pass(m, d, t, q, v, Span{0, n}, w.pairs);
  pressed_pulleys(m, w.pairs, w.on);
  advance_pulleys(m, d, t, dt, q, v);
  auto pos = [q0](int k) { return Vec2(q0[3 * k], q0[3 * k + 1]); };
  auto vel = [v0](int k) { return Vec2(v0[3 * k], v0[3 * k + 1]); };
  auto cross = [](const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); };
  for (int i = 0; i < n; ++i) {
    const Vec2 V = vel(i);
    double rest = V.norm() * std::abs(dt);
    if (rest < reach) {
      kinematic_move(m, w.on[i], dt, i, q, v);
      continue;
    }
    // the direction of the element's motion along the belt
    const int dir = (V.dot(pos((i + 1) % n) - pos((i + n - 1) % n)) >= 0) == (dt > 0) ? 1 : n - 1;
    int a = i, b = i;
    double f = -1, dth = 0;
    for (int walked = 0; walked < n / 2; ++walked, a = b) {
      b = (a + dir) % n;
      const bool arc = w.on[a] >= 0 && w.on[a] == w.on[b];
      double seg;
      if (arc) {
        const Vec2 C = m.centre(w.on[a], q), da = pos(a) - C, db = pos(b) - C;
        dth = std::atan2(cross(da, db), da.dot(db));
        seg = 0.5 * (da.norm() + db.norm()) * std::abs(dth);
      } else {
        seg = (pos(b) - pos(a)).norm();
      }
      if (rest <= seg) {
        f = seg > 0 ? rest / seg : 0;
        break;
      }
      rest -= seg;
    }
    if (f < 0) {  // a walk round half the belt: the kinematic prediction
      kinematic_move(m, w.on[i], dt, i, q, v);
      continue;
    }
    Vec2 P1, V1;
    if (w.on[a] >= 0 && w.on[a] == w.on[b]) {
      const Vec2 C = m.centre(w.on[a], q), da = pos(a) - C, db = pos(b) - C;
      const double ra = da.norm(), rb = db.norm();
      const Vec2 ea = da / ra, eb = db / rb;
      const double c = std::cos(f * dth), s = std::sin(f * dth);
      const Vec2 e(c * ea.x() - s * ea.y(), s * ea.x() + c * ea.y());
      const double vr = (1 - f) * vel(a).dot(ea) + f * vel(b).dot(eb);
      const double vt = (1 - f) * cross(ea, vel(a)) + f * cross(eb, vel(b));
      P1 = C + ((1 - f) * ra + f * rb) * e;
      V1 = vr * e + vt * Vec2(-e.y(), e.x());
    } else {
      P1 = (1 - f) * pos(a) + f * pos(b);
      V1 = (1 - f) * vel(a) + f * vel(b);
    }
    const double phi = q0[3 * a + 2] + f * wrap_angle(q0[3 * b + 2] - q0[3 * a + 2]);
    q[3 * i] = P1.x(), q[3 * i + 1] = P1.y();
    q[3 * i + 2] = q0[3 * i + 2] + wrap_angle(phi - q0[3 * i + 2]);
    v[3 * i] = V1.x(), v[3 * i + 1] = V1.y();
    v[3 * i + 2] = (1 - f) * v0[3 * a + 2] + f * v0[3 * b + 2];
  }
}

uint64_t contact_branches(const Model& m, const ContactList& pairs) {
  // FNV-1a over (pulley, element, branch code) of every pair in contact
  uint64_t h = 1469598103934665603ull;
  auto mix = [&h](uint64_t x) { h = (h ^ x) * 1099511628211ull; };
  for (const ContactPair& c : pairs) {
    if (!c.touching) continue;
    const NormalLaw& nl = c.nl;
    uint64_t code = 1 + (nl.pushing ? 2 : 0) + (nl.p < m.contact.p_max ? 4 : 0);
    if (nl.pushing) {
      const double x = c.fl.vT / m.friction.dv;
      code += x <= -1 ? 8 : x >= 1 ? 16 : 0;
    }
    mix(static_cast<uint64_t>(c.j) << 40 | static_cast<uint64_t>(c.i) << 8 | code);
  }
  return h;
}

}  // namespace beltsim
