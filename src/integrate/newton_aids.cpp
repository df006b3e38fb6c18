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
// Local solve (friction_local_solve): an implicit stage solves G(Z) = Z - ψ - F(Z)/s = 0. Move the
// velocity of every element k pressing on a pulley by w_k·t̂_k (and its position by w_k·t̂_k/s,
// which keeps the position rows G_q = Z_q - ψ_q - Z_v/s at zero and leaves the penetration
// unchanged to first order), with everything else held. An SDE is a vector Kelvin–Voigt element
// (model/sde.cpp): moving the velocity of one of its ends by δ (its position by δ/s) changes its
// force by (c + k/s)·δ, and the velocity residual G_v = V - ψ_v - F_v/s of either end by λ·δ with
//   λ = (c + k/s)/(m·s),
// and the tangential residuals of a run of consecutive elements on one pulley (a wrap) become
//   g_k(w) = g0_k + (1 + 2λ)·w_k - λ·(t̂_k·t̂_{k-1})·w_{k-1} - λ·(t̂_k·t̂_{k+1})·w_{k+1}
//            + B_k·(sat((u0_k + w_k)/Δv) - sat(u0_k/Δv)),     B_k = μ_k·N_k/(m·s),
// with u0 the slip velocity (V - V_C)·t̂ - Ω·r, relative to the pulley's centre C (a tensioner arm
// moves it; the arm's angle is held), and g0 = t̂·G_v at the iterate (a neighbour off the run is
// held: its term drops). The linear part A is symmetric and diagonally dominant, sat is increasing,
// so g = ∇E of the strictly convex, piecewise quadratic
//   E(w) = ½·wᵀA·w + Σ_k (g0_k - B_k·sat(u0_k/Δv))·w_k + Σ_k B_k·Δv·H((u0_k + w_k)/Δv),
// H(x) = x²/2 for |x| <= 1, |x| - ½ beyond (Huber's function, H' = sat), and g(w) = 0 has one
// solution: E's minimum. Newton's method on g with the tridiagonal Hessian of the current piece
// (A plus B_k/Δv for each element in the band; Thomas' algorithm) and an exact line search on E
// (E is piecewise quadratic along a line: safeguarded Newton on its increasing, piecewise linear
// derivative) finds it; a full step that stays on its piece ends the iteration exactly. A run of one
// element is the scalar case g(w) = g0 + A·w + B·(sat((u0 + w)/Δv) - sat0).
// Solving whole wraps matters on fine belts: λ grows with the element count (k ∝ n, m ∝ 1/n), so
// neighbours are held far more by each other than by their own inertia, and a run of elements at
// the edge of a slip arc changes branch together: solved element by element, Newton would move
// the edge by one element per iteration and run out of iterations (docs/fine-belts.md).
//
// The local solve is Threlfall's alone: Stribeck's μ falls from μ_s to μ_k outside the band, so
// its g is not increasing, E not convex and g(w) = 0 may have several solutions; with that law
// friction_local_solve moves nothing and Newton goes without it. The reseat reads only the band
// |v_T| < Δv, which both laws have, and serves both.
//
// Overshoot (friction_overshoot): Newton's stop asks how far its last correction carries a slip
// velocity v_T past an edge of the band (esdirk.cpp says why). With x = v_T/Δv the pieces of sat(x)
// are x <= -1, |x| < 1 and x >= 1; a correction from x0 to x1 leaves x0's piece by the part of
// [x0, x1] beyond its edge. The change of v_T is taken to first order, along the tangent t̂ of the
// iterate: (δV - δV_C)·t̂ - δΩ·r, with δV_C the pulley centre's (a tensioner arm's speed times its
// length) and δΩ the pulley's (none for a kinematic pulley).
//
// Falling friction (falling_friction_rate): an element in contact, slipping at v_T, feels the
// tangential force -μ(v_T)·N; with everything else held its slip velocity obeys
//   m·dv_T/dt = -μ(v_T)·N + ...,   so   ∂(dv_T/dt)/∂v_T = -μ'(v_T)·N/m = ρ.
// On Threlfall's curve μ' >= 0 and ρ <= 0. Where a curve falls (Stribeck's past its peak, about
// v_s; LuGre's at a held bristle deflection) ρ > 0: the slip runs away at that rate until the
// element sticks or slides fast, within microseconds on the paper's drive (μ' ≈ -22 s/m at v_s =
// 0.01 m/s on a dry stretch, N ≈ 100 N, m ≈ 2 g: ρ ≈ 1e6 1/s). An implicit stage solves
// v - h·γ·a(v) = ψ, whose slope in that element's v_T is 1 - h·γ·ρ: past h·γ·ρ = 1 the slope
// turns negative, the stage damps the runaway the motion has (superstability) and Newton may settle
// on a root the motion never visits: elements held on the falling curve at slip speeds they
// would leave. On the half-wet drive under Stribeck's law that was the whole error: rtol 1e-5
// 7 % off in the span tensions where 1e-3 was 2.3 % (the integrator's own error estimate, a
// difference of two such solutions, cannot see it). The stepper refuses a stage past
// h·γ·ρ = 1 and keeps the next step below it (esdirk.cpp).
//
// Kinematic predictor (kinematic_predict): an implicit stage at t + dt starts Newton from the
// previous stage's value, taken at t. An element wrapped on a pulley moves round it by
// |v|·dt ≈ 1.2 mm in a stage at rtol 1e-3 (3.4 m/s, dt ≈ 0.35 ms), so left where it was it is
// 1.2 mm behind, its velocity turned by |v|·dt/R ≈ 0.012 rad from the tangent it will have: the
// first Newton correction, linear, moves it along the chord, off the circle by (|v|·dt)²/2R ≈ 7 µm
// (7 % of the static penetration) and with a slip velocity of |v|·0.012 ≈ 4 cm/s, 4 000 times
// the friction band: whole wraps would leave the band and cost iterations to come back. The
// predictor moves each pressing element as the wrap moves it: a rotation about the pulley centre
// C by θ = ((P - C) × V)/|P - C|²·dt, applied to P - C, to V and (as +θ) to the element angle, which
// keeps its penetration, slip velocity and spin as they are; a free element moves by V·dt (its
// angle by φ̇·dt), exact for a span in uniform motion; a pulley's angle by Ω·dt. On a pulley whose
// speed is prescribed, Ω changes over the stage, so the slip velocity v_T = V·t̂ - Ω·r is kept by
// adding (Ω(t + dt) - Ω(t))·r·t̂ to V (keep_slip): without it the whole wrap of a crankshaft
// with a firing pulsation started Newton slipping at some 300 bands, and the iteration took a
// Jacobian for each of the stick/slip changes on the way back.
// On a tensioner arm the centre moves: C(t) = c0 with velocity V_C = vc0, and the arm, turned at
// its rate ψ̇ over dt, holds it at c1 with velocity vc1 at t + dt. The rotation is that of the
// element relative to the centre, θ = ((P - c0) × (V - vc0))/|P - c0|²·dt, and the element lands
// at c1 + R(θ)·(P - c0) with velocity vc1 + R(θ)·(V - vc0), which keeps its penetration and slip
// velocity relative to the moving centre. Rotated with its absolute velocity about a centre held
// where it was, the serpentine's tensioner wrap (arm at 0.7 rad/s on a 63 mm lever, V_C ≈ 44 mm/s)
// started every stage slipping at a few bands; Newton's first correction, on the slipping
// branch, left the pulley 0.6–1 rad/s off its root, and the iteration swung the wrap by ±7 000
// bands between the local solve and Newton's corrections until the line search halved one (three
// Jacobians a stage). The arms', rotors' and hubs' angles advance at their rates, as the pulleys'.
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
// the two elements it lands between, about the pulley's centre (radius, angle, radial and
// tangential velocity, relative to the centre and its motion on an arm, as above) when both press
// on the same pulley, linearly otherwise; the angle φ by its wrapped difference, kept on the
// element's own branch of 2π. This is exact for a steady state whose fields are linear between
// elements, and for a wrap turning rigidly at a constant radius
// (tests/integrate/newton_aids_test.cpp). On a coarse belt the interpolation across a pitch is the
// larger error (20 mm pitches at 60 elements, the wrap ends' chords), so elements that travel
// less than half a pitch keep the kinematic prediction.
//
// Branches (contact_branches): the Jacobian and its factorisation are reused within a step while
// every pair stays on the same smooth piece of the contact and friction laws; the hash names
// that piece for every pair (out of contact, clamped, p < p_max, sticking or slipping either way).
#include "integrate/newton_aids.hpp"

#include <algorithm>
#include <cmath>

#include "model/block_matrix.hpp"
#include "model/contact_law.hpp"
#include "model/forces.hpp"

namespace beltsim {

namespace {
double sat(double x) { return std::clamp(x, -1.0, 1.0); }

// Minimises E over the elements lo .. lo + L - 1 of w.* (the pressing pairs on one pulley, see
// friction_local_solve) and, when w.J > 0, that pulley's speed change w.omega: Newton's method
// on ∇E with an exact line search. The Hessian of the current piece is tridiagonal in the
// elements (with breaks where two are not neighbours) bordered by the pulley's row, solved by
// Thomas' algorithm twice (for the gradient and for the border) and the border's Schur
// complement. Returns the iterations taken.
int solve_block(LocalSolveScratch& w, int lo, int L, double diag, double band) {
  double* x = w.w.data() + lo;
  const double* u0 = w.u0.data() + lo;
  const double* lin = w.lin.data() + lo;
  const double* B = w.B.data() + lo;
  const double* r = w.r.data() + lo;
  const double* off = w.off.data() + lo;  // off[k] couples k and k + 1 (0: no coupling)
  double* grad = w.grad.data() + lo;
  double* dir = w.dir.data() + lo;
  double* dz = w.dz.data() + lo;
  double* cp = w.cp.data() + lo;
  double* den = w.den.data() + lo;
  const double J = w.J;
  double& om = w.omega;
  auto Aw = [&](const double* v, int k) {
    double a = diag * v[k];
    if (k > 0) a += off[k - 1] * v[k - 1];
    if (k + 1 < L) a += off[k] * v[k + 1];
    return a;
  };
  auto slip = [&](int k, double wk, double o) { return (u0[k] + wk - r[k] * o) / band; };
  auto piece = [&](double y) { return y <= -1 ? -1 : y >= 1 ? 1 : 0; };
  // T·out = in with T's factorisation in cp, den (Thomas' algorithm)
  auto thomas = [&](const double* in, double* out) {
    for (int k = 0; k < L; ++k) out[k] = (in[k] - (k > 0 ? off[k - 1] * out[k - 1] : 0)) / den[k];
    for (int k = L - 2; k >= 0; --k) out[k] -= cp[k] * out[k + 1];
  };
  constexpr int kMaxIter = 50;
  int it = 0;
  for (; it < kMaxIter; ++it) {
    double gmax = 0, g_om = J > 0 ? w.lin_omega + J * om : 0;
    for (int k = 0; k < L; ++k) {
      const double f = B[k] * sat(slip(k, x[k], om));
      grad[k] = lin[k] + Aw(x, k) + f;
      g_om -= r[k] * f;
      gmax = std::max(gmax, std::abs(grad[k]));
    }
    gmax = std::max(gmax, std::abs(g_om));
    if (!(gmax > 0)) break;
    // the Hessian of the piece: T = A + diag(D), D_k = B_k/Δv in the band; border b_k = -r_k·D_k,
    // corner J + Σ r_k²·D_k
    double corner = J;
    for (int k = 0; k < L; ++k) {
      const double Dk = piece(slip(k, x[k], om)) == 0 ? B[k] / band : 0;
      const double sub = k > 0 ? off[k - 1] : 0;
      den[k] = diag + Dk - sub * (k > 0 ? cp[k - 1] : 0);
      cp[k] = k + 1 < L ? off[k] / den[k] : 0;
      dz[k] = -r[k] * Dk;  // the border, solved in place below
      corner += r[k] * r[k] * Dk;
      grad[k] = -grad[k];
    }
    thomas(grad, dir);  // y = -T⁻¹·g
    double d_om = 0;
    if (J > 0) {
      double bz = 0, by = 0;
      for (int k = 0; k < L; ++k) by += dz[k] * dir[k];
      thomas(dz, dz);  // z = T⁻¹·b (in place: each out[k] reads in[k] before it is written)
      for (int k = 0; k < L; ++k) bz += -r[k] * (piece(slip(k, x[k], om)) == 0 ? B[k] / band : 0) * dz[k];
      d_om = (-g_om - by) / (corner - bz);
      for (int k = 0; k < L; ++k) dir[k] -= dz[k] * d_om;
    }
    for (int k = 0; k < L; ++k) grad[k] = -grad[k];
    double slope = g_om * d_om, dmax = std::abs(d_om) * (L > 0 ? r[0] : 0);
    for (int k = 0; k < L; ++k) slope += grad[k] * dir[k], dmax = std::max(dmax, std::abs(dir[k]));
    if (!(slope < 0) || dmax <= 1e-6 * band) break;
    // exact line search: E along the direction is convex and piecewise quadratic, so its derivative
    // φ'(α) is increasing and piecewise linear; safeguarded Newton on φ' from α = 1
    double c0 = d_om * (J > 0 ? w.lin_omega + J * om : 0), dAd = J * d_om * d_om;
    for (int k = 0; k < L; ++k) c0 += dir[k] * (lin[k] + Aw(x, k)), dAd += dir[k] * Aw(dir, k);
    // (piece: a hash of the piece every element's slip is on at α, where φ' is linear)
    auto dphi = [&](double al, double& curv, uint64_t& piece_at) {
      double val = c0 + al * dAd;
      curv = dAd;
      piece_at = 0;
      for (int k = 0; k < L; ++k) {
        const double du = dir[k] - r[k] * d_om;
        if (du == 0) continue;
        const double yk = slip(k, x[k], om) + al * du / band;
        if (std::abs(yk) < 1) {
          val += B[k] * du * yk;
          curv += B[k] * du * du / band;
          piece_at = piece_at * 3 + 1;
        } else {
          val += B[k] * du * (yk > 0 ? 1 : -1);
          piece_at = piece_at * 3 + (yk > 0 ? 2 : 0);
        }
      }
      return val;
    };
    double lo_a = 0, hi_a = 1, curv = 0;
    uint64_t at = 0;
    double val = dphi(1, curv, at);
    for (int grow = 0; val < 0 && grow < 30; ++grow) lo_a = hi_a, hi_a *= 4, val = dphi(hi_a, curv, at);
    double alpha = hi_a;
    for (int ls = 0; ls < 60 && val != 0 && hi_a - lo_a > 1e-14 * hi_a; ++ls) {
      (val < 0 ? lo_a : hi_a) = alpha;
      double next = alpha - val / curv;
      const bool newton = next > lo_a && next < hi_a;
      if (!newton) next = 0.5 * (lo_a + hi_a);
      if (next == alpha) break;
      const uint64_t was = at;
      alpha = next;
      val = dphi(alpha, curv, at);
      // a Newton step that stayed on its piece landed on the zero of φ' there: φ' is linear on a
      // piece, so what is left of val is rounding, which further steps would only dither on
      if (newton && at == was) break;
    }
    bool same = true;
    const double om1 = om + alpha * d_om;
    for (int k = 0; k < L; ++k) {
      const double xn = x[k] + alpha * dir[k];
      same = same && piece(slip(k, xn, om1)) == piece(slip(k, x[k], om));
      x[k] = xn;
    }
    om = om1;
    if (same && std::abs(alpha - 1) < 1e-9) {  // a full step within one piece: E's minimum there
      ++it;
      break;
    }
  }
  return it;
}
}  // namespace

int friction_local_solve(const Model& m, const Drive& d, const ContactView& pairs, double s, double* q, double* v,
                         const double* g, LocalSolveScratch& w) {
  if (!m.every_law(FrictionKind::threlfall)) return 0;  // E is convex only for Threlfall's sat
  const double band = m.friction.dv;
  const Belt& bl = m.belt;
  // in units of force·time: an element's row times m, the pulley's times its inertia; then one
  // SDE adds c/s·... (c + k/s)/s per end
  const double lam = (bl.c + bl.k / s) / s;
  const double diag = bl.mass + 2 * lam;
  int moved = 0;
  for (int j = 0; j < m.n_p(); ++j) {
    // the pulley's pressing pairs, in element order (the pass's order within a pulley)
    w.pair.clear();
    for (int p = 0; p < pairs.size(); ++p)
      if (pairs[p].j == j && pairs[p].touching && pairs[p].nl.pushing) w.pair.push_back(p);
    const int L = static_cast<int>(w.pair.size());
    if (L == 0) continue;
    w.u0.resize(L), w.lin.resize(L), w.B.resize(L), w.r.resize(L), w.off.resize(L), w.w.assign(L, 0.0);
    w.grad.resize(L), w.dir.resize(L), w.dz.resize(L), w.cp.resize(L), w.den.resize(L);
    const int pc = m.pulley_coord(j);
    w.J = d.kinematic(j) ? 0 : d.mass(m, pc);
    w.omega = 0;
    w.lin_omega = w.J * g[pc];
    const Vec2 Vc = m.centre_velocity(j, q, v);
    for (int k = 0; k < L; ++k) {
      const ContactPair& c = pairs[w.pair[k]];
      const int i = c.i;
      const NormalLaw& nl = c.nl;
      const Vec2 V = Vec2(v[3 * i], v[3 * i + 1]) - Vc;  // relative to the pulley's centre (a tensioner arm moves it)
      w.u0[k] = V.dot(nl.t) - c.omega * nl.r;
      w.r[k] = w.J > 0 ? nl.r : 0;
      w.B[k] = c.mu * nl.N / s;
      const double f0 = w.B[k] * sat(w.u0[k] / band);
      w.lin[k] = bl.mass * (g[3 * i] * nl.t.x() + g[3 * i + 1] * nl.t.y()) - f0;
      w.lin_omega += w.r[k] * f0;
      w.off[k] = 0;
      if (k + 1 < L && pairs[w.pair[k + 1]].i == i + 1) w.off[k] = -lam * nl.t.dot(pairs[w.pair[k + 1]].nl.t);
    }
    solve_block(w, 0, L, diag, band);
    for (int k = 0; k < L; ++k) {
      if (w.w[k] == 0) continue;
      const ContactPair& c = pairs[w.pair[k]];
      const int i = c.i;
      v[3 * i] += w.w[k] * c.nl.t.x();
      v[3 * i + 1] += w.w[k] * c.nl.t.y();
      q[3 * i] += w.w[k] / s * c.nl.t.x();
      q[3 * i + 1] += w.w[k] / s * c.nl.t.y();
      ++moved;
    }
    if (w.omega != 0) v[pc] += w.omega, q[pc] += w.omega / s, ++moved;
  }
  return moved;
}

int friction_reseat(const Model& m, const Drive& d, const ContactView& pairs, const double* q, double* v,
                    const double* dq, double* dv, Reseat where) {
  int moved = 0;
  for (const ContactPair& c : pairs) {
    if (!c.touching || !c.nl.pushing) continue;
    const Friction& f = m.friction_of(c.i);
    if (f.law == FrictionKind::lugre) continue;  // no band: the bristle law is smooth but at v_T = 0
    const double band = f.dv;
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

double friction_overshoot(const Model& m, const Drive& d, const ContactView& pairs, const double* q, const double* dv) {
  double worst = 0;
  for (const ContactPair& c : pairs) {
    if (!c.touching || !c.nl.pushing) continue;
    const Friction& f = m.friction_of(c.i);
    if (f.law == FrictionKind::lugre) continue;
    const int i = c.i, j = c.j;
    // the slip velocity's change: the element's along t̂, against the pulley centre's (linear in
    // the arm's speed) and the surface's
    const Vec2 dV = Vec2(dv[3 * i], dv[3 * i + 1]) - m.centre_velocity(j, q, dv);
    const double domega = d.kinematic(j) ? 0.0 : dv[m.pulley_coord(j)];
    const double x0 = c.fl.vT / f.dv, x1 = x0 + (dV.dot(c.nl.t) - domega * c.nl.r) / f.dv;
    // the part of [x0, x1] outside x0's piece: (-∞, -1], (-1, 1) or [1, ∞)
    const double past = x0 >= 1 ? 1 - x1 : x0 <= -1 ? x1 + 1 : std::abs(x1) - 1;
    worst = std::max(worst, past);
  }
  return worst;
}

double falling_friction_rate(const Model& m, const ContactView& pairs) {
  double worst = 0;
  for (const ContactPair& c : pairs)
    if (c.touching && c.nl.pushing && c.fl.dmu < 0) worst = std::max(worst, -c.fl.dmu * c.nl.N / m.belt.mass);
  return worst;
}

void pressed_pulleys(const Model& m, const ContactView& pairs, std::vector<int>& on) {
  on.assign(m.belt.n, -1);
  for (const ContactPair& c : pairs)  // pulley by pulley: the first pulley an element presses on
    if (c.touching && c.nl.pushing && on[c.i] < 0) on[c.i] = c.j;
}

namespace {
// the pulleys' angles, and the arms', rotors' and hubs' (the coordinates after the pulleys'),
// each at its rate
void advance_pulleys(const Model& m, const Drive& d, double t, double dt, double* q, const double* v) {
  for (int j = 0; j < m.n_p(); ++j) q[m.pulley_coord(j)] += dt * d.omega(m, j, t, v);
  for (int k = m.pulley_coord(0) + m.n_p(); k < m.n_coord(); ++k) q[k] += dt * v[k];
}

// the pulley each element presses on (w.on), each pulley's change of speed over the stage (w.dom:
// a prescribed speed's Ω(t + dt) - Ω(t), 0 for a speed that is a state, which the prediction
// keeps) and its centre with its velocity before and after (w.c0, w.vc0, w.c1, w.vc1: they differ
// on a tensioner arm); the pulleys and arms are moved on (advance_pulleys) in between
void prepare(const Model& m, const Drive& d, double t, double dt, const ContactView& pairs, double* q, const double* v,
             PredictScratch& w) {
  pressed_pulleys(m, pairs, w.on);
  const int np = m.n_p();
  w.dom.assign(np, 0.0);
  w.c0.resize(np), w.vc0.resize(np), w.c1.resize(np), w.vc1.resize(np);
  for (int j = 0; j < np; ++j) {
    if (d.kinematic(j)) w.dom[j] = d.omega(m, j, t + dt, v) - d.omega(m, j, t, v);
    w.c0[j] = m.centre(j, q), w.vc0[j] = m.centre_velocity(j, q, v);
  }
  advance_pulleys(m, d, t, dt, q, v);
  for (int j = 0; j < np; ++j) w.c1[j] = m.centre(j, q), w.vc1[j] = m.centre_velocity(j, q, v);
}

// element i, on pulley j at t + dt, keeps its slip velocity v_T = V·t̂ - Ω·r when Ω changes by
// dom over the stage: V gains dom·r along t̂
void keep_slip(const PredictScratch& w, int j, int i, const double* q, double* v) {
  const double dom = w.dom[j];
  if (dom == 0) return;
  const Vec2 e = Vec2(q[3 * i], q[3 * i + 1]) - w.c1[j];  // r·n; r·t̂ = (-e_y, e_x)
  v[3 * i] -= dom * e.y(), v[3 * i + 1] += dom * e.x();
}

// element i moved by kinematic_predict, given the pulley it presses on (-1: none)
void kinematic_move(const PredictScratch& w, double dt, int i, double* q, double* v) {
  const int on = w.on[i];
  const Vec2 P(q[3 * i], q[3 * i + 1]), V(v[3 * i], v[3 * i + 1]);
  if (on < 0) {
    q[3 * i] += dt * V.x(), q[3 * i + 1] += dt * V.y(), q[3 * i + 2] += dt * v[3 * i + 2];
    return;
  }
  // relative to the centre, which moves from c0 to c1 on a tensioner arm
  const Vec2 d = P - w.c0[on], U = V - w.vc0[on], C = w.c1[on], Vc = w.vc1[on];
  const double th = (d.x() * U.y() - d.y() * U.x()) / d.squaredNorm() * dt;
  const double c = std::cos(th), s = std::sin(th);
  q[3 * i] = C.x() + c * d.x() - s * d.y();
  q[3 * i + 1] = C.y() + s * d.x() + c * d.y();
  q[3 * i + 2] += th;
  v[3 * i] = Vc.x() + c * U.x() - s * U.y();
  v[3 * i + 1] = Vc.y() + s * U.x() + c * U.y();
  keep_slip(w, on, i, q, v);
}
}  // namespace

void kinematic_predict(const Model& m, const Drive& d, double t, double dt, const ContactView& pairs, double* q,
                       double* v, PredictScratch& w) {
  prepare(m, d, t, dt, pairs, q, v, w);
  for (int i = 0; i < m.belt.n; ++i) kinematic_move(w, dt, i, q, v);
}

void convective_predict(const Model& m, const Drive& d, double t, double dt, const ContactView& pairs, double* q,
                        double* v, PredictScratch& w) {
  constexpr double kTravel = 0.5;  // pitches an element travels in dt before it takes the state found there
  const int n = m.belt.n;
  const double reach = kTravel * m.belt.pitch;
  bool any = false;
  for (int i = 0; i < n && !any; ++i) any = std::hypot(v[3 * i], v[3 * i + 1]) * std::abs(dt) >= reach;
  if (!any) {
    kinematic_predict(m, d, t, dt, pairs, q, v, w);
    return;
  }
  w.q0.assign(q, q + 3 * n);
  w.v0.assign(v, v + 3 * n);
  const double* q0 = w.q0.data();
  const double* v0 = w.v0.data();
  prepare(m, d, t, dt, pairs, q, v, w);
  auto pos = [q0](int k) { return Vec2(q0[3 * k], q0[3 * k + 1]); };
  auto vel = [v0](int k) { return Vec2(v0[3 * k], v0[3 * k + 1]); };
  auto cross = [](const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); };
  for (int i = 0; i < n; ++i) {
    const Vec2 V = vel(i);
    double rest = V.norm() * std::abs(dt);
    if (rest < reach) {
      kinematic_move(w, dt, i, q, v);
      continue;
    }
    // the direction of the element's motion along the belt
    const int dir = (V.dot(pos(after(i, n)) - pos(before(i, n))) >= 0) == (dt > 0) ? 1 : n - 1;
    int a = i, b = i;
    double f = -1, dth = 0;
    for (int walked = 0; walked < n / 2; ++walked, a = b) {
      b = (a + dir) % n;
      const bool arc = w.on[a] >= 0 && w.on[a] == w.on[b];
      double seg;
      if (arc) {
        const Vec2 C = w.c0[w.on[a]], da = pos(a) - C, db = pos(b) - C;
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
      kinematic_move(w, dt, i, q, v);
      continue;
    }
    Vec2 P1, V1;
    if (w.on[a] >= 0 && w.on[a] == w.on[b]) {
      // about the centre, relative to its motion (c0 at t, c1 at t + dt on a tensioner arm)
      const int j = w.on[a];
      const Vec2 da = pos(a) - w.c0[j], db = pos(b) - w.c0[j], ua = vel(a) - w.vc0[j], ub = vel(b) - w.vc0[j];
      const double ra = da.norm(), rb = db.norm();
      const Vec2 ea = da / ra, eb = db / rb;
      const double c = std::cos(f * dth), s = std::sin(f * dth);
      const Vec2 e(c * ea.x() - s * ea.y(), s * ea.x() + c * ea.y());
      const double vr = (1 - f) * ua.dot(ea) + f * ub.dot(eb);
      const double vt = (1 - f) * cross(ea, ua) + f * cross(eb, ub);
      P1 = w.c1[j] + ((1 - f) * ra + f * rb) * e;
      V1 = w.vc1[j] + vr * e + vt * Vec2(-e.y(), e.x());
    } else {
      P1 = (1 - f) * pos(a) + f * pos(b);
      V1 = (1 - f) * vel(a) + f * vel(b);
    }
    const double phi = q0[3 * a + 2] + f * wrap_angle(q0[3 * b + 2] - q0[3 * a + 2]);
    q[3 * i] = P1.x(), q[3 * i + 1] = P1.y();
    q[3 * i + 2] = q0[3 * i + 2] + wrap_angle(phi - q0[3 * i + 2]);
    v[3 * i] = V1.x(), v[3 * i + 1] = V1.y();
    v[3 * i + 2] = (1 - f) * v0[3 * a + 2] + f * v0[3 * b + 2];
    if (w.on[a] >= 0 && w.on[a] == w.on[b]) keep_slip(w, w.on[a], i, q, v);
  }
}

uint64_t contact_branches(const Model& m, const ContactView& pairs) {
  // FNV-1a over (pulley, element, branch code) of every pair in contact
  uint64_t h = 1469598103934665603ull;
  auto mix = [&h](uint64_t x) { h = (h ^ x) * 1099511628211ull; };
  for (const ContactPair& c : pairs) {
    if (!c.touching) continue;
    const NormalLaw& nl = c.nl;
    uint64_t code = 1 + (nl.pushing ? 2 : 0) + (nl.p < m.contact.p_max ? 4 : 0);
    if (nl.pushing) {
      const double x = c.fl.vT / m.friction_of(c.i).dv;
      code += x <= -1 ? 8 : x >= 1 ? 16 : 0;
    }
    mix(static_cast<uint64_t>(c.j) << 40 | static_cast<uint64_t>(c.i) << 8 | code);
  }
  return h;
}

}  // namespace beltsim
