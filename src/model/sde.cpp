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
#include <cmath>
#include <limits>

#include "model/forces.hpp"

namespace beltsim {
namespace {

struct Pair {
  int a, b;
  double h;
  Vec2 ea, eb, d, dd;  // axes, gap, gap rate
  Eigen::Matrix<double, 2, 6> D;
};

// ea: the axis of element i-1 when the caller has it (loops over the SDEs in order pass the
// previous pair's eb, which halves the sines and cosines)
Pair make_pair(const Model& m, const double* q, const double* v, int i, const Vec2* ea = nullptr) {
  const int n = m.belt.n;
  Pair s;
  s.a = (i + n - 1) % n;
  s.b = i;
  s.h = 0.5 * m.belt.rigid_length;
  const double* qa = q + 3 * s.a;
  const double* qb = q + 3 * s.b;
  s.ea = ea ? *ea : axis(qa[2]);
  s.eb = axis(qb[2]);
  s.d = Vec2(qb[0] - qa[0], qb[1] - qa[1]) - s.h * (s.ea + s.eb);
  s.D.setZero();
  s.D.block<2, 2>(0, 0) = -Eigen::Matrix2d::Identity();
  s.D.col(2) = -s.h * perp(s.ea);
  s.D.block<2, 2>(0, 3) = Eigen::Matrix2d::Identity();
  s.D.col(5) = -s.h * perp(s.eb);
  if (v) {
    Eigen::Matrix<double, 6, 1> vab;
    vab << v[3 * s.a], v[3 * s.a + 1], v[3 * s.a + 2], v[3 * s.b], v[3 * s.b + 1], v[3 * s.b + 2];
    s.dd = s.D * vab;
  } else {
    s.dd.setZero();
  }
  return s;
}

// spring part k·g(d)
Vec2 spring(const Belt& b, const Vec2& d) {
  if (b.e_tra == 1.0) return b.k * d;
  const double r = d.norm();
  return r > 0 ? Vec2(b.k * std::pow(r, b.e_tra - 1.0) * d) : Vec2::Zero();
}

}  // namespace

Vec2 sde_gap(const Model& m, const double* q, int i) { return make_pair(m, q, nullptr, i).d; }

int sde_nearest(const Model& m, const double* q, const Vec2& point) {
  const int n = m.belt.n;
  int best = 0;
  double bd = std::numeric_limits<double>::max();
  for (int i = 0; i < n; ++i) {
    const int a = (i + n - 1) % n;
    const Vec2 c(0.5 * (q[3 * a] + q[3 * i]), 0.5 * (q[3 * a + 1] + q[3 * i + 1]));
    const double d = (c - point).squaredNorm();
    if (d < bd) bd = d, best = i;
  }
  return best;
}

double sde_axial_force(const Model& m, const double* q, const double* v, int i) {
  const Pair s = make_pair(m, q, v, i);
  const Vec2 F = spring(m.belt, s.d) + m.belt.c * s.dd;
  // tension is positive when the force pulls the two ends together, along the belt's direction
  const Vec2 dir = (s.ea + s.eb).normalized();
  return F.dot(dir);
}

void sde_forces(const Model& m, const double* q, const double* v, double* f, double* e_rate) {
  const Belt& b = m.belt;
  Vec2 prev;
  for (int i = 0; i < b.n; ++i) {
    const Pair s = make_pair(m, q, v, i, i > 0 ? &prev : nullptr);
    prev = s.eb;
    const Vec2 F = spring(b, s.d) + b.c * s.dd;
    const Eigen::Matrix<double, 6, 1> Q = -s.D.transpose() * F;
    for (int k = 0; k < 3; ++k) {
      f[3 * s.a + k] += Q[k];
      f[3 * s.b + k] += Q[3 + k];
    }
    if (e_rate) e_rate[kDissSdeAxial] += b.c * s.dd.squaredNorm();
  }
}

void sde_jacobian(const Model& m, const double* q, const double* v, BlockMatrix& K, BlockMatrix& C) {
  const Belt& b = m.belt;
  Vec2 prev;
  for (int i = 0; i < b.n; ++i) {
    const Pair s = make_pair(m, q, v, i, i > 0 ? &prev : nullptr);
    prev = s.eb;
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
    const Eigen::Matrix<double, 6, 6> DtD = s.D.transpose() * s.D;
    Eigen::Matrix<double, 6, 6> Kl;
    if (b.e_tra == 1.0)
      Kl = -b.k * DtD;
    else
      Kl = -b.k * s.D.transpose() * G * s.D;
    // -c·Dᵀ·Ḋ: Ḋ has only its two φ columns
    Kl.col(2) -= (b.c * s.h * v[3 * s.a + 2]) * (s.D.transpose() * s.ea);
    Kl.col(5) -= (b.c * s.h * v[3 * s.b + 2]) * (s.D.transpose() * s.eb);
    Kl(2, 2) -= s.h * s.ea.dot(F);
    Kl(5, 5) -= s.h * s.eb.dot(F);
    K.add_pair(s.a, s.b, Kl);
    C.add_pair(s.a, s.b, -b.c * DtD);
  }
}

double sde_potential(const Model& m, const double* q) {
  const Belt& b = m.belt;
  double u = 0;
  for (int i = 0; i < b.n; ++i) {
    const double r = sde_gap(m, q, i).norm();
    u += b.k * std::pow(r, b.e_tra + 1.0) / (b.e_tra + 1.0);
  }
  return u;
}

}  // namespace beltsim
