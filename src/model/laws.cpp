// Pulley laws (laws.hpp): each term, its value and its derivatives.
//
//   constant                      c                     ∂/∂Ω = 0       ∂/∂t = 0
//   per_speed                     k·Ω                   ∂/∂Ω = k
//   table(t), speed_table(Ω)      y_i + s·(y_{i+1} − y_i), s = (x − x_i)/(x_{i+1} − x_i) on
//                                 [x_i, x_{i+1}], y_0 before x_0, y_n after x_n
//                                 slope (y_{i+1} − y_i)/(x_{i+1} − x_i) inside, 0 outside
//   ramp (linear)                 from + (to − from)·s,  s = (t − t0)/(t1 − t0) ∈ [0, 1]
//                                 ∂/∂t = (to − from)/(t1 − t0) inside, ∂²/∂t² = 0
//   ramp (cosine)                 from + (to − from)·(1 − cos πs)/2
//                                 ∂/∂t = (to − from)·π·sin(πs)/(2(t1 − t0))
//                                 ∂²/∂t² = (to − from)·π²·cos(πs)/(2(t1 − t0)²)
//   step (t0 = t1)                from before t0, to after it; derivatives 0 (the jump itself
//                                 is a restart of the integrator at t0, Simulation::set_landings)
//   sine                          m + a·sin(2πf·t + φ)
//                                 ∂/∂t = 2πf·a·cos(2πf·t + φ), ∂²/∂t² = −(2πf)²·a·sin(2πf·t + φ)
//   harmonic                      a·sin(k·ω_m·t + φ)
//                                 ∂/∂t = kω_m·a·cos(kω_m·t + φ), ∂²/∂t² = −(kω_m)²·a·sin(kω_m·t + φ)
//   fn(t, Ω)                      code; derivatives by finite differences (below)
//
// Kinks (the value's or the slope's jumps in time: table breakpoints, ramp ends) and jumps (steps)
// are reported to the run's one schedule (src/integrate/timeline), which lands on them exactly.
#include "model/laws.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace beltsim {

double interpolate(const std::vector<double>& x, const std::vector<double>& y, double at) {
  if (x.empty()) return 0.0;
  if (at <= x.front()) return y.front();
  if (at >= x.back()) return y.back();
  const auto it = std::upper_bound(x.begin(), x.end(), at);
  const size_t k = static_cast<size_t>(it - x.begin());  // x[k-1] <= at < x[k]
  const double s = (at - x[k - 1]) / (x[k] - x[k - 1]);
  return y[k - 1] + s * (y[k] - y[k - 1]);
}

double interpolate_slope(const std::vector<double>& x, const std::vector<double>& y, double at) {
  if (x.size() < 2 || at < x.front() || at >= x.back()) return 0.0;
  const auto it = std::upper_bound(x.begin(), x.end(), at);
  const size_t k = static_cast<size_t>(it - x.begin());
  return (y[k] - y[k - 1]) / (x[k] - x[k - 1]);
}

double TimeSpeedLaw::table(double time) const { return interpolate(t, value, time); }
double TimeSpeedLaw::table_slope(double time) const { return interpolate_slope(t, value, time); }

bool TimeSpeedLaw::is_zero() const {
  return constant == 0.0 && per_speed == 0.0 && t.empty() && omega.empty() && ramps.empty() && sines.empty() &&
         harmonics.empty() && !fn;
}

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// ramp value and its first two time derivatives at `time`
struct RampAt {
  double v, d1, d2;
};
RampAt ramp_at(const Ramp& r, double time, bool after_jump) {
  if (r.is_step()) return {(time > r.t0 || (time == r.t0 && after_jump)) ? r.to : r.from, 0, 0};
  if (time < r.t0) return {r.from, 0, 0};
  if (time >= r.t1) return {r.to, 0, 0};
  const double d = r.t1 - r.t0, s = (time - r.t0) / d, dv = r.to - r.from;
  if (!r.cosine) return {r.from + dv * s, dv / d, 0};
  return {r.from + dv * 0.5 * (1 - std::cos(M_PI * s)), dv * M_PI * std::sin(M_PI * s) / (2 * d),
          dv * M_PI * M_PI * std::cos(M_PI * s) / (2 * d * d)};
}

// a step h that is exactly representable next to x (x + h − x == h)
double exact_step(double x, double h) {
  volatile double xp = x + h;
  return xp - x;
}

// Finite-difference steps for `fn`, whose smoothness scale we do not know, so the steps are
// relative to the argument's size with 1 (rad/s, s) as the floor:
//  - ∂/∂Ω enters only the Jacobian (the Newton iteration's convergence rate, never the solution),
//    so a forward difference suffices; its error h·|f''|/2 + ε·|f|/h is smallest at
//    h = sqrt(ε)·scale, giving ~1e-8 relative;
//  - ∂/∂t of a prescribed speed is the pulley's acceleration, which enters the equations
//    themselves: a central difference, error h²·|f'''|/6 + ε·|f|/h, best at h = ε^(1/3)·scale
//    (~1e-11 relative);
//  - ∂²/∂t² (only in Rosenbrock's ∂f/∂t): central second difference, best at h = ε^(1/4)·scale.
double fd_omega_step(double omega) { return exact_step(omega, std::sqrt(kEps) * std::max(std::abs(omega), 1.0)); }
double fd_time_step(double t) { return exact_step(t, std::cbrt(kEps) * std::max(std::abs(t), 1.0)); }
double fd_time2_step(double t) { return exact_step(t, std::sqrt(std::sqrt(kEps)) * std::max(std::abs(t), 1.0)); }

}  // namespace

double TimeSpeedLaw::eval(double time, double omega_now, bool after_jump) const {
  double v = constant + per_speed * omega_now + table(time) + interpolate(omega, omega_value, omega_now);
  for (const Ramp& r : ramps) v += ramp_at(r, time, after_jump).v;
  for (const Sine& s : sines) v += s.mean + s.amplitude * std::sin(2 * M_PI * s.frequency * time + s.phase);
  for (const Harmonic& h : harmonics) v += h.amplitude * std::sin(h.order * h.mean_speed * time + h.phase);
  if (fn) v += fn->value(time, omega_now);
  return v;
}

double TimeSpeedLaw::d_omega(double time, double omega_now) const {
  double d = per_speed + interpolate_slope(omega, omega_value, omega_now);
  if (fn) {
    const double h = fd_omega_step(omega_now);
    d += (fn->value(time, omega_now + h) - fn->value(time, omega_now)) / h;
  }
  return d;
}

double TimeSpeedLaw::d_time(double time, double omega_now) const {
  double d = table_slope(time);
  for (const Ramp& r : ramps) d += ramp_at(r, time, false).d1;
  for (const Sine& s : sines) {
    const double w = 2 * M_PI * s.frequency;
    d += w * s.amplitude * std::cos(w * time + s.phase);
  }
  for (const Harmonic& h : harmonics) {
    const double w = h.order * h.mean_speed;
    d += w * h.amplitude * std::cos(w * time + h.phase);
  }
  if (fn) {
    const double h = fd_time_step(time);
    d += (fn->value(time + h, omega_now) - fn->value(time - h, omega_now)) / (2 * h);
  }
  return d;
}

double TimeSpeedLaw::d_time2(double time) const {
  double d = 0;
  for (const Ramp& r : ramps) d += ramp_at(r, time, false).d2;
  for (const Sine& s : sines) {
    const double w = 2 * M_PI * s.frequency;
    d -= w * w * s.amplitude * std::sin(w * time + s.phase);
  }
  for (const Harmonic& h : harmonics) {
    const double w = h.order * h.mean_speed;
    d -= w * w * h.amplitude * std::sin(w * time + h.phase);
  }
  if (fn) {
    const double h = fd_time2_step(time);
    d += (fn->value(time + h, 0) - 2 * fn->value(time, 0) + fn->value(time - h, 0)) / (h * h);
  }
  return d;
}

std::vector<double> TimeSpeedLaw::kinks() const {
  std::vector<double> out = t;
  for (const Ramp& r : ramps)
    if (!r.is_step()) out.push_back(r.t0), out.push_back(r.t1);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::vector<double> TimeSpeedLaw::jumps() const {
  std::vector<double> out;
  for (const Ramp& r : ramps)
    if (r.is_step() && r.from != r.to) out.push_back(r.t0);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

namespace {

// a + b for two tables: exact on the union of their breakpoints (both are linear between them
// and constant outside)
void add_tables(std::vector<double>& x, std::vector<double>& y, const std::vector<double>& bx,
                const std::vector<double>& by) {
  if (bx.empty()) return;
  std::vector<double> u = x;
  u.insert(u.end(), bx.begin(), bx.end());
  std::sort(u.begin(), u.end());
  u.erase(std::unique(u.begin(), u.end()), u.end());
  std::vector<double> v;
  for (double at : u) v.push_back(interpolate(x, y, at) + interpolate(bx, by, at));
  x = std::move(u), y = std::move(v);
}

// two pieces of code: their sum, as one
class SumFunction final : public LawFunction {
 public:
  SumFunction(std::shared_ptr<const LawFunction> a, std::shared_ptr<const LawFunction> b)
      : a_(std::move(a)), b_(std::move(b)) {}
  double value(double t, double omega) const override { return a_->value(t, omega) + b_->value(t, omega); }
  std::string describe() const override { return a_->describe() + " + " + b_->describe(); }
  long calls() const override { return a_->calls() + b_->calls(); }

 private:
  std::shared_ptr<const LawFunction> a_, b_;
};

}  // namespace

TimeSpeedLaw& TimeSpeedLaw::operator+=(const TimeSpeedLaw& o) {
  constant += o.constant;
  per_speed += o.per_speed;
  add_tables(t, value, o.t, o.value);
  add_tables(omega, omega_value, o.omega, o.omega_value);
  ramps.insert(ramps.end(), o.ramps.begin(), o.ramps.end());
  sines.insert(sines.end(), o.sines.begin(), o.sines.end());
  harmonics.insert(harmonics.end(), o.harmonics.begin(), o.harmonics.end());
  if (o.fn) fn = fn ? std::make_shared<SumFunction>(fn, o.fn) : o.fn;
  return *this;
}

}  // namespace beltsim
