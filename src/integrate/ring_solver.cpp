#include "integrate/ring_solver.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/LU>

namespace beltsim {

void RingSolver::resize(int n, int np) {
  n_ = n, np_ = np;
  const bool split = n >= kHalvesElements;
  nb_ = split ? 2 : 1;
  border_[0] = 0, border_[1] = split ? half_start(n) : 0;
  mb_ = 3 * nb_ + np;
  chains_.assign(nb_, Chain{});
  if (split) {
    chains_[0].first = 1, chains_[0].len = border_[1] - 1;
    chains_[1].first = border_[1] + 1, chains_[1].len = n - border_[1] - 1;
  } else {
    chains_[0].first = 1, chains_[0].len = n - 1;
  }
  for (Chain& ch : chains_) {
    const int l = ch.len;
    ch.Dinv.resize(l), ch.Lam.resize(l), ch.U.resize(l);
    ch.F.setZero(mb_, 3 * l), ch.Y.resize(3 * l, mb_);
    ch.z.resize(3 * l);
    ch.f_lo.assign(np, 0), ch.f_hi.assign(np, 0);
    ch.start.resize(mb_);
    if (split) ch.FY.resize(mb_, mb_), ch.Fz.resize(mb_);
  }
  G_.resize(mb_, mb_), rb_.resize(mb_), xb_.resize(mb_);
}

int RingSolver::border_of(int i) const {
  for (int k = 0; k < nb_; ++k)
    if (border_[k] == i) return k;
  return -1;
}

template <class F>
void RingSolver::each_chain(F&& f) {
  if (nb_ == 2 && two_)
    two_->run([&](int p) { f(chains_[p]); });
  else
    for (Chain& ch : chains_) f(ch);
}

bool RingSolver::factor_chain(Chain& ch, const Model& m, double alpha, double beta, const BlockMatrix& C,
                              const BlockMatrix& K) const {
  const int n = n_, np = np_, nt = ch.len, mb = mb_, pb = 3 * nb_;
  const Mat3 Mel = Eigen::Vector3d(m.belt.mass, m.belt.mass, m.belt.rot_inertia).asDiagonal();
  auto block = [&](const Mat3& c, const Mat3& k) -> Mat3 { return -beta * c - k; };
  auto elem = [&](int t) { return ch.first + t; };

  // couplings to the border, E written into Y (Y = T⁻¹·E in place below): the chain's first
  // element to its left neighbour, its last to its right one (both border elements). E's columns
  // are written whole. F stays zero but where a factorisation writes it: its border elements' rows
  // in the first and last blocks (the only blocks f_times reads of them) and its pulley rows
  // between f_lo and f_hi, which are cleared before they are written again (clearing whole rows
  // of the column-major F took a memset per column)
  Eigen::MatrixXd& E = ch.Y;
  if (nb_ == 1) {  // fixed sizes
    E.leftCols<3>().setZero();
    ch.F.topLeftCorner<3, 3>().setZero();
    ch.F.topRightCorner<3, 3>().setZero();
  } else {
    E.leftCols<6>().setZero();
    ch.F.topLeftCorner<6, 3>().setZero();
    ch.F.topRightCorner<6, 3>().setZero();
  }
  const int a = elem(0), b = elem(nt - 1);
  const int left = before(a, n), right = after(b, n);
  const int ka = border_of(left), kb = border_of(right);
  ch.F.block<3, 3>(3 * ka, 0) += block(C.upper[left], K.upper[left]);
  ch.F.block<3, 3>(3 * kb, 3 * (nt - 1)) += block(C.lower[right], K.lower[right]);
  E.block<3, 3>(0, 3 * ka) += block(C.lower[a], K.lower[a]);
  E.block<3, 3>(3 * (nt - 1), 3 * kb) += block(C.upper[b], K.upper[b]);
  // E's pulley columns and F's pulley rows, and the blocks where each is non-zero: zero but where
  // C or K marks an element's border entries (BlockMatrix::border_cols)
  E.rightCols(np).setZero();
  for (int j = 0; j < np; ++j) ch.F.row(pb + j).segment(3 * ch.f_lo[j], 3 * (ch.f_hi[j] - ch.f_lo[j])).setZero();
  for (int j = 0; j < np; ++j) ch.start[pb + j] = nt, ch.f_lo[j] = nt, ch.f_hi[j] = 0;
  for (int t = 0; t < nt; ++t) {
    BlockMatrix::each_col(C.border_cols[elem(t)] | K.border_cols[elem(t)], np, [&](int j) {
      bool e_nz = false, f_nz = false;
      for (int r = 0; r < 3; ++r) {
        const int row = 3 * elem(t) + r;
        const double e = -beta * C.elem_pulley(row, j) - K.elem_pulley(row, j);
        const double f = -beta * C.pulley_elem(j, row) - K.pulley_elem(j, row);
        E(3 * t + r, pb + j) = e;
        ch.F(pb + j, 3 * t + r) = f;
        e_nz |= e != 0, f_nz |= f != 0;
      }
      if (e_nz) ch.start[pb + j] = std::min(ch.start[pb + j], t);
      if (f_nz) ch.f_lo[j] = std::min(ch.f_lo[j], t), ch.f_hi[j] = t + 1;
    });
  }
  for (int j = 0; j < np; ++j) ch.f_hi[j] = std::max(ch.f_hi[j], ch.f_lo[j]);
  // the border elements' columns of E: the left neighbour's in the first block, the right one's
  // in the last
  for (int k = 0; k < nb_; ++k)
    for (int c = 0; c < 3; ++c) ch.start[3 * k + c] = k == ka ? 0 : k == kb ? nt - 1 : nt;

  // block Thomas on the chain
  for (int t = 0; t < nt; ++t) {
    const int i = elem(t);
    Mat3 D = alpha * Mel + block(C.diag[i], K.diag[i]);
    if (t > 0) {
      const Mat3 L = block(C.lower[i], K.lower[i]);
      ch.Lam[t] = L * ch.Dinv[t - 1];
      D -= ch.Lam[t] * ch.U[t - 1];
    }
    // closed-form 3×3 inverse (cofactors): the blocks are diagonally dominant (see the header),
    // so no pivoting is needed, and this is several times cheaper than an LU with a solve
    bool invertible = false;
    double det = 0;
    D.computeInverseAndDetWithCheck(ch.Dinv[t], det, invertible, 0.0);
    if (!invertible || !std::isfinite(det) || std::abs(det) <= 1e-300) return false;
    ch.U[t] = (t + 1 < nt) ? block(C.upper[i], K.upper[i]) : Mat3::Zero();
  }
  // Y = T⁻¹·E, each column's forward sweep from its first non-zero block (a pulley's column from
  // its wrap; split, the border element after the chain from the last block)
  solve_T(ch, ch.Y.data(), mb, 3 * nt, ch.start.data());
  if (nb_ == 2) f_times(ch, ch.Y, ch.FY, false);
  return true;
}

bool RingSolver::factor(const Model& m, const Drive& d, double alpha, double beta, const BlockMatrix& C, const BlockMatrix& K,
                        TwoWay* two) {
  const int n = m.n_el(), np = m.n_border();  // the pulleys, the tensioner arms and the coupled rotors
  if (n != n_ || np != np_) resize(n, np);
  two_ = two;
  const int pb = 3 * nb_;
  const Mat3 Mel = Eigen::Vector3d(m.belt.mass, m.belt.mass, m.belt.rot_inertia).asDiagonal();
  auto block = [&](const Mat3& c, const Mat3& k) -> Mat3 { return -beta * c - k; };

  // G: the border elements (not neighbours of each other when split) and the pulleys
  G_.setZero();
  for (int k = 0; k < nb_; ++k) {
    const int e = border_[k];
    G_.block<3, 3>(3 * k, 3 * k) = alpha * Mel + block(C.diag[e], K.diag[e]);
  }
  for (int j = 0; j < np; ++j) {
    for (int k = 0; k < nb_; ++k)
      for (int r = 0; r < 3; ++r) {
        const int row = 3 * border_[k] + r;
        G_(3 * k + r, pb + j) = -beta * C.elem_pulley(row, j) - K.elem_pulley(row, j);
        G_(pb + j, 3 * k + r) = -beta * C.pulley_elem(j, row) - K.pulley_elem(j, row);
      }
    for (int l = 0; l < np; ++l) G_(pb + j, pb + l) = -beta * C.pulley_pulley(j, l) - K.pulley_pulley(j, l);
    G_(pb + j, pb + j) += alpha * d.mass(m, 3 * n + j);
  }

  each_chain([&](Chain& ch) { ch.ok = factor_chain(ch, m, alpha, beta, C, K); });
  for (const Chain& ch : chains_)
    if (!ch.ok) return false;
  // S = G - F·Y in place
  if (nb_ == 1) {
    f_times(chains_[0], chains_[0].Y, G_, true);
  } else {
    for (const Chain& ch : chains_) G_ -= ch.FY;
  }
  S_.compute(G_);
  return std::isfinite(S_.matrixLU().norm()) && std::abs(S_.determinant()) > 0;
}

void RingSolver::solve_T(const Chain& ch, double* z, int cols, int stride, const int* start) {
  const int nt = ch.len;
  using V3 = Eigen::Map<Eigen::Vector3d>;
  auto first = [&](int c) { return start ? start[c] : 0; };
  // the columns side by side, block by block: each column's arithmetic is that of a lone sweep,
  // but the independent columns overlap in the pipeline (a lone sweep waits on its previous block)
  for (int t = 1; t < nt; ++t)
    for (int c = 0; c < cols; ++c) {
      if (t <= first(c)) continue;
      double* zc = z + c * stride;
      V3(zc + 3 * t) -= ch.Lam[t] * V3(zc + 3 * (t - 1));
    }
  for (int c = 0; c < cols; ++c) {
    if (first(c) >= nt) continue;  // a zero column stays zero
    double* zc = z + c * stride;
    V3(zc + 3 * (nt - 1)) = ch.Dinv[nt - 1] * V3(zc + 3 * (nt - 1)).eval();
  }
  for (int t = nt - 2; t >= 0; --t)
    for (int c = 0; c < cols; ++c) {
      if (first(c) >= nt) continue;
      double* zc = z + c * stride;
      V3(zc + 3 * t) = ch.Dinv[t] * (V3(zc + 3 * t) - ch.U[t] * V3(zc + 3 * (t + 1)));
    }
}

template <class X, class Out>
void RingSolver::f_times(const Chain& ch, const X& x, Out&& out, bool subtract) const {
  const int pb = 3 * nb_, nt = ch.len;
  const double sign = subtract ? -1.0 : 1.0;
  // the border elements' rows: their neighbours are the chain's first and last elements
  if (!subtract) out.topRows(pb).setZero();
  out.topRows(pb).noalias() += sign * (ch.F.topLeftCorner(pb, 3) * x.topRows(3));
  if (nt > 1) out.topRows(pb).noalias() += sign * (ch.F.topRightCorner(pb, 3) * x.bottomRows(3));
  for (int j = 0; j < np_; ++j) {
    const int lo = ch.f_lo[j], len = ch.f_hi[j] - lo;
    if (!subtract) out.row(pb + j).setZero();
    if (len > 0)
      out.row(pb + j).noalias() += sign * (ch.F.row(pb + j).segment(3 * lo, 3 * len) * x.middleRows(3 * lo, 3 * len));
  }
}

void RingSolver::solve(const double* r, double* x) {
  const int pb = 3 * nb_;
  // border right-hand side: the border elements first, then the pulleys
  for (int k = 0; k < nb_; ++k)
    for (int c = 0; c < 3; ++c) rb_[3 * k + c] = r[3 * border_[k] + c];
  for (int j = 0; j < np_; ++j) rb_[pb + j] = r[3 * n_ + j];
  if (nb_ == 1) {  // one chain: the unsplit solver's arithmetic, subtracting F·z in one product
    Chain& ch = chains_[0];
    for (int k = 0; k < 3 * ch.len; ++k) ch.z[k] = r[3 * ch.first + k];
    solve_T(ch, ch.z.data());
    f_times(ch, ch.z, rb_, true);
  } else {
    each_chain([&](Chain& ch) {
      for (int k = 0; k < 3 * ch.len; ++k) ch.z[k] = r[3 * ch.first + k];
      solve_T(ch, ch.z.data());
      f_times(ch, ch.z, ch.Fz, false);
    });
    for (const Chain& ch : chains_) rb_ -= ch.Fz;
  }
  xb_ = S_.solve(rb_);  // into a kept vector: the step loop allocates nothing
  const Eigen::VectorXd& xb = xb_;
  auto finish = [&](Chain& ch) {
    ch.z.noalias() -= ch.Y * xb;
    for (int k = 0; k < 3 * ch.len; ++k) x[3 * ch.first + k] = ch.z[k];
  };
  if (nb_ == 1)
    finish(chains_[0]);
  else
    each_chain(finish);
  for (int k = 0; k < nb_; ++k)
    for (int c = 0; c < 3; ++c) x[3 * border_[k] + c] = xb[3 * k + c];
  for (int j = 0; j < np_; ++j) x[3 * n_ + j] = xb[pb + j];
}

}  // namespace beltsim
