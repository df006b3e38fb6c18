#include "sim/interval_means.hpp"

#include <algorithm>
#include <limits>
#include <utility>

#include "integrate/integrator.hpp"
#include "scene/scene.hpp"

namespace beltsim {

IntervalMeans::IntervalMeans(const Model& m, const Drive& drive, const Route& route, const Integrator& integ)
    : model_(m), drive_(drive), route_(route), integ_(integ), acc_(2 * m.n_p() + route.spans.size(), 0.0) {}

const std::vector<double>& IntervalMeans::values(StepEnd& c, double t, const Eigen::VectorXd& y, long serial) const {
  if (c.t == t && c.serial == serial) return c.v;
  c.v.clear();
  observe_pulleys(model_, drive_, t, y.data(), c.contacts, c.pulleys);
  for (const PulleyObs& p : c.pulleys) {
    c.v.push_back(p.torque);
    c.v.push_back(p.belt_torque);
  }
  for (const Route::Span& sp : route_.spans) c.v.push_back(span_force(model_, sp, y.data()));
  c.t = t, c.serial = serial;
  return c.v;
}

std::vector<double> IntervalMeans::integral_to(double t, long serial) const {
  std::vector<double> out = acc_;
  const double a = integ_.t_prev(), b = integ_.t();
  const double c = std::max(covered_, a), d = std::min(t, b);
  if (!(b > a) || !(d > c)) return out;
  // the last step's end is this step's start
  if (!(a_.t == a && a_.serial == serial) && b_.t == a && b_.serial == serial) std::swap(a_, b_);
  const std::vector<double>& fa = values(a_, a, integ_.y_prev(), serial);
  const std::vector<double>& fb = values(b_, b, integ_.y(), serial);
  const double tc = (c - a) / (b - a), td = (d - a) / (b - a);
  for (size_t k = 0; k < out.size(); ++k) {
    const double f_c = fa[k] + tc * (fb[k] - fa[k]), f_d = fa[k] + td * (fb[k] - fa[k]);
    out[k] += 0.5 * (d - c) * (f_c + f_d);
  }
  return out;
}

std::vector<double> IntervalMeans::means_to(double t, long serial) const {
  std::vector<double> m = integral_to(t, serial);
  const double dt = t - from_;
  for (double& v : m) v = dt > 0 ? v / dt : std::numeric_limits<double>::quiet_NaN();
  return m;
}

void IntervalMeans::cover(double t, long serial) {
  if (t <= covered_) return;
  acc_ = integral_to(t, serial);
  covered_ = t;
}

void IntervalMeans::start(double t) {
  std::fill(acc_.begin(), acc_.end(), 0.0);
  covered_ = from_ = t;
}

void IntervalMeans::set_state(const State& s) {
  acc_ = s.integral;
  from_ = s.from, covered_ = s.covered;
}

}  // namespace beltsim
