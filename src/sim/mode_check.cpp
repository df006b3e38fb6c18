#include "sim/mode_check.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <complex>
#include <functional>
#include <vector>

#include "model/block_matrix.hpp"
#include "sim/eigen.hpp"
#include "sim/outputs.hpp"
#include "sim/run_on.hpp"

namespace beltsim {

namespace {

using cplx = std::complex<double>;

// the belt's displacement normal to span k at its middle: where the elements' polygon crosses the
// span's normal line there [m] (NaN when it does not)
double span_middle(const Scene& sc, const Eigen::VectorXd& y, int k) {
  const Route::Span& sp = sc.route.spans[k];
  const Vec2 mid = 0.5 * (sp.from + sp.to), t = (sp.to - sp.from).normalized(), nrm(-t.y(), t.x());
  const int n = sc.model.n_el();
  double best = NAN, near = INFINITY;
  for (int i = 0; i < n; ++i) {
    const int j = after(i, n);
    const Vec2 a(y[3 * i], y[3 * i + 1]), b(y[3 * j], y[3 * j + 1]);
    const double sa = (a - mid).dot(t), sb = (b - mid).dot(t);
    if ((sa <= 0) == (sb <= 0)) continue;
    const double w = sa / (sa - sb), off = ((1 - w) * (a - mid) + w * (b - mid)).dot(nrm);
    if (std::abs(off) < near) near = std::abs(off), best = off;
  }
  return best;
}

// what can be watched in the space-fixed frame: its name, the mode's predicted complex amplitude
// there and how to read it from a state
struct Watch {
  std::string name;
  cplx predicted;
  std::function<double(const Eigen::VectorXd&)> read;
};

Watch where_it_moves(const Scene& sc, const Drive& d, const Eigen::VectorXd& y, const Mode& md) {
  const Model& m = sc.model;
  std::vector<Watch> all;
  auto coordinate = [&](const std::string& name, int k, double lever) {
    all.push_back(
        {name + " angle", md.vector[k] * lever, [k, lever](const Eigen::VectorXd& s) { return s[k] * lever; }});
  };
  for (int j = 0; j < m.n_p(); ++j)
    if (!d.pulleys[j].kinematic) coordinate("pulley_" + m.pulleys[j].name, m.pulley_coord(j), m.pulleys[j].radius);
  for (int a = 0; a < m.n_arm(); ++a)
    coordinate("arm_" + m.pulleys[m.arms[a].pulley].name, m.arm_coord(a), m.arms[a].length);
  for (int c = 0; c < m.n_coupling(); ++c)
    coordinate("rotor_" + m.pulleys[m.couplings[c].pulley].name, m.rotor_coord(c),
               m.pulleys[m.couplings[c].pulley].radius);
  for (int k = 0; k < static_cast<int>(sc.route.spans.size()); ++k) {
    const Route::Span& sp = sc.route.spans[k];
    const Vec2 mid = 0.5 * (sp.from + sp.to), t = (sp.to - sp.from).normalized(), nrm(-t.y(), t.x());
    int near = 0;  // the element (the slot) nearest the middle now
    for (int i = 1; i < m.n_el(); ++i)
      if ((Vec2(y[3 * i], y[3 * i + 1]) - mid).norm() < (Vec2(y[3 * near], y[3 * near + 1]) - mid).norm()) near = i;
    all.push_back({span_name(sc, k) + " middle", md.vector[3 * near] * nrm.x() + md.vector[3 * near + 1] * nrm.y(),
                   [&sc, k](const Eigen::VectorXd& s) { return span_middle(sc, s, k); }});
  }
  return *std::max_element(all.begin(), all.end(), [](const Watch& a, const Watch& b) {
    return std::abs(a.predicted) < std::abs(b.predicted);
  });
}

// Prony: x_k (spacing dt) as a sum of p damped exponentials, by linear prediction in least squares;
// the poles s [1/s] with Im s > 0 and their amplitudes
std::vector<std::pair<cplx, double>> prony(const std::vector<double>& x, double dt, int p) {
  const int K = static_cast<int>(x.size());
  if (K < 2 * p) return {};
  Eigen::MatrixXd A(K - p, p);
  Eigen::VectorXd b(K - p);
  for (int k = p; k < K; ++k) {
    for (int j = 0; j < p; ++j) A(k - p, j) = x[k - 1 - j];
    b[k - p] = x[k];
  }
  const Eigen::VectorXd a = A.colPivHouseholderQr().solve(b);
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(p, p);
  for (int j = 0; j < p; ++j) C(0, j) = a[j];
  for (int j = 1; j < p; ++j) C(j, j - 1) = 1;
  const Eigen::VectorXcd z = eigen_pairs(C, false, false, "prony").values;
  // the amplitudes, each pole's column scaled to norm 1 (a spurious growing pole's column would
  // otherwise be larger than the others by e^(Re s·window) and leave them none)
  Eigen::MatrixXcd V(K, p);
  for (int k = 0; k < K; ++k)
    for (int j = 0; j < p; ++j) V(k, j) = std::pow(z[j], k);
  const Eigen::VectorXd norm = V.colwise().norm().transpose();
  for (int j = 0; j < p; ++j) V.col(j) /= norm[j];
  // V c = x in least squares as the real system [Re V, -Im V; Im V, Re V] [Re c; Im c] = [x; 0], the
  // same minimum: the real QR above again rather than a complex one (9 s more of GCC's time)
  Eigen::MatrixXd R(2 * K, 2 * p);
  R << V.real(), -V.imag(), V.imag(), V.real();
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(2 * K);
  rhs.head(K) = Eigen::VectorXd::Map(x.data(), K);
  const Eigen::VectorXd re_im = R.colPivHouseholderQr().solve(rhs);
  const Eigen::VectorXcd c =
      (re_im.head(p).cast<cplx>() + cplx(0, 1) * re_im.tail(p).cast<cplx>()).cwiseQuotient(norm.cast<cplx>());
  std::vector<std::pair<cplx, double>> out;
  for (int j = 0; j < p; ++j)
    if (z[j].imag() > 0) out.emplace_back(std::log(z[j]) / dt, 2 * std::abs(c[j]));
  return out;
}

// the watched value of a run from (t, y) over `window`, sampled every dt
std::vector<double> watch(const Scene& sc, const Drive& d, double t, const Eigen::VectorXd& y, double window, double dt,
                          double rtol, const Watch& w) {
  std::vector<double> out;
  run_on(sc.model, d, t, y, window, dt, rtol, [&](double, const Eigen::VectorXd& s) { out.push_back(w.read(s)); });
  return out;
}

// one mode's check made ready: where it is watched, the pushed state, the runs' length and samples
struct Plan {
  Watch w;
  Eigen::VectorXd pushed;
  double window = 0;
  double dt = 0;
  int per_passing = 0;  // samples per element passing (a Floquet mode), else 0
};

Plan plan(const Scene& sc, const Drive& d, const Eigen::VectorXd& y, const ModeAnalysis& a, const Mode& md,
          const ModeCheckSettings& s) {
  const Model& m = sc.model;
  Plan p{where_it_moves(sc, d, y, md), y};
  const int N = m.n_coord();
  for (int c = 0; c < 2 * N; ++c) p.pushed[c] += s.push * md.vector[c].real();
  for (int c = 0; c < m.n_bristle(); ++c) p.pushed[m.bristle_offset() + c] += s.push * md.vector[2 * N + c].real();
  p.window = s.periods / md.frequency;
  // samples 40 a period of the mode; of a Floquet mode (a.period > 0) at whole passings too
  p.per_passing = a.period > 0 ? static_cast<int>(std::ceil(a.period * 40 * md.frequency)) : 0;
  p.dt = a.period > 0 ? a.period / p.per_passing : 1 / (40 * md.frequency);
  return p;
}

// the check of mode md from the plain run's and the pushed run's watched values (the pushed run's
// last sample is its window's end, on the grid or off it: left out, as the plain run's samples
// may go on past it)
ModeCheck judge(const Plan& p, const Mode& md, const ModeAnalysis& a, const std::vector<double>& plain,
                const std::vector<double>& moved, const ModeCheckSettings& s) {
  const double dt = p.dt;
  std::vector<double> diff;
  for (size_t i = 0; i + 1 < moved.size() && i < plain.size(); ++i) diff.push_back((moved[i] - plain[i]) / s.push);
  ModeCheck out;
  out.where = p.w.name;
  double err = 0, size = 0;
  auto compare = [&](size_t i) {
    const double predicted = (p.w.predicted * std::exp(md.lambda * (i * dt))).real();
    err += (diff[i] - predicted) * (diff[i] - predicted);
    size += predicted * predicted;
  };
  if (a.period > 0) {
    // a Floquet mode is V·e^{λt} times a motion of the passing's period: exact at whole passings,
    // where the drive stands as it stood; at those over its first period, and at least three
    const double over = std::max(1 / md.frequency, 3 * a.period) * (1 + 1e-9);
    for (size_t i = 0; i < diff.size() && i * dt <= over; i += p.per_passing) compare(i);
  } else {
    for (size_t i = 0; i < diff.size() && i * dt <= 1 / md.frequency; ++i) compare(i);
  }
  out.misfit = size > 0 ? std::sqrt(err / size) : NAN;
  // the strongest oscillation between a quarter and four times the mode's frequency: the largest
  // RMS over the window (a heavily damped pole fitting the first samples' transient may carry a
  // large amplitude but little of the difference)
  double strongest = 0;
  const double span = dt * static_cast<double>(diff.size());
  for (const auto& [pole, amplitude] : prony(diff, dt, 8)) {
    const double f = pole.imag() / (2 * M_PI), x = 2 * pole.real() * span;
    const double rms = amplitude * std::sqrt(std::abs(x) < 1e-9 ? 1.0 : std::expm1(x) / x);
    if (f < 0.25 * md.frequency || f > 4 * md.frequency || rms <= strongest) continue;
    strongest = rms;
    out.frequency = f;
    out.damping = -pole.real() / std::abs(pole);
  }
  out.agrees = out.misfit <= s.max_misfit;
  return out;
}

// y with every pulley's angle brought within ±π by whole turns, a coupled rotor's (and its clutch
// hub's) turned with it, which keeps the coupling's twist: nothing else in the drive depends on a
// pulley's turns (why the runs start there: mode_check.hpp)
Eigen::VectorXd turns_taken_off(const Model& m, Eigen::VectorXd y) {
  for (int j = 0; j < m.n_p(); ++j) {
    const double turns = 2 * M_PI * std::round(y[m.pulley_coord(j)] / (2 * M_PI));
    y[m.pulley_coord(j)] -= turns;
    for (int c = 0; c < m.n_coupling(); ++c) {
      if (m.couplings[c].pulley != j) continue;
      y[m.rotor_coord(c)] -= turns;
      if (m.couplings[c].one_way) y[m.hub_coord(c)] -= turns;
    }
  }
  return y;
}

}  // namespace

std::vector<ModeCheck> check_modes(const Scene& sc, const Drive& d, double t, const Eigen::VectorXd& at,
                                   const ModeAnalysis& a, const std::vector<size_t>& ks, const ModeCheckSettings& s) {
  const Eigen::VectorXd y = turns_taken_off(sc.model, at);
  std::vector<Plan> plans;
  double longest = 0;
  for (size_t k : ks) {
    plans.push_back(plan(sc, d, y, a, a.modes.at(k), s));
    longest = std::max(longest, plans.back().window);
  }
  // one plain run for all the modes, as long as the longest window, each mode's point watched on
  // its own grid (the samples come from the dense output: the run's steps do not depend on them)
  std::vector<std::vector<double>> plain(ks.size());
  std::vector<DriveOptions::Stream> grids;
  for (size_t i = 0; i < ks.size(); ++i)
    grids.push_back({t, plans[i].dt, [&plain, &plans, i](double, const Eigen::VectorXd& st) {
                       plain[i].push_back(plans[i].w.read(st));
                     }});
  if (!ks.empty()) run_on(sc.model, d, t, y, longest, s.rtol, std::move(grids));
  std::vector<ModeCheck> out;
  for (size_t i = 0; i < ks.size(); ++i) {
    const Plan& p = plans[i];
    const std::vector<double> moved = watch(sc, d, t, p.pushed, p.window, p.dt, s.rtol, p.w);
    out.push_back(judge(p, a.modes[ks[i]], a, plain[i], moved, s));
  }
  return out;
}

ModeCheck check_mode(const Scene& sc, const Drive& d, double t, const Eigen::VectorXd& y, const ModeAnalysis& a,
                     size_t k, const ModeCheckSettings& s) {
  return check_modes(sc, d, t, y, a, {k}, s).front();
}

}  // namespace beltsim
