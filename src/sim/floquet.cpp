#include "sim/floquet.hpp"

#include <Eigen/KLUSupport>
#include <Eigen/SparseCore>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "model/rhs.hpp"
#include "model/sparse.hpp"
#include "model/workspace.hpp"
#include "sim/eigen.hpp"
#include "sim/run_on.hpp"

namespace beltsim {

Eigen::SparseMatrix<double> ode_matrix(const Model& m, const Drive& d, double t, const Eigen::VectorXd& y,
                                       const std::vector<int>& keep) {
  Workspace ws(m, false);
  Jacobian J;
  J.resize(m);
  jacobian(m, d, t, y.data(), J, &ws);
  Eigen::SparseMatrix<double> full;
  assemble_ode_jacobian(m, d, J.K, J.C, m.n_bristle() ? &J.B : nullptr, full);
  const int S = static_cast<int>(keep.size());
  std::vector<Eigen::Triplet<double>> tr;
  for (int k = 0; k < S; ++k) tr.emplace_back(k, keep[k], 1.0);
  Eigen::SparseMatrix<double> sel(S, full.rows());
  sel.setFromTriplets(tr.begin(), tr.end());
  return sel * full * sel.transpose();
}

namespace {

using Sparse = Eigen::SparseMatrix<double>;
using cplx = std::complex<double>;

// The kept layout's element rows: q's and v's three per element, z's one. slot(r) is the element
// whose row r is, row(r, i) the same row of element i
struct Layout {
  int n, N;
  bool element(int r) const { return r < 3 * n || (r >= N && r < N + 3 * n) || r >= 2 * N; }
  int slot(int r) const { return r < N ? r / 3 : r < 2 * N ? (r - N) / 3 : r - 2 * N; }
  int row(int r, int i) const { return r < N ? 3 * i + r % 3 : r < 2 * N ? N + 3 * i + (r - N) % 3 : 2 * N + i; }
};

// the drive's own motion from (t0, y0) over T, every T/steps (steps + 1 states)
std::vector<Eigen::VectorXd> passing_motion(const Model& m, const Drive& d, double t0, const Eigen::VectorXd& y0,
                                            double T, int steps) {
  const double h = T / steps;
  std::vector<Eigen::VectorXd> ys;
  double last = -INFINITY;
  run_on(m, d, t0, y0, T, h, 1e-9, [&](double t, const Eigen::VectorXd& y) {
    if (t - last < 0.5 * h) return;  // (t_end's sample when it falls on the grid's last point)
    last = t;
    ys.push_back(y);
  });
  if (static_cast<int>(ys.size()) != steps + 1) throw std::logic_error("floquet: the samples are not the steps");
  return ys;
}

// how far the motion is from repeating itself: element i after the passing against element
// i + step before it, in position (over the pitch) and velocity (over the belt's RMS speed)
void repeat_defects(const Layout& L, int step, double pitch, const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                    FloquetModes& out) {
  double dx = 0, dv = 0, speed = 0;
  for (int i = 0; i < L.n; ++i) {
    const int j = (i + step + L.n) % L.n;
    dx += std::pow(b[3 * i] - a[3 * j], 2) + std::pow(b[3 * i + 1] - a[3 * j + 1], 2);
    dv += std::pow(b[L.N + 3 * i] - a[L.N + 3 * j], 2) + std::pow(b[L.N + 3 * i + 1] - a[L.N + 3 * j + 1], 2);
    speed += std::pow(a[L.N + 3 * i], 2) + std::pow(a[L.N + 3 * i + 1], 2);
  }
  out.position_defect = std::sqrt(dx / L.n) / pitch;
  out.velocity_defect = std::sqrt(dv / speed);
}

// BDF2 on the variational equation along the samples ys (step h): (I − h·J_1)·X_1 = X_0, then
// (I − ⅔h·J_k)·X_k = (4·X_{k−1} − X_{k−2})/3, the factors kept for a second sweep
struct Bdf2 {
  std::vector<std::unique_ptr<Eigen::KLU<Sparse>>> lu;
  Bdf2(const Model& m, const Drive& d, double t0, double h, const std::vector<Eigen::VectorXd>& ys,
       const std::vector<int>& keep) {
    const int S = static_cast<int>(keep.size());
    Sparse I(S, S);
    I.setIdentity();
    lu.resize(ys.size());
    for (size_t k = 1; k < ys.size(); ++k) {
      lu[k] = std::make_unique<Eigen::KLU<Sparse>>();
      lu[k]->compute(Sparse(I - (k == 1 ? h : 2 * h / 3) * ode_matrix(m, d, t0 + k * h, ys[k], keep)));
      if (lu[k]->info() != Eigen::Success) throw std::runtime_error("floquet: a step's matrix is singular");
    }
  }
  int steps() const { return static_cast<int>(lu.size()) - 1; }
  // X (and Xm, the step before) one step on, to step k
  void advance(int k, Eigen::MatrixXd& X, Eigen::MatrixXd& Xm) const {
    Eigen::MatrixXd next = k == 1 ? lu[k]->solve(X) : lu[k]->solve(Eigen::MatrixXd((4 * X - Xm) / 3));
    Xm = std::move(X);
    X = std::move(next);
  }
};

// The turn (radians) of each column of W carried through the passing: the phase of its
// space-fixed reading U against itself, followed step by step. U a fraction s of a passing on: the
// elements have run s of a slot towards slot + step, so slot j lies between element j − step
// (s short of it) and element j (s past it), U_j = (1 − s)·X_j + s·X_{j−step} on the elements'
// rows, X itself on the others. The reading's weights are the kinetic energy's (each velocity's
// mass): ⟨W, U⟩ = (1 − s)·⟨G_e·W, X⟩ + s·⟨G'_e·W, X⟩ + ⟨G_o·W, X⟩, G_e on the elements' rows, G'_e
// the same moved a slot back, G_o on the others.
std::vector<double> turns(const Model& m, const Layout& L, int step, const Bdf2& bdf, const Eigen::MatrixXcd& W) {
  const Eigen::Index S = W.rows(), c = W.cols();
  Eigen::MatrixXcd We = Eigen::MatrixXcd::Zero(S, c), Wb = We, Wo = We;
  for (int r = L.N; r < 2 * L.N; ++r) {
    const double g = m.mass_of(r - L.N);
    if (!L.element(r)) {
      Wo.row(r) = g * W.row(r);
      continue;
    }
    We.row(r) = g * W.row(r);
    Wb.row(L.row(r, (L.slot(r) - step + L.n) % L.n)) = g * W.row(r);
  }
  auto reading = [](const Eigen::MatrixXcd& A, const Eigen::MatrixXd& re, const Eigen::MatrixXd& im) {
    // column by column Σ conj(A)·(re + i·im)
    return Eigen::VectorXcd((A.real().cwiseProduct(re) + A.imag().cwiseProduct(im)).colwise().sum().transpose() +
                            cplx(0, 1) *
                                (A.real().cwiseProduct(im) - A.imag().cwiseProduct(re)).colwise().sum().transpose());
  };
  Eigen::MatrixXd X(S, 2 * c), Xm;
  X << W.real(), W.imag();
  Xm = X;
  std::vector<double> phase(c, 0.0), turned(c, 0.0);
  for (int k = 1; k <= bdf.steps(); ++k) {
    bdf.advance(k, X, Xm);
    const double s = static_cast<double>(k) / bdf.steps();
    const Eigen::MatrixXd re = X.leftCols(c), im = X.rightCols(c);
    const Eigen::VectorXcd p = (1 - s) * reading(We, re, im) + s * reading(Wb, re, im) + reading(Wo, re, im);
    for (Eigen::Index j = 0; j < c; ++j) {
      const double arg = std::arg(p[j]);
      turned[j] += std::remainder(arg - phase[j], 2 * M_PI);
      phase[j] = arg;
    }
  }
  return turned;
}

}  // namespace

FloquetModes floquet_modes(const Scene& sc, const Drive& d, double t0, const Eigen::VectorXd& y0, double nu,
                           double max_decay, const std::vector<int>& keep) {
  if (!(nu != 0) || !std::isfinite(nu)) throw std::invalid_argument("floquet: the belt does not run (nu = 0)");
  const Model& m = sc.model;
  const int S = static_cast<int>(keep.size());
  const Layout L{m.n_el(), m.n_coord()};
  const int step = nu > 0 ? 1 : -1;
  FloquetModes out;
  out.period = 1 / std::abs(nu);
  out.steps = std::max(40, static_cast<int>(std::ceil(out.period * 40 * kFloquetResolution)));
  const double T = out.period;
  const std::vector<Eigen::VectorXd> ys = passing_motion(m, d, t0, y0, T, out.steps);
  repeat_defects(L, step, m.belt.pitch, ys.front(), ys.back(), out);

  // Φ, then M = P·Φ (element i's rows to slot i + step) and its eigen-analysis, balanced
  const Bdf2 bdf(m, d, t0, T / out.steps, ys, keep);
  Eigen::MatrixXd X = Eigen::MatrixXd::Identity(S, S), Xm = X;
  for (int k = 1; k <= out.steps; ++k) bdf.advance(k, X, Xm);
  Eigen::MatrixXd M(S, S);
  for (int r = 0; r < S; ++r) M.row(L.element(r) ? L.row(r, (L.slot(r) + step + L.n) % L.n) : r) = X.row(r);
  const EigenPairs es = eigen_pairs(std::move(M), true, true, "floquet");

  // the candidates: multipliers above rounding and within max_decay, each with its turn
  const double floor = std::max(std::exp(-max_decay * T), 1e-12);
  std::vector<int> cand;
  for (int k = 0; k < S; ++k)
    if (std::abs(es.values[k]) > floor) cand.push_back(k);
  const int c = static_cast<int>(cand.size());
  Eigen::MatrixXcd W(S, c);
  for (int j = 0; j < c; ++j) W.col(j) = es.vectors.col(cand[j]);
  const std::vector<double> turned = turns(m, L, step, bdf, W);
  std::vector<int> kept;
  for (int j = 0; j < c; ++j) {
    const cplx mu = es.values[cand[j]];
    // the turn followed, rounded to arg μ plus whole turns
    const double whole = std::round((turned[j] - std::arg(mu)) / (2 * M_PI));
    const cplx lambda(std::log(std::abs(mu)) / T, (std::arg(mu) + 2 * M_PI * whole) / T);
    if (lambda.imag() <= 0) continue;  // (its conjugate's pair)
    out.lambda.push_back(lambda);
    kept.push_back(j);
  }
  out.vectors.resize(S, static_cast<Eigen::Index>(kept.size()));
  for (size_t o = 0; o < kept.size(); ++o) out.vectors.col(static_cast<Eigen::Index>(o)) = W.col(kept[o]);
  return out;
}

}  // namespace beltsim
