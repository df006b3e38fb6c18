// Torsional spring-damper elements (paper eq. 6): the belt's bending stiffness.
//
// SDE i joins element a = i-1 to element b = i. With the bend Δ = wrap(φ_b - φ_a) in (-π, π]
// (φ grows by 2π per lap of the loop, the spring sees only the bend) and Δ̇ = ω_b - ω_a:
//   M = k_t·s(Δ) + c_t·Δ̇,   s(Δ) = sign(Δ)·|Δ|^e   (e = e_tor >= 1; e = 1: M = k_t·Δ + c_t·Δ̇)
//   Q_φb = -M,   Q_φa = +M
// Jacobian (only φ rows and columns):
//   ∂Q_φb/∂φ_b = -k_t·s'(Δ),  ∂Q_φb/∂φ_a = +k_t·s'(Δ),  s'(Δ) = e·|Δ|^(e-1)
//   ∂Q_φb/∂ω_b = -c_t,        ∂Q_φb/∂ω_a = +c_t;        Q_φa is the negative of each.
// The belt's free shape is straight (Δ = 0); on a pulley of radius R it carries M ≈ EI/R.
// Potential k_t·|Δ|^(e+1)/(e+1); dissipated power c_t·Δ̇².
#include <cmath>

#include "model/forces.hpp"

namespace beltsim {

double wrap_angle(double a) {
  // neighbours' bends are almost always inside (-π, π], where fmod would return a unchanged
  if (a > -M_PI && a <= M_PI) return a;
  constexpr double two_pi = 2.0 * M_PI;
  a = std::fmod(a, two_pi);
  if (a > M_PI) a -= two_pi;
  if (a <= -M_PI) a += two_pi;
  return a;
}

namespace {
double spring(const Belt& b, double delta) {
  if (b.e_tor == 1.0) return b.kt * delta;
  return b.kt * std::copysign(std::pow(std::abs(delta), b.e_tor), delta);
}
double spring_slope(const Belt& b, double delta) {
  if (b.e_tor == 1.0) return b.kt;
  return b.kt * b.e_tor * std::pow(std::abs(delta), b.e_tor - 1.0);
}
}  // namespace

void bending_forces(const Model& m, const double* q, const double* v, double* f, double* e_rate, const Span& span) {
  const Belt& b = m.belt;
  for_pairs(b.n, span, [&](int i, const auto& own) __attribute__((always_inline)) {
    const int a = before(i, b.n);
    const double delta = wrap_angle(q[3 * i + 2] - q[3 * a + 2]);
    const double rate = v[3 * i + 2] - v[3 * a + 2];
    const double M = spring(b, delta) + b.ct * rate;
    if (own.owns(i)) {
      f[3 * i + 2] -= M;
      if (e_rate) e_rate[kDissSdeBending] += b.ct * rate * rate;
    }
    if (own.owns(a)) f[3 * a + 2] += M;
  });
}

void bending_jacobian(const Model& m, const double* q, const double*, BlockMatrix& K, BlockMatrix& C,
                      const Span& span) {
  const Belt& b = m.belt;
  for_pairs(b.n, span, [&](int i, const auto& own) __attribute__((always_inline)) {
    const int a = before(i, b.n);
    const double ks = spring_slope(b, wrap_angle(q[3 * i + 2] - q[3 * a + 2]));
    // only the (φ, φ) entries of the pair's four blocks (the formulas at the top), written in
    // place: adding whole 6×6 pair blocks would make the Jacobian a third slower (BM_Jacobian)
    if (own.owns(a)) {
      K.diag[a](2, 2) -= ks, K.upper[a](2, 2) += ks;
      C.diag[a](2, 2) -= b.ct, C.upper[a](2, 2) += b.ct;
    }
    if (own.owns(i)) {
      K.lower[i](2, 2) += ks, K.diag[i](2, 2) -= ks;
      C.lower[i](2, 2) += b.ct, C.diag[i](2, 2) -= b.ct;
    }
  });
}

double bending_potential(const Model& m, const double* q) {
  const Belt& b = m.belt;
  double u = 0;
  for (int i = 0; i < b.n; ++i) {
    const int a = before(i, b.n);
    const double delta = std::abs(wrap_angle(q[3 * i + 2] - q[3 * a + 2]));
    u += b.e_tor == 1.0 ? 0.5 * b.kt * delta * delta : b.kt * std::pow(delta, b.e_tor + 1.0) / (b.e_tor + 1.0);
  }
  return u;
}

}  // namespace beltsim
