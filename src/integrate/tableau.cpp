#include <cmath>
#include "integrate/tableau.hpp"

#include <Eigen/Dense>

namespace beltsim {

const ExplicitTableau& fehlberg45() {
  static const ExplicitTableau t = [] {
    ExplicitTableau f;
    f.c = {0.0, 1.0 / 4, 3.0 / 8, 12.0 / 13, 1.0, 1.0 / 2};
    f.a = {{},
           {1.0 / 4},
           {3.0 / 32, 9.0 / 32},
           {1932.0 / 2197, -7200.0 / 2197, 7296.0 / 2197},
           {439.0 / 216, -8.0, 3680.0 / 513, -845.0 / 4104},
           {-8.0 / 27, 2.0, -3544.0 / 2565, 1859.0 / 4104, -11.0 / 40}};
    // 4th order (propagated) and 5th order (for the estimate)
    f.b = {25.0 / 216, 0.0, 1408.0 / 2565, 2197.0 / 4104, -1.0 / 5, 0.0};
    f.b_hat = {16.0 / 135, 0.0, 6656.0 / 12825, 28561.0 / 56430, -9.0 / 50, 2.0 / 55};
    return f;
  }();
  return t;
}

void RosenbrockTableau::derive() {
  const int s = stages;
  Eigen::MatrixXd G = Eigen::MatrixXd::Zero(s, s), A = G;
  for (int i = 0; i < s; ++i)
    for (int j = 0; j <= i; ++j) {
      G(i, j) = j < static_cast<int>(Gamma[i].size()) ? Gamma[i][j] : 0.0;
      if (j < i) A(i, j) = j < static_cast<int>(alpha[i].size()) ? alpha[i][j] : 0.0;
    }
  for (int i = 0; i < s; ++i) G(i, i) = gamma;
  const Eigen::MatrixXd Gi = G.inverse();
  const Eigen::MatrixXd Ad = A * Gi;
  const Eigen::MatrixXd Cd = Eigen::MatrixXd(Eigen::VectorXd::Constant(s, 1.0 / gamma).asDiagonal()) - Gi;
  Eigen::RowVectorXd bv(s), bh(s);
  for (int i = 0; i < s; ++i) bv[i] = b[i], bh[i] = b_hat[i];
  const Eigen::RowVectorXd mv = bv * Gi, ev = (bv - bh) * Gi;
  a.assign(s, std::vector<double>(s, 0.0));
  c = a;
  m.resize(s), e.resize(s), alpha_sum.resize(s), gamma_sum.resize(s);
  for (int i = 0; i < s; ++i) {
    for (int j = 0; j < i; ++j) a[i][j] = Ad(i, j), c[i][j] = Cd(i, j);
    m[i] = mv[i];
    e[i] = ev[i];
    alpha_sum[i] = A.row(i).sum();
    gamma_sum[i] = G.row(i).sum();
  }
}

const EsdirkTableau& esdirk32() {
  // Kennedy & Carpenter (2003), ESDIRK3(2)4L[2]SA (the implicit half of ARK3(2)4L[2]SA):
  // 4 stages, order 3, embedded order 2, L-stable, stiffly accurate, stage order 2
  static const EsdirkTableau t = [] {
    EsdirkTableau e;
    e.name = "esdirk32", e.order = 3, e.embedded_order = 2;
    const double g = 1767732205903.0 / 4055673282236.0;
    e.stages = 4;
    e.gamma = g;
    e.a = {{0, 0, 0, 0},
           {g, g, 0, 0},
           {2746238789719.0 / 10658868560708.0, -640167445237.0 / 6845629431997.0, g, 0},
           {1471266399579.0 / 7840856788654.0, -4482444167858.0 / 7529755066697.0,
            11266239266428.0 / 11593286722821.0, g}};
    e.b = e.a[3];
    e.b_hat = {2756255671327.0 / 12835298489170.0, -10771552573575.0 / 22201958757719.0,
               9247589265047.0 / 10645013368117.0, 2193209047091.0 / 5459859503100.0};
    e.c = {0.0, 2 * g, 3.0 / 5.0, 1.0};
    return e;
  }();
  return t;
}

const EsdirkTableau& trbdf2() {
  // TR-BDF2 as an ESDIRK (Hosea & Shampine 1996): a trapezoidal stage to 2γ·h, then BDF2 to h.
  // 3 stages of which 2 implicit, order 2, L-stable, stiffly accurate; the companion is of
  // order 3 (the error estimate b - b̂ is that of the order-2 solution)
  static const EsdirkTableau t = [] {
    EsdirkTableau e;
    e.name = "trbdf2", e.order = 2, e.embedded_order = 3;
    const double g = 1 - std::sqrt(2.0) / 2, w = std::sqrt(2.0) / 4;
    e.stages = 3;
    e.gamma = g;
    e.a = {{0, 0, 0}, {g, g, 0}, {w, w, g}};
    e.b = e.a[2];
    e.b_hat = {(1 - w) / 3, (3 * w + 1) / 3, g / 3};
    e.c = {0.0, 2 * g, 1.0};
    e.interior_stages = true;
    return e;
  }();
  return t;
}

const RosenbrockTableau& ros34pw2() {
  // Rang & Angermann (2005), ROS34PW2: 4 stages, order 3, embedded order 2, L-stable,
  // stiffly accurate, a W-method (order kept with an approximate Jacobian)
  static const RosenbrockTableau t = [] {
    RosenbrockTableau r;
    r.stages = 4;
    r.gamma = 4.3586652150845900e-01;
    r.alpha = {{},
               {8.7173304301691801e-01},
               {8.4457060015369423e-01, -1.1299064236484185e-01},
               {0.0, 0.0, 1.0}};
    r.Gamma = {{},
               {-8.7173304301691801e-01},
               {-9.0338057013044082e-01, 5.4180672388095326e-02},
               {2.4212380706095346e-01, -1.2232505839045147e+00, 5.4526025533510214e-01}};
    r.b = {2.4212380706095346e-01, -1.2232505839045147e+00, 1.5452602553351020e+00, 4.3586652150845900e-01};
    r.b_hat = {3.7810903145819369e-01, -9.6042292212423178e-02, 5.0000000000000000e-01, 2.1793326075422950e-01};
    r.derive();
    return r;
  }();
  return t;
}

}  // namespace beltsim
