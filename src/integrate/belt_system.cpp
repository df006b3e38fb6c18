#include "integrate/belt_system.hpp"

#include <cmath>
#include <limits>
#include <sstream>

#include "integrate/newton_aids.hpp"
#include "integrate/switches.hpp"
#include "model/sparse.hpp"


namespace beltsim {

BeltSystem::BeltSystem(const Model& m, const Drive& d) : model_(m), drive_(d), ws_(m) { J_.resize(m); }

double BeltSystem::atol_scale(int k) const {
  // natural sizes: 0.1 m (layout), 1 rad, 1 m/s, 10 rad/s (element spin), 1 J
  const int N = model_.n_coord(), ne = 3 * model_.n_el();
  if (k >= 2 * N) return 1.0;
  const bool vel = k >= N;
  const int c = vel ? k - N : k;
  if (c >= ne) return 1.0;  // pulley angle [rad], speed [rad/s]
  if (c % 3 == 2) return vel ? 10.0 : 1.0;
  return vel ? 1.0 : 0.1;
}

double BeltSystem::resolution(int k) const {
  // an element's velocity (x, y) and a pulley's surface speed: the friction band Δv
  const int N = model_.n_coord(), ne = 3 * model_.n_el();
  if (k < N || k >= 2 * N) return std::numeric_limits<double>::infinity();
  const int c = k - N;
  if (c < ne) return c % 3 == 2 ? std::numeric_limits<double>::infinity() : model_.friction.dv;
  return model_.friction.dv / model_.pulleys[c - ne].radius;
}

bool BeltSystem::reseat(double t, double* z, double* dz, bool keep_correction) {
  const int N = model_.n_coord();
  contact_pass(model_, drive_, t, z, z + N, Span{0, model_.n_el()}, pairs_);
  return friction_reseat(model_, drive_, pairs_, z, z + N, dz, dz + N,
                         keep_correction ? Reseat::correction : Reseat::iterate) > 0;
}

bool BeltSystem::local_solve(double t, double s, double* z, const double* g) {
  const int N = model_.n_coord();
  contact_pass(model_, drive_, t, z, z + N, Span{0, model_.n_el()}, pairs_);
  return friction_local_solve(model_, drive_, pairs_, s, z, z + N, g + N) > 0;
}

int BeltSystem::switch_count() const { return beltsim::switch_count(model_); }

void BeltSystem::switches(double t, const double* y, double* g) const {
  contact_pass(model_, drive_, t, y, y + model_.n_coord(), Span{0, model_.n_el()}, pairs_, Pairs::all);
  contact_switches(model_, pairs_, g);
}

void BeltSystem::predict(double t, double dt, double* z) const {
  convective_predict(model_, drive_, t, dt, z, z + model_.n_coord(), predict_);
}

uint64_t BeltSystem::branches(double t, const double* y) const {
  contact_pass(model_, drive_, t, y, y + model_.n_coord(), Span{0, model_.n_el()}, pairs_);
  return contact_branches(model_, pairs_);
}

bool BeltSystem::prepare_jacobian(double t, const double* y) {
  jacobian(model_, drive_, t, y, J_, &ws_);
  return true;
}

void BeltSystem::time_derivative(double* f_t) const {
  const int N = model_.n_coord();
  for (int k = 0; k < N; ++k) f_t[N + k] = J_.f_t[k] / drive_.mass(model_, k);
}

bool BeltSystem::sparse_jacobian(double t, const double* y, Eigen::SparseMatrix<double>& J) {
  jacobian(model_, drive_, t, y, J_, &ws_);
  assemble_ode_jacobian(model_, drive_, J_.K, J_.C, J);
  return true;
}

bool BeltSystem::factor(double s) {
  s_ = s;
  return solver_.factor(model_, drive_, s * s, s, J_.C, J_.K, ws_.halves ? &ws_.halves->two : nullptr);
}

void BeltSystem::solve(const double* r, double* u) {
  const int N = model_.n_coord();
  const double s = s_;
  rhs_.resize(N);
  kr_.resize(N);
  auto rows = [&](int lo, int hi) {
    for (int k = lo; k < hi; ++k) rhs_[k] = s * drive_.mass(model_, k) * r[N + k] + kr_[k];
  };
  if (!ws_.halves) {
    J_.K.multiply(r, kr_.data());
    rows(0, N);
  } else {
    // each half multiplies the rows of K it assembled (read by this thread, they would have to
    // come over from the other core's cache and go back for the next Jacobian)
    const int n = model_.n_el();
    ws_.halves->two.run([&](int p) {
      const HalfRange e = half_range(n, p);
      J_.K.multiply_elements(r, kr_.data(), e.lo, e.hi);
      rows(3 * e.lo, 3 * e.hi);
    });
    J_.K.multiply_pulleys(r, kr_.data());
    rows(3 * n, N);
  }
  uv_.resize(N);
  solver_.solve(rhs_.data(), uv_.data());
  for (int k = 0; k < N; ++k) {
    u[N + k] = uv_[k];
    u[k] = (r[k] + uv_[k]) / s;
  }
  for (int k = 2 * N; k < model_.n_state(); ++k) u[k] = r[k] / s;
}

std::string BeltSystem::describe(int k) const {
  static const char* elem_q[] = {"x position", "y position", "angle"};
  static const char* elem_v[] = {"x velocity", "y velocity", "angular velocity"};
  static const char* energy[] = {"work of the torques", "SDE axial dissipation", "SDE bending dissipation",
                                 "contact dissipation", "friction dissipation"};
  const int N = model_.n_coord(), ne = 3 * model_.n_el();
  std::ostringstream s;
  if (k >= 2 * N) {
    s << "energy integral (" << energy[k - 2 * N] << ")";
    return s.str();
  }
  const bool vel = k >= N;
  const int c = vel ? k - N : k;
  if (c < ne)
    s << "element " << c / 3 << ' ' << (vel ? elem_v : elem_q)[c % 3];
  else
    s << "pulley '" << model_.pulleys[c - ne].name << "' " << (vel ? "speed" : "angle");
  return s.str();
}

std::string BeltSystem::check(double, const double* y) const {
  const int N = model_.n_coord();
  const int n = model_.n_state();
  for (int k = 0; k < n; ++k)
    if (!std::isfinite(y[k])) return describe(k) + " is " + (std::isnan(y[k]) ? "NaN" : "infinite");
  // runaway: a belt element more than 100 pitches away from every pulley's contact circle or
  // moving faster than 1 km/s, a pulley faster than 1e5 rad/s
  double reach = 0;
  for (const Pulley& p : model_.pulleys) reach = std::max(reach, p.centre.norm() + p.radius);
  reach += 100 * model_.belt.pitch;
  std::ostringstream s;
  for (int i = 0; i < model_.n_el(); ++i) {
    const double x = y[3 * i], yy = y[3 * i + 1];
    const double speed = std::hypot(y[N + 3 * i], y[N + 3 * i + 1]);
    if (std::hypot(x, yy) > reach) {
      s << "element " << i << " flew off to (" << x << ", " << yy << ") m";
      return s.str();
    }
    if (speed > 1e3) {
      s << "element " << i << " runs away at " << speed << " m/s";
      return s.str();
    }
  }
  for (int j = 0; j < model_.n_p(); ++j) {
    const double w = y[N + model_.pulley_coord(j)];
    if (std::abs(w) > 1e5) {
      s << "pulley '" << model_.pulleys[j].name << "' runs away at " << w << " rad/s";
      return s.str();
    }
  }
  return {};
}

}  // namespace beltsim
