// Longitudinal spring-damper elements (paper eq. 5).
//
// SDE i joins end B of element a = i-1 to end A of element b = i (h = l_e/2, e(φ) = (cos φ, sin φ),
// e'(φ) = (-sin φ, cos φ)):
//   B = P_a + h·e_a,   A = P_b - h·e_b,   d = A - B,   ḋ = D·v_ab
// where D (2×6) = ∂d/∂(x_a, y_a, φ_a, x_b, y_b, φ_b) = [ -I | -h·e'_a | I | -h·e'_b ].
// Force law (vector Kelvin–Voigt, exponent e = e_tra >= 1):
//   F = k·g(d) + c·ḋ,   g(d) = |d|^(e-1)·d     (e = 1: F = k·d + c·ḋ)
// The generalized forces follow from virtual work, Q = -Dᵀ·F: element a is pulled by +F at B,
// element b by -F at A; the φ rows are the moments h·e × F (paper eq. 7's M^Ltra, M^Rtra).
//
// Jacobian (6×6 for the pair):
//   ∂Q/∂q = -k·Dᵀ·G·D - c·Dᵀ·Ḋ - diag(0,0, h·e_a·F, 0,0, h·e_b·F)
//   ∂Q/∂v = -c·DᵀD
// with G = ∂g/∂d = |d|^(e-1)·(I + (e-1)·d̂d̂ᵀ), Ḋ = ∂ḋ/∂q: zero but for the φ columns,
// h·ω_a·e_a and h·ω_b·e_b (from ∂e'/∂φ = -e); the last term is -(∂Dᵀ/∂φ)·F with ∂e'/∂φ = -e.
//
// Potential k·|d|^(e+1)/(e+1); dissipated power c·|ḋ|².
//
// D is never formed: with A = -h·e'_a and B = -h·e'_b, D = [-I | A | I | B], so
//   ḋ = V_b - V_a + ω_a·A + ω_b·B,   Q = (F, -A·F | -F, -B·F),
// and for a symmetric 2×2 M the four 3×3 blocks of Dᵀ·M·D (rows and columns (x, y, φ) of a, b) are
//   (a,a) = [ M  -MA ; -(MA)ᵀ  A·MA ]     (a,b) = [ -M  -MB ; (MA)ᵀ  A·MB ]
//   (b,a) = [ -M  MA ; -(MB)ᵀ  A·MB ]     (b,b) = [ M  MB ; (MB)ᵀ  B·MB ]
// (M = k·G for K, c·I for C), written straight into the block rows; the φ columns of Dᵀ·Ḋ are
// Dᵀ·e = (-e, A·e | e, B·e) for e = e_a, e_b. This costs about a fifth fewer machine instructions
// per element than forming the dense 2×6 D and its 6×6 products, for the forces and for the
// Jacobian (callgrind over `beltsim wp` of the dry second; the sine and cosine of the element's
// angle are about 150 of each).
#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <type_traits>

#include "model/forces.hpp"

namespace beltsim {
namespace {

struct Pair {
  int a, b;
  double h;
  Vec2 ea, eb, d, dd;  // axes, gap, gap rate
  Vec2 A, B;           // D's φ columns, -h·e'_a and -h·e'_b
};

// the axis of element k, from the memo (brought up to date for the span by AxisMemo::update);
// an element outside `own` (a half of the belt evaluating its edge pair) is the other half's
template <class Own>
inline Vec2 element_axis(const double* q, int k, const AxisMemo* memo, const Own& own) {
  if (!memo || !own.owns(k)) return axis(q[3 * k + 2]);
  return {memo->c[k], memo->s[k]};
}

// ea: the axis of element i-1 when the caller has it (loops over the SDEs in order pass the
// previous pair's eb, which halves the sines and cosines)
// (always inlined: called out of line, its overhead took back what the memo saved)
template <class Own = WholeBelt>
[[gnu::always_inline]] inline Pair make_pair(const Model& m, const double* q, const double* v, int i,
                                             const Vec2* ea = nullptr, AxisMemo* memo = nullptr,
                                             const Own& own = Own{}) {
  const int n = m.belt.n;
  Pair s;
  s.a = before(i, n);
  s.b = i;
  s.h = 0.5 * m.belt.rigid_length;
  const double* qa = q + 3 * s.a;
  const double* qb = q + 3 * s.b;
  s.ea = ea ? *ea : element_axis(q, s.a, memo, own);
  s.eb = element_axis(q, s.b, memo, own);
  s.d = Vec2(qb[0] - qa[0], qb[1] - qa[1]) - s.h * (s.ea + s.eb);
  s.A = -s.h * perp(s.ea);
  s.B = -s.h * perp(s.eb);
  if (v) {
    const double* va = v + 3 * s.a;
    const double* vb = v + 3 * s.b;
    s.dd = Vec2(vb[0] - va[0], vb[1] - va[1]) + va[2] * s.A + vb[2] * s.B;
  } else {
    s.dd.setZero();
  }
  return s;
}

// adds w·Dᵀ·M·D (M symmetric 2×2) to the pair's four blocks of J (formulas at the top), entry by
// entry in place (a 3×3 temporary per block would cost about 5 % of the dry drive's time);
// row_a, row_b: whether the block rows of elements a and b are written
void add_dtmd(BlockMatrix& J, const Pair& s, double w, const Eigen::Matrix2d& M, bool row_a, bool row_b) {
  const Vec2 MA = w * (M * s.A), MB = w * (M * s.B);
  const double m00 = w * M(0, 0), m01 = w * M(0, 1), m11 = w * M(1, 1);
  const double amb = s.A.dot(MB);
  // rows (x, y, φ) of block X get (r0; r1; r2), each row three columns
  auto add = [](Mat3& X, double a00, double a01, double a02, double a10, double a11, double a12, double a20,
                double a21, double a22) {
    X(0, 0) += a00, X(0, 1) += a01, X(0, 2) += a02;
    X(1, 0) += a10, X(1, 1) += a11, X(1, 2) += a12;
    X(2, 0) += a20, X(2, 1) += a21, X(2, 2) += a22;
  };
  if (row_a) {
    add(J.diag[s.a], m00, m01, -MA.x(), m01, m11, -MA.y(), -MA.x(), -MA.y(), s.A.dot(MA));
    add(J.upper[s.a], -m00, -m01, -MB.x(), -m01, -m11, -MB.y(), MA.x(), MA.y(), amb);
  }
  if (row_b) {
    add(J.lower[s.b], -m00, -m01, MA.x(), -m01, -m11, MA.y(), -MB.x(), -MB.y(), amb);
    add(J.diag[s.b], m00, m01, MB.x(), m01, m11, MB.y(), MB.x(), MB.y(), s.B.dot(MB));
  }
}

// spring part k·g(d)
Vec2 spring(const Belt& b, const Vec2& d) {
  if (b.e_tra == 1.0) return b.k * d;
  const double r = d.norm();
  return r > 0 ? Vec2(b.k * std::pow(r, b.e_tra - 1.0) * d) : Vec2::Zero();
}

}  // namespace

void AxisMemo::update(const double* q, int lo, int hi) {
  // the angles of the last update, bit for bit (sde_jacobian at the state sde_forces has just
  // read): the axes stand; a changed angle is usually the first one, so the test costs little
  int same = lo;
  while (same < hi && std::bit_cast<std::uint64_t>(q[3 * same + 2]) == std::bit_cast<std::uint64_t>(phi[same])) ++same;
  if (same == hi) return;
  for (int k = lo; k < hi; ++k) {
    const double a = q[3 * k + 2], ga = axis_anchor(a);
    phi[k] = a;
    // (a new anchor also when only a zero's sign changes: sin(-0.0) is -0.0; a NaN angle: NaN)
    if (ga != g[k] || std::signbit(ga) != std::signbit(g[k])) g[k] = ga, cg[k] = std::cos(ga), sg[k] = std::sin(ga);
  }
  const double* __restrict pk = phi.data(), * __restrict gk = g.data(), * __restrict ck = cg.data(), * __restrict sk = sg.data();
  double* __restrict co = c.data(), * __restrict si = s.data();
  for (int k = lo; k < hi; ++k) {  // (no branch: vectorised)
    double ek, fk;
    turn_off_anchor(ck[k], sk[k], pk[k] - gk[k], ek, fk);
    co[k] = ek, si[k] = fk;
  }
  for (int k = lo; k < hi; ++k)  // turn's case of an angle on its anchor
    if (pk[k] == gk[k]) co[k] = ck[k], si[k] = sk[k];
}

Vec2 sde_gap(const Model& m, const double* q, int i) { return make_pair(m, q, nullptr, i).d; }

int sde_nearest(const Model& m, const double* q, const Vec2& point) {
  int best = 0;
  sde_nearest(m, q, &point, 1, &best);
  return best;
}

void sde_nearest(const Model& m, const double* q, const Vec2* points, int count, int* out) {
  constexpr int kBatch = 8;  // points per pass, their best distances in registers
  for (int k0 = 0; k0 < count; k0 += kBatch) {
    const int nk = std::min(kBatch, count - k0);
    double bd[kBatch];
    for (int k = 0; k < nk; ++k) bd[k] = std::numeric_limits<double>::max(), out[k0 + k] = 0;
    const int n = m.belt.n;
    for (int i = 0, a = n - 1; i < n; a = i++) {  // SDE i joins elements a = i - 1 (mod n) and i
      const Vec2 c(0.5 * (q[3 * a] + q[3 * i]), 0.5 * (q[3 * a + 1] + q[3 * i + 1]));
      for (int k = 0; k < nk; ++k) {
        const double d = (c - points[k0 + k]).squaredNorm();
        if (d < bd[k]) bd[k] = d, out[k0 + k] = i;
      }
    }
  }
}

namespace {
// tension is positive when the force pulls the two ends together, along the belt's direction
double axial_force(const Belt& b, const Pair& s) {
  const Vec2 F = spring(b, s.d) + b.c * s.dd;
  return F.dot((s.ea + s.eb).normalized());
}
}  // namespace

double sde_axial_force(const Model& m, const double* q, const double* v, int i) {
  return axial_force(m.belt, make_pair(m, q, v, i));
}

void sde_axial_forces(const Model& m, const double* q, const double* v, double* out) {
  Vec2 prev;
  for (int i = 0; i < m.belt.n; ++i) {
    const Pair s = make_pair(m, q, v, i, i > 0 ? &prev : nullptr);
    prev = s.eb;
    out[i] = axial_force(m.belt, s);
  }
}

void sde_forces(const Model& m, const double* q, const double* v, double* f, double* e_rate, AxisMemo* memo,
                const Span& span) {
  const Belt& b = m.belt;
  if (memo) memo->update(q, span.lo, span.hi);
  Vec2 prev;
  int prev_i = -2;  // the pair whose eb is in prev
  for_pairs(b.n, span, [&](int i, const auto& own) __attribute__((always_inline)) {
    constexpr bool whole = std::is_same_v<std::decay_t<decltype(own)>, WholeBelt>;
    const Pair s = make_pair(m, q, v, i, i > 0 && (whole || prev_i == i - 1) ? &prev : nullptr, memo, own);
    prev = s.eb;
    if constexpr (!whole) prev_i = i;
    const Vec2 F = spring(b, s.d) + b.c * s.dd;
    if (own.owns(s.a)) {
      double* fa = f + 3 * s.a;
      fa[0] += F.x(), fa[1] += F.y(), fa[2] -= s.A.dot(F);
    }
    if (own.owns(s.b)) {  // a pair belongs to its end b, as its power does
      double* fb = f + 3 * s.b;
      fb[0] -= F.x(), fb[1] -= F.y(), fb[2] -= s.B.dot(F);
      if (e_rate) e_rate[kDissSdeAxial] += b.c * s.dd.squaredNorm();
    }
  });
}

void sde_jacobian(const Model& m, const double* q, const double* v, BlockMatrix& K, BlockMatrix& C, AxisMemo* memo,
                  const Span& span) {
  const Belt& b = m.belt;
  if (memo) memo->update(q, span.lo, span.hi);
  Vec2 prev;
  int prev_i = -2;
  for_pairs(b.n, span, [&](int i, const auto& own) __attribute__((always_inline)) {
    constexpr bool whole = std::is_same_v<std::decay_t<decltype(own)>, WholeBelt>;
    const Pair s = make_pair(m, q, v, i, i > 0 && (whole || prev_i == i - 1) ? &prev : nullptr, memo, own);
    prev = s.eb;
    if constexpr (!whole) prev_i = i;
    const bool ra = own.owns(s.a), rb = own.owns(s.b);
    Eigen::Matrix2d G = Eigen::Matrix2d::Identity();
    if (b.e_tra != 1.0) {
      const double r = s.d.norm();
      if (r > 0) {
        const Vec2 u = s.d / r;
        G = std::pow(r, b.e_tra - 1.0) * (Eigen::Matrix2d::Identity() + (b.e_tra - 1.0) * u * u.transpose());
      } else {
        G.setZero();
      }
    }
    const Vec2 F = spring(b, s.d) + b.c * s.dd;
    add_dtmd(K, s, -b.k, G, ra, rb);
    add_dtmd(C, s, -b.c, Eigen::Matrix2d::Identity(), ra, rb);
    // -c·Dᵀ·Ḋ: Ḋ has only its two φ columns, h·ω_a·e_a and h·ω_b·e_b
    const double ga = b.c * s.h * v[3 * s.a + 2], gb = b.c * s.h * v[3 * s.b + 2];
    if (ra) K.diag[s.a].col(2) -= ga * Eigen::Vector3d(-s.ea.x(), -s.ea.y(), s.A.dot(s.ea));
    if (rb) K.lower[s.b].col(2) -= ga * Eigen::Vector3d(s.ea.x(), s.ea.y(), s.B.dot(s.ea));
    if (ra) K.upper[s.a].col(2) -= gb * Eigen::Vector3d(-s.eb.x(), -s.eb.y(), s.A.dot(s.eb));
    if (rb) K.diag[s.b].col(2) -= gb * Eigen::Vector3d(s.eb.x(), s.eb.y(), s.B.dot(s.eb));
    if (ra) K.diag[s.a](2, 2) -= s.h * s.ea.dot(F);
    if (rb) K.diag[s.b](2, 2) -= s.h * s.eb.dot(F);
  });
}

double sde_potential(const Model& m, const double* q) {
  const Belt& b = m.belt;
  double u = 0;
  Vec2 prev;
  for (int i = 0; i < b.n; ++i) {
    const Pair s = make_pair(m, q, nullptr, i, i > 0 ? &prev : nullptr);
    prev = s.eb;
    const double r2 = s.d.squaredNorm();
    u += b.e_tra == 1.0 ? 0.5 * b.k * r2 : b.k * std::pow(std::sqrt(r2), b.e_tra + 1.0) / (b.e_tra + 1.0);
  }
  return u;
}

}  // namespace beltsim
