#include "sim/modes.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "model/block_matrix.hpp"
#include "model/contacts.hpp"
#include "model/observables.hpp"
#include "model/workspace.hpp"
#include "sim/eigen.hpp"
#include "sim/floquet.hpp"
#include "sim/outputs.hpp"

namespace beltsim {

namespace {

double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double s = std::clamp((p - a).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
  return (p - (a + s * ab)).norm();
}

// ν: the elements passing a fixed point per second, the mean over the elements of their speed
// along the ring (towards the next element) over their spacing; and the belt's mean speed
void element_rate(const Model& m, const Eigen::VectorXd& y, double& nu, double& speed) {
  const int n = m.n_el(), N = m.n_coord();
  nu = speed = 0;
  for (int i = 0; i < n; ++i) {
    const int a = before(i, n), b = after(i, n);
    const Vec2 chord(y[3 * b] - y[3 * a], y[3 * b + 1] - y[3 * a + 1]);
    const double along = Vec2(y[N + 3 * i], y[N + 3 * i + 1]).dot(chord) / chord.norm();
    speed += along;
    nu += along / (0.5 * chord.norm());
  }
  nu /= n;
  speed /= n;
}

// the size of the displacement each coordinate's unit motion gives a point: 1 for an element's x
// and y (taken together), a pulley's radius, an arm's length, a rotor's pulley's radius; 0 for an
// element's angle (its centre does not move)
double lever(const Model& m, int k) {
  const int ne = 3 * m.n_el();
  if (k < ne) return k % 3 == 2 ? 0.0 : 1.0;
  if (k < ne + m.n_p()) return m.pulleys[k - ne].radius;
  if (k < ne + m.n_p() + m.n_arm()) return m.arms[k - ne - m.n_p()].length;
  for (int c = 0; c < m.n_coupling(); ++c)
    if (k == m.rotor_coord(c) || (m.couplings[c].one_way && k == m.hub_coord(c)))
      return m.pulleys[m.couplings[c].pulley].radius;
  return 0;
}

// eigenvector v scaled so that the largest point displacement is 1 m, real and
// positive in its largest component
Eigen::VectorXcd normalised_shape(const Model& m, const Eigen::VectorXcd& v) {
  const int N = m.n_coord(), ne = 3 * m.n_el();
  const Eigen::VectorXcd q = v.head(N);
  double best = 0;
  int ref = 0;
  for (int k = 0; k < N; ++k) {
    if (k < ne && k % 3 != 0) continue;  // an element's point is looked at once, at its x
    const double size = k < ne ? std::hypot(std::abs(q[k]), std::abs(q[k + 1])) : lever(m, k) * std::abs(q[k]);
    if (size <= best) continue;
    best = size;
    ref = k < ne && std::abs(q[k + 1]) > std::abs(q[k]) ? k + 1 : k;
  }
  if (best == 0) return v;
  const std::complex<double> c = q[ref];
  return v * (std::conj(c) / std::abs(c)) / best;
}

}  // namespace

std::vector<int> coordinate_groups(const Scene& sc, const Drive& d, double t, const Eigen::VectorXd& y,
                                   std::vector<std::string>& names) {
  const Model& m = sc.model;
  const int n = m.n_el(), spans = static_cast<int>(sc.route.spans.size());
  names.clear();
  for (int k = 0; k < spans; ++k) names.push_back(span_name(sc, k));
  for (const Pulley& p : m.pulleys) names.push_back("wrap_" + p.name);
  for (const Pulley& p : m.pulleys) names.push_back("pulley_" + p.name);
  for (const Arm& a : m.arms) names.push_back("arm_" + m.pulleys[a.pulley].name);
  for (const Coupling& c : m.couplings) names.push_back("rotor_" + m.pulleys[c.pulley].name);
  std::vector<int> g(m.n_coord(), -1);
  Workspace ws(m, false);
  const ContactRecords& rec = contacts_at(m, d, t, y.data(), ws);
  for (int i = 0; i < n; ++i) {
    int group = element_contact(rec, i).pulley;
    if (group >= 0) {
      group += spans;
    } else {
      const Vec2 p(y[3 * i], y[3 * i + 1]);
      double near = INFINITY;
      for (int k = 0; k < spans; ++k) {
        const double dist = segment_distance(p, sc.route.spans[k].from, sc.route.spans[k].to);
        if (dist < near) near = dist, group = k;
      }
    }
    for (int r = 0; r < 3; ++r) g[3 * i + r] = group;
  }
  for (int j = 0; j < m.n_p(); ++j)
    if (!d.pulleys[j].kinematic) g[m.pulley_coord(j)] = spans + m.n_p() + j;
  for (int a = 0; a < m.n_arm(); ++a) g[m.arm_coord(a)] = spans + 2 * m.n_p() + a;
  for (int c = 0; c < m.n_coupling(); ++c) {
    g[m.rotor_coord(c)] = spans + 2 * m.n_p() + m.n_arm() + c;
    if (m.couplings[c].one_way) g[m.hub_coord(c)] = g[m.rotor_coord(c)];
  }
  return g;
}

ModeAnalysis analyze_modes(const Scene& sc, const Drive& d, double t, const Eigen::VectorXd& y, const ModeSettings& s) {
  if (!(s.f_min >= 0) || !(s.f_max > s.f_min))
    throw std::invalid_argument("modes: f_min must be >= 0 and below f_max (got " + std::to_string(s.f_min) + " and " +
                                std::to_string(s.f_max) + " Hz)");
  const Model& m = sc.model;
  if (y.size() != m.n_state()) throw std::invalid_argument("modes: the state has the wrong size");
  const int n = m.n_el(), N = m.n_coord(), nz = m.n_bristle();
  ModeAnalysis out;
  out.t = t;
  // the state without the energy integrals: [q | v | z]
  const int S = 2 * N + nz;
  std::vector<int> keep(S);
  for (int k = 0; k < 2 * N; ++k) keep[k] = k;
  for (int k = 0; k < nz; ++k) keep[2 * N + k] = m.bristle_offset() + k;
  double nu = 0;
  element_rate(m, y, nu, out.belt_speed);
  out.states = S;
  // the eigenvalues and eigenvectors: J's own at rest (or in the material frame), the Floquet
  // modes of the motion over one element passing when the belt runs
  std::vector<std::complex<double>> lambdas;
  Eigen::MatrixXcd vectors;
  if (s.transport && s.floquet && std::abs(nu) >= kFloquetRate) {
    out.element_rate = nu;
    // decays up to that of ζ = zeta_max at f_max: a mode it leaves out would be left out below (f
    // above f_max or ζ above zeta_max)
    const double max_decay = 2 * M_PI * s.f_max * s.zeta_max / std::sqrt(1 - s.zeta_max * s.zeta_max);
    FloquetModes fm = floquet_modes(sc, d, t, y, nu, max_decay, keep);
    out.period = fm.period;
    out.position_defect = fm.position_defect;
    out.velocity_defect = fm.velocity_defect;
    lambdas = std::move(fm.lambda);
    vectors = std::move(fm.vectors);
  } else {
    Eigen::MatrixXd A(ode_matrix(m, d, t, y, keep));  // J of the state
    if (s.transport) {
      // −ν·(U_{i+1} − U_{i−1})/2 on every element row of q, v and z
      out.element_rate = nu;
      auto transport = [&](int first, int per) {
        for (int i = 0; i < n; ++i)
          for (int r = 0; r < per; ++r) {
            const int row = first + per * i + r;
            A(row, first + per * after(i, n) + r) -= 0.5 * nu;
            A(row, first + per * before(i, n) + r) += 0.5 * nu;
          }
      };
      transport(0, 3);
      transport(N, 3);
      if (nz) transport(2 * N, 1);
    }
    EigenPairs es = eigen_pairs(std::move(A), true, s.balance, "modes");
    lambdas.assign(es.values.begin(), es.values.end());
    vectors = std::move(es.vectors);
  }
  for (int j = 0; j < m.n_p() && out.forced < 0 && out.period > 0; ++j) {
    const PulleyDrive& p = d.pulleys[j];
    const double omega = d.omega(m, j, t, y.data() + N);
    const TimeSpeedLaw& law = p.kinematic ? p.speed : p.torque;
    // its fastest change within kForcingWindow of t, against its value at t (a ripple's phase at t
    // is not what matters)
    const double value = std::max(std::abs(law.eval(t, omega)), 1e-9);
    double rate = 0;
    for (int k = -20; k <= 20; ++k)
      if (const double tk = t + k * kForcingWindow / 20; tk >= 0)
        rate = std::max(rate, std::abs(law.d_time(tk, omega)) / value);
    if (rate > kForcingRate) out.forced = j, out.forcing_rate = rate;
  }
  const std::vector<int> group = coordinate_groups(sc, d, t, y, out.groups);
  const int G = static_cast<int>(out.groups.size());
  for (size_t k = 0; k < lambdas.size(); ++k) {
    const std::complex<double> lambda = lambdas[k];
    const double f = lambda.imag() / (2 * M_PI);
    if (!(f >= s.f_min && f <= s.f_max)) continue;
    Mode md;
    md.lambda = lambda;
    md.frequency = f;
    md.damping = -lambda.real() / std::abs(lambda);
    if (!(md.damping <= s.zeta_max)) continue;
    const Eigen::VectorXcd v = vectors.col(static_cast<Eigen::Index>(k));
    md.participation.assign(G, 0.0);
    double total = 0;
    for (int c = 0; c < N; ++c) {
      if (group[c] < 0) continue;
      const double e = m.mass_of(c) * std::norm(v[N + c]);
      md.participation[group[c]] += e;
      total += e;
    }
    if (total > 0)
      for (double& p : md.participation) p /= total;
    md.dominant =
        static_cast<int>(std::max_element(md.participation.begin(), md.participation.end()) - md.participation.begin());
    md.vector = normalised_shape(m, v);
    md.shape = md.vector.head(N);
    out.modes.push_back(std::move(md));
  }
  // by frequency, then by damping: modes locked at half the passing rate share their frequency
  // exactly, and their number must not depend on the order the eigensolver gives them in
  std::sort(out.modes.begin(), out.modes.end(), [](const Mode& a, const Mode& b) {
    return a.frequency != b.frequency ? a.frequency < b.frequency : a.damping < b.damping;
  });
  Observation obs;
  observe(m, d, sc.senses(), t, y.data(), obs);
  for (const PulleyObs& p : obs.pulleys) out.slip_arc.push_back(p.slip_arc);
  return out;
}

Eigen::VectorXd mode_state(const Eigen::VectorXd& y, const Mode& m, double amplitude, double phase) {
  Eigen::VectorXd out = y;
  const std::complex<double> turn = std::polar(amplitude, phase);
  for (Eigen::Index k = 0; k < m.shape.size(); ++k) out[k] += (m.shape[k] * turn).real();
  return out;
}

std::vector<std::complex<double>> mode_tension_change(const Scene& sc, const Drive& d, double t,
                                                      const Eigen::VectorXd& y, const Mode& m) {
  constexpr double eps = 1e-7;  // [m] the deflection of the point that moves most
  const std::vector<int> sense = sc.senses();
  // the change per metre along Re(shape·e^{iφ}) (central differences)
  auto along = [&](double phase) {
    Observation up, down;
    observe(sc.model, d, sense, t, mode_state(y, m, eps, phase).data(), up);
    observe(sc.model, d, sense, t, mode_state(y, m, -eps, phase).data(), down);
    std::vector<double> dt(up.elements.size());
    for (size_t k = 0; k < dt.size(); ++k) dt[k] = (up.elements[k].tension - down.elements[k].tension) / (2 * eps);
    return dt;
  };
  // Re(c·e^{iφ}) = Re c·cos φ − Im c·sin φ: Re c the change at φ = 0, −Im c at φ = π/2
  const std::vector<double> at0 = along(0), at90 = along(0.5 * M_PI);
  std::vector<std::complex<double>> c(at0.size());
  double largest = 0;
  for (size_t k = 0; k < c.size(); ++k) largest = std::max(largest, std::abs(c[k] = {at0[k], -at90[k]}));
  if (largest > 0)
    for (auto& ck : c) ck /= largest;
  return c;
}

std::vector<std::string> mode_columns(const ModeAnalysis& a) {
  std::vector<std::string> c{"mode", "frequency_Hz", "damping_ratio", "decay_1_s"};
  for (const std::string& g : a.groups) c.push_back(g);
  return c;
}

std::vector<double> mode_row(const ModeAnalysis& a, size_t k) {
  const Mode& m = a.modes[k];
  std::vector<double> r{static_cast<double>(k + 1), m.frequency, m.damping, -m.lambda.real()};
  r.insert(r.end(), m.participation.begin(), m.participation.end());
  return r;
}

std::string where_text(const std::vector<std::string>& groups, const std::vector<double>& participation) {
  std::vector<std::pair<double, std::string>> g;
  for (size_t k = 0; k < groups.size() && k < participation.size(); ++k) g.emplace_back(participation[k], groups[k]);
  std::stable_sort(g.begin(), g.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  size_t n = 0;
  while (n < g.size() && g[n].first >= kWhereShare) ++n;
  const bool spread = n == 0;
  if (spread) n = std::min(kWhereSpread, g.size());
  std::string s = spread && n > 0 ? "spread: " : "";
  for (size_t k = 0; k < n; ++k) {
    char buf[32];
    std::snprintf(buf, sizeof buf, " %.0f %%", 100 * g[k].first);
    s += (k ? ", " : "") + g[k].second + buf;
  }
  return s;
}

}  // namespace beltsim
