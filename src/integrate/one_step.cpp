// A one-step method (stepper.hpp) with its step-size controller as a live Integrator. It keeps
// (t, y, F) of the last two step ends and the states the method solved for inside the last step
// (Stepper::interior); the solution inside the last step is the dense output of samples, frames
// and pauses alike:
// - through states alone where the method gives interior ones: the polynomial through y at the
//   step's start, its stage values and y at its end (trbdf2: a quadratic, esdirk32: a cubic), of
//   the order of the stage values' accuracy (Hairer & Wanner IV.6, stage-value interpolation);
// - else the cubic Hermite interpolant on (y, F) at the two ends (Hairer, Nørsett & Wanner I, II.6).
// On a stiff problem F at a step's end carries the stiff components' small departures from their
// slow motion times their large rates: a light pulley's acceleration swings with the contact
// forces' vibration, and the Hermite cubic bulges between two right ends. On the paper's drive
// with both pulleys just above the inertia floor (3.1e-6 kg·m²) at rtol 1e-4 the samples were 5e-3
// off where the step ends were 9e-5 off; through the stage values ... (commit message).
#include <algorithm>
#include <climits>
#include <cmath>
#include <limits>
#include <sstream>

#include "integrate/integrator.hpp"
#include "integrate/stepper.hpp"
#include "io/number_text.hpp"

namespace beltsim {

namespace {

// A run that makes no progress stops with a word instead of creeping on (issue 12). The limits
// come from measurement (a temporary counter, removed again) on scripts/paper_dry.lua,
// paper_wet.lua and automotive_wet.lua as they stand (esdirk32, rtol 1e-4) and cut to 0.3 s with
// rkf45 at rtol 1e-2 and trbdf2 at 1e-6:
//   floor: an accepted step no longer than kFloorUlps units of rounding of max(1, |t|) (the
//          collapse guard below throws at 16). The shortest step of those runs was 5e7 such
//          units (esdirk32) and 1.7e8 (rkf45), so a step this short is the controller stuck
//          on a mode it cannot resolve; kFloorSteps of them in a row (2e-9 s at t < 1 s) is a
//          run that will not get anywhere.
//   Newton: implicit iterations that did not converge, in a row (an accepted step resets the
//          count). Those runs had at most 1 in a row. Each failure cuts the step to a fifth
//          (StepController::propose's largest shrink), so kFailedInARow = 10 is a step 1e7 times
//          shorter without the iteration recovering; the former 60 could never be reached, as
//          the collapse guard below stops a step of at most 1 ms after 17 cuts at the latest.
constexpr double kFloorUlps = 1024;
constexpr long kFloorSteps = 10000;
constexpr long kFailedInARow = 10;
// [s] the longest first step, of a run and after a restart (start())
constexpr double kFirstStepMax = 1e-3;
// a step that would stop just short of a landing is stretched onto it: at most kLandStretch times
// its length, plus kLandSlack of max(1 s, t) for the landing's rounding
constexpr double kLandStretch = 1.1, kLandSlack = 1e-12;

class OneStep final : public Integrator {
 public:
  OneStep(std::unique_ptr<Stepper> owned, Stepper& st, const OdeSystem& sys, const Tolerances& tol, double h_max)
      : owned_(std::move(owned)), st_(&st), sys_(sys), ctl_(*sys.problem, tol, std::min(st.order(), st.embedded_order()),
              st.order() < st.embedded_order() ? st.order() : 0, st.l_stable()),
        h_max_(h_max > 0 ? h_max : std::numeric_limits<double>::infinity()) {
    if (st.needs_linear_solver() && !sys.linear)
      throw std::invalid_argument("integrator: " + st.name() + " is implicit and needs a linear solver; the system has none");
    st_->attach(ctl_);
    const int n = sys.problem->size();
    f_.resize(n), y1_.resize(n), f1_.resize(n), err_.resize(n), y_prev_.resize(n), f_prev_.resize(n);
  }
  std::string name() const override { return st_->name(); }
  bool implicit() const override { return st_->needs_linear_solver(); }

  void start(double t, const Eigen::VectorXd& y) override {
    t_ = t_prev_ = t;
    y_ = y;
    sys_.problem->rhs(t, y_.data(), f_.data());
    sys_.problem->counters.rhs++;
    if (const std::string bad = sys_.problem->check(t, y_.data()); !bad.empty())
      throw DivergenceError(t, "at t = " + rounded_text(t, 9) + " s, " + bad);
    y_prev_ = y_, f_prev_ = f_;
    ic_.clear(), iz_.clear();  // the held step is the point t: no interior
    // first step (Hairer II.4, simplified): make the first-order term small against the
    // tolerance; at most 1 ms, a small part of any belt's period of interest. A restart after a
    // jump (a change of μ or of a law) starts the same way, and no longer than the last step:
    // F there carries the jump's fast transient (elements re-settling on the pulley within
    // microseconds), and a long first step would take that F into the cubic Hermite dense output
    // of its samples (on the dry drive with 12 elements wetted at t = 0.01 s, a 7 ms first step
    // draws the pulleys swinging to +4.8 rad/s between samples, which the step's ends never show).
    const double d0 = ctl_.weighted_norm(y_, y_), d1 = ctl_.weighted_norm(y_, f_);
    double h0 = (d0 < 1e-5 || d1 < 1e-5 || !std::isfinite(d0 / d1)) ? 1e-6 : 0.01 * d0 / d1;
    h0 = std::min({h0, h_max_, kFirstStepMax});
    if (!started_) {
      h_ = h0;
      started_ = true;
    } else if (h_used_ > 0) {
      h_ = std::min({h_, h_used_, h0});
    }
  }

  void step(double t_land) override {
    for (;;) {
      bool lands = false;
      double h = h_;
      // land on t_land; a step that would stop just short of it is stretched onto it, so no
      // sliver of a step is left between (at most 10 % longer than the controller asked). A step
      // that ends on it as asked keeps its size: t_land - t_ differs from h where t_ + h rounded,
      // and a run stopped at a step's end (a pause, Ctrl-C) is replayed as run_to(that end), whose
      // last step must be the run's own, bit for bit
      if (t_ + kLandStretch * h >= t_land - kLandSlack * std::max(1.0, std::abs(t_land))) {
        if (t_ + h != t_land) h = t_land - t_;
        lands = true;
      }
      const bool ok = st_->step(sys_, t_, y_, f_, h, y1_, err_);
      int worst = worst_;
      double e = ok ? ctl_.error_norm(lands ? t_land : t_ + h, y_, y1_, err_, &worst) : 1e300;
      double ci = 0;
      const Eigen::VectorXd *zi = nullptr, *ei = nullptr;
      if (ok && st_->interior_error(sys_, t_, y_, h, ci, zi, ei))
        e = std::max(e, ctl_.interior_norm(t_ + ci * h, y_, *zi, *ei));
      worst_ = worst;
      const double ulp = std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(t_));
      if (!(e <= 1.0)) {
        sys_.problem->counters.rejected++;
        // refused for its size alone (Stepper::h_limit, a growth the step cannot follow): retried
        // at the size the method can take, and capped like a failed iteration, since the growth
        // comes back as the next elements reach the falling part of a friction curve (without the
        // cap, Stribeck's half-wet drive at rtol 1e-3 was 5 % off in its span tensions at 0.38 s,
        // with it 0.2 %; commit message)
        const bool too_long = !ok && st_->h_limit() < h;
        if (!ok) cap_ = 0.5 * h;
        if (!ok && !too_long) {
          sys_.problem->counters.warnings.add(WarningKind::failed_step, t_);
          ++failed_in_a_row_;
        }
        h_ = too_long ? st_->h_limit() : ctl_.propose(h, ok ? e : 1e300);
        if (!ok && failed_in_a_row_ >= kFailedInARow)
          throw DivergenceError(t_, "no progress at t = " + rounded_text(t_, 9) + " s: the implicit iteration failed " +
                                        std::to_string(failed_in_a_row_) + " times in a row (step size now " +
                                        rounded_text(h_, 9) + " s); " + absurd_input(t_ + h) + largest_error(worst) +
                                        "; " + divergence_hint(implicit()));
        if (!(h_ >= 16 * ulp))
          throw DivergenceError(t_, "the step size collapsed to " + rounded_text(h_, 9) +
                                        " s at t = " + rounded_text(t_, 9) + " s; " + absurd_input(t_ + h) +
                                        largest_error(worst) + "; " + divergence_hint(implicit()));
        continue;
      }
      failed_in_a_row_ = 0;
      if (h <= kFloorUlps * ulp && !lands) {
        if (++at_floor_ >= kFloorSteps)
          throw DivergenceError(t_, "no progress at t = " + rounded_text(t_, 9) +
                                        " s: the step size has stayed at the "
                                        "rounding floor of t (" +
                                        rounded_text(h, 9) + " s) for " + std::to_string(at_floor_) + " steps; " +
                                        absurd_input(t_ + h) + largest_error(worst) + "; " +
                                        divergence_hint(implicit()));
      } else {
        at_floor_ = 0;
      }
      const double t1 = lands ? t_land : t_ + h;
      sys_.problem->rhs(t1, y1_.data(), f1_.data());
      sys_.problem->counters.rhs++;
      sys_.problem->counters.steps++;
      if (const std::string bad = sys_.problem->check(t1, y1_.data()); !bad.empty())
        throw DivergenceError(t_, diverged_text(t_, t1, bad));
      t_prev_ = t_, t_ = t1;
      y_prev_.swap(y_), y_.swap(y1_);
      f_prev_.swap(f_), f_.swap(f1_);
      st_->interior(ic_, iz_);
      h_used_ = t1 - t_prev_;
      // After a step that could not be taken (an implicit method's iteration did not converge)
      // the step size is capped below the failed one; the cap relaxes by 5 % per accepted step,
      // so the controller does not keep walking back into the size at which the iteration fails.
      cap_ *= 1.05;
      h_ = std::min({ctl_.propose(h_used_, e), h_max_, cap_, st_->h_limit()});
      return;
    }
  }

  // an input beyond the problem's scales (OdeProblem::absurd_input: an applied torque no belt could
  // carry) at the start or the end of the step that failed, "...; ", named before the largest
  // error: the stop is its doing, wherever the error shows
  std::string absurd_input(double t_end) const { return sys_.problem->absurd_note(t_, t_end, y_.data()); }

  // "the largest error is in <component>" for the stop messages; before any error estimate (every
  // step failed from the start) no component can be named
  std::string largest_error(int worst) const {
    return worst < 0 ? "no step was taken, so no component has an error estimate (the forces of the initial state, "
                       "or their Jacobian, are beyond what the iteration solves)"
                     : "the largest error is in " + sys_.problem->describe(worst);
  }

  void dense(double t, Eigen::VectorXd& out) const override {
    if (t >= t_) {
      out = y_;
    } else if (t <= t_prev_) {
      out = y_prev_;
    } else if (ic_.empty()) {
      hermite((t - t_prev_) / (t_ - t_prev_), t_ - t_prev_, y_prev_, f_prev_, y_, f_, out);
    } else {
      // Lagrange's form on the nodes 0, c_1 .. c_k, 1 (in units of the step)
      const double th = (t - t_prev_) / (t_ - t_prev_);
      const int k = static_cast<int>(ic_.size());
      auto node = [&](int i) { return i == 0 ? 0.0 : i == k + 1 ? 1.0 : ic_[i - 1]; };
      auto value = [&](int i) -> const Eigen::VectorXd& { return i == 0 ? y_prev_ : i == k + 1 ? y_ : iz_[i - 1]; };
      out.setZero(y_.size());
      for (int i = 0; i <= k + 1; ++i) {
        double l = 1;
        for (int j = 0; j <= k + 1; ++j)
          if (j != i) l *= (th - node(j)) / (node(i) - node(j));
        out += l * value(i);
      }
    }
  }

  // The last step and the next as step() and start() make them, from a run that began at t = 0:
  // the last one's length is the distance of its ends (unless a restart put both ends at its
  // end); it was at most kGrowMax times the one before it, which lay in [0, t_prev], or the
  // first step, and a landing stretched it by at most kLandStretch; the next is at most kGrowMax
  // times the last, or a first step after a restart. A step's end far past the checkpoint's time
  // (its dense output spanning it) is refused so.
  static void check_steps(const IntegratorState& s) {
    if (s.t != s.t_prev && s.h_used != s.t - s.t_prev)
      throw StateError("integrator.h_used",
                       "the last step's length must be the distance between its ends, integrator.t - integrator.t_prev = " +
                           number_text(s.t - s.t_prev) + " s (got " + number_text(s.h_used) + " s)");
    const double longest = kLandStretch * std::max(kFirstStepMax, StepController::kGrowMax * s.t_prev) +
                           kLandSlack * std::max(1.0, s.t);
    if (!(s.h_used <= longest))
      throw StateError("integrator.h_used", "a step of " + number_text(s.h_used) + " s from t = " +
                                                number_text(s.t_prev) + " s is longer than any this integrator takes from there (" +
                                                number_text(longest) + " s)");
    const double next = std::max(kFirstStepMax, StepController::kGrowMax * s.h_used);
    if (!(s.h <= next))
      throw StateError("integrator.h", "a next step of " + number_text(s.h) + " s after one of " +
                                           number_text(s.h_used) + " s is longer than this integrator proposes (at most " +
                                           number_text(next) + " s)");
  }

  WorkCounters work() const override { return sys_.problem->counters; }
  std::string stiffest() const override { return worst_ < 0 ? std::string() : sys_.problem->describe(worst_); }

  bool can_save() const override { return true; }
  IntegratorState get_state() const override {
    IntegratorState s;
    s.method = st_->name(), s.t = t_, s.t_prev = t_prev_;
    s.y = y_, s.f = f_, s.y_prev = y_prev_, s.f_prev = f_prev_;
    // the states at the held step's nodes (after a restart there are none; iz_ may hold the step
    // before's)
    s.interior_c = ic_, s.interior.assign(iz_.begin(), iz_.begin() + static_cast<std::ptrdiff_t>(ic_.size()));
    s.h = h_, s.h_used = h_used_, s.h_cap = cap_, s.started = started_;
    s.worst = worst_, s.at_floor = at_floor_, s.failed_in_a_row = failed_in_a_row_;
    s.counters = sys_.problem->counters;
    return s;
  }
  void set_state(const IntegratorState& s) override {
    const Eigen::Index n = sys_.problem->size();
    if (s.method != st_->name())
      throw StateError("integrator.state", "the state of " + s.method + ", not of " + st_->name());
    if (!(s.t_prev >= 0)) throw StateError("integrator.t_prev", "a run starts at t = 0 s: no step starts before it");
    if (!(s.t_prev <= s.t)) throw StateError("integrator.t_prev", "the step's start lies after its end");
    for (const auto& [key, h] : {std::pair{"integrator.h", s.h}, {"integrator.h_used", s.h_used}})
      if (!(h >= 0)) throw StateError(key, "a step size must be >= 0");
    check_steps(s);
    if (!(s.h_cap > 0)) throw StateError("integrator.h_cap", "a step size cap must be > 0");
    const WarningStat& failed = s.counters.warnings[WarningKind::failed_step];
    if (failed.count == 0 ? failed.first_t != -1 : !(failed.first_t >= 0 && failed.first_t <= s.t))
      throw StateError("integrator.failed_first_t", failed.count == 0 ? "-1 expected: no step failed"
                                                                     : "the first failed step must lie in [0 s, integrator.t]");
    for (const auto& [key, v] : {std::pair{"integrator.y", &s.y},
                                 {"integrator.f", &s.f},
                                 {"integrator.y_prev", &s.y_prev},
                                 {"integrator.f_prev", &s.f_prev}})
      if (v->size() != n)
        throw StateError(key, std::to_string(v->size()) + " values for a state of " + std::to_string(n));
    for (double c : s.interior_c)
      if (!(c > 0 && c < 1))
        throw StateError("integrator.interior_c", "an interior node must lie strictly inside the step, in (0, 1)");
    if (s.interior.size() != s.interior_c.size())
      throw StateError("integrator.interior", std::to_string(s.interior.size()) + " interior states for " +
                                                  std::to_string(s.interior_c.size()) + " nodes");
    for (const Eigen::VectorXd& z : s.interior)
      if (z.size() != n)
        throw StateError("integrator.interior",
                         std::to_string(z.size()) + " values for a state of " + std::to_string(n));
    if (s.worst < -1 || s.worst >= n) throw StateError("integrator.worst", "not a component of the state");
    t_ = s.t, t_prev_ = s.t_prev;
    y_ = s.y, f_ = s.f, y_prev_ = s.y_prev, f_prev_ = s.f_prev;
    ic_ = s.interior_c, iz_ = s.interior;
    h_ = s.h, h_used_ = s.h_used, cap_ = s.h_cap, started_ = s.started;
    worst_ = s.worst, at_floor_ = s.at_floor, failed_in_a_row_ = s.failed_in_a_row;
    sys_.problem->counters = s.counters;
  }

 private:
  std::unique_ptr<Stepper> owned_;
  Stepper* st_;
  OdeSystem sys_;
  StepController ctl_;
  double h_max_;
  double h_ = 0, h_used_ = 0;
  double cap_ = std::numeric_limits<double>::infinity();
  bool started_ = false;
  int worst_ = -1;              // the component with the largest error in the last estimate (-1: none yet)
  long at_floor_ = 0;           // accepted steps in a row at the rounding floor of t
  long failed_in_a_row_ = 0;    // implicit iterations in a row that did not converge
  Eigen::VectorXd f_, y1_, f1_, err_, f_prev_;
  std::vector<double> ic_;           // the last step's interior nodes (Stepper::interior; none: Hermite)
  std::vector<Eigen::VectorXd> iz_;  // the states there
};

}  // namespace

std::unique_ptr<Integrator> make_one_step(Stepper& stepper, const OdeSystem& sys, const Tolerances& tol, double h_max) {
  check_tolerances(tol);
  return std::make_unique<OneStep>(nullptr, stepper, sys, tol, h_max);
}

std::unique_ptr<Integrator> make_one_step(std::unique_ptr<Stepper> stepper, const OdeSystem& sys, const Tolerances& tol,
                                          double h_max) {
  check_tolerances(tol);
  Stepper& ref = *stepper;
  return std::make_unique<OneStep>(std::move(stepper), ref, sys, tol, h_max);
}

}  // namespace beltsim
