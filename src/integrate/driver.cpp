#include "integrate/driver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

namespace beltsim {

void hermite(double th, double h, const Eigen::VectorXd& y0, const Eigen::VectorXd& f0, const Eigen::VectorXd& y1,
             const Eigen::VectorXd& f1, Eigen::VectorXd& out) {
  // Hairer, Nørsett & Wanner I, II.6: y(θ) = (1-θ)y0 + θy1 + θ(θ-1)[(1-2θ)(y1-y0) + (θ-1)h·f0 + θh·f1]
  out = (1 - th) * y0 + th * y1 + (th * (th - 1)) * ((1 - 2 * th) * (y1 - y0) + ((th - 1) * h) * f0 + (th * h) * f1);
}

namespace {
std::string fmt(double v) {
  std::ostringstream s;
  s.precision(9);
  s << v;
  return s.str();
}
}  // namespace

DriveResult drive(OdeSystem& sys, Stepper& stepper, const Tolerances& tol, const DriveOptions& opt,
                  Eigen::VectorXd& y, const SampleFn& sample, const ProgressFn& progress) {
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  const int n = sys.size();
  const StepController ctl(sys, tol, std::min(stepper.order(), stepper.embedded_order()));
  stepper.attach(ctl);
  DriveResult res;
  const double span = opt.t_end - opt.t0;
  const double h_max = opt.h_max > 0 ? opt.h_max : span;

  // sample times t0 + k·dt (integer k: no drift), the last one at t_end
  const long n_samples = opt.sample_dt > 0 ? static_cast<long>(std::floor(span / opt.sample_dt * (1 + 1e-12))) : 0;
  long next_sample = 0;
  auto sample_time = [&](long k) { return k > n_samples ? opt.t_end : opt.t0 + static_cast<double>(k) * opt.sample_dt; };
  const long last_sample = (n_samples >= 0 && sample_time(n_samples) < opt.t_end - 1e-12 * span) ? n_samples + 1
                                                                                                   : n_samples;
  std::vector<double> events;
  for (double e : opt.events)
    if (e > opt.t0 && e < opt.t_end) events.push_back(e);
  std::sort(events.begin(), events.end());
  events.push_back(opt.t_end);
  size_t next_event = 0;

  double t = opt.t0;
  Eigen::VectorXd f0(n), f1(n), y1(n), err(n), dense(n);
  sys.rhs(t, y.data(), f0.data());
  sys.counters.rhs++;
  if (const std::string bad = sys.check(t, y.data()); !bad.empty())
    throw DivergenceError(t, "initial state at t = " + fmt(t) + " s: " + bad);
  if (next_sample <= last_sample && sample_time(next_sample) <= t) sample(t, y), next_sample++;
  // frames: frame_t0 + k·frame_dt (integer k) up to t_end, by the same dense output
  const bool frames = opt.frame && opt.frame_dt > 0;
  long next_frame = 0;
  auto frame_time = [&](long k) { return opt.frame_t0 + static_cast<double>(k) * opt.frame_dt; };
  if (frames)
    while (frame_time(next_frame) < t - 1e-12 * span) next_frame++;
  if (frames && std::abs(frame_time(next_frame) - t) <= 1e-12 * span) opt.frame(frame_time(next_frame), y), next_frame++;

  // first step (Hairer II.4, simplified): make the first-order term small against the tolerance
  double h;
  {
    const double d0 = ctl.weighted_norm(y, y), d1 = ctl.weighted_norm(y, f0);
    h = (d0 < 1e-5 || d1 < 1e-5) ? 1e-6 : 0.01 * d0 / d1;
    h = std::min({h, h_max, 1e-3 * span});
  }

  // After a step that could not be taken (an implicit method's iteration did not converge) the
  // step size is capped below the failed one; the cap relaxes by 5 % per accepted step, so the
  // controller does not keep walking back into the size at which the iteration fails.
  double cap = std::numeric_limits<double>::infinity();
  while (t < opt.t_end) {
    if (opt.stop && opt.stop->load()) {
      res.interrupted = true;
      break;
    }
    const double t_event = events[next_event];
    bool hits_event = false;
    // land on the event; a step that would stop just short of it is stretched onto it, so no
    // sliver of a step is left between (at most 10 % longer than the controller asked)
    if (t + 1.1 * h >= t_event - 1e-12 * std::max(1.0, std::abs(t_event))) {
      h = t_event - t;
      hits_event = true;
    }
    const bool ok = stepper.step(sys, t, y, f0, h, y1, err);
    int worst = 0;
    const double e = ok ? ctl.error_norm(y, y1, err, &worst) : 1e300;
    if (e > 1.0) {
      sys.counters.rejected++;
      if (!ok) cap = 0.5 * h;
      h = ctl.propose(h, ok ? e : 1e300);
      if (h < 16 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(t)))
        throw DivergenceError(t, "the step size collapsed to " + fmt(h) + " s at t = " + fmt(t) +
                                     " s; the largest error is in " + sys.describe(worst));
      continue;
    }
    // accepted
    const double t1 = hits_event ? t_event : t + h;
    sys.rhs(t1, y1.data(), f1.data());
    sys.counters.rhs++;
    sys.counters.steps++;
    if (const std::string bad = sys.check(t1, y1.data()); !bad.empty())
      throw DivergenceError(t1, "the run diverged at t = " + fmt(t1) + " s: " + bad);
    while (next_sample <= last_sample && sample_time(next_sample) <= t1 + 1e-12 * span) {
      const double ts = std::min(sample_time(next_sample), t1);
      if (ts >= t1) {
        sample(t1, y1);
      } else {
        hermite((ts - t) / (t1 - t), t1 - t, y, f0, y1, f1, dense);
        sample(ts, dense);
      }
      next_sample++;
    }
    while (frames && frame_time(next_frame) <= std::min(t1, opt.t_end) + 1e-12 * span) {
      // the frame's own time even when it falls on (or within rounding of) the step's end, so
      // frame times never depend on where the steps fell
      const double tf = std::min(frame_time(next_frame), opt.t_end);
      if (tf >= t1) {
        opt.frame(tf, y1);
      } else {
        hermite((tf - t) / (t1 - t), t1 - t, y, f0, y1, f1, dense);
        opt.frame(tf, dense);
      }
      next_frame++;
    }
    const double h_used = t1 - t;
    t = t1;
    y.swap(y1);
    f0.swap(f1);
    h = std::min(ctl.propose(h_used, e), h_max);
    if (hits_event) {
      next_event++;
      if (opt.on_event && t < opt.t_end) {
        // restart: a one-step method needs only F at the new start
        opt.on_event(t, y);
        sys.rhs(t, y.data(), f0.data());
        sys.counters.rhs++;
        h = std::min(h, h_used);
      }
    }
    cap *= 1.05;
    h = std::min(h, cap);
    if (progress) progress(t, sys.counters);
  }
  res.work = sys.counters;
  res.t_reached = t;
  res.wall_seconds = std::chrono::duration<double>(clock::now() - start).count();
  return res;
}

}  // namespace beltsim
