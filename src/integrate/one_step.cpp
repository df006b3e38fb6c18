// A one-step method (stepper.hpp) with its step-size controller as a live Integrator. It keeps
// (t, y, F) of the last two step ends; the solution inside the last step is the cubic Hermite
// interpolant on them (Hairer, Nørsett & Wanner I, II.6), third order, which is the dense output
// of samples, frames and pauses alike.
#include <algorithm>
#include <climits>
#include <cmath>
#include <limits>
#include <sstream>

#include "integrate/integrator.hpp"
#include "integrate/stepper.hpp"
#include "io/checkpoint_text.hpp"
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
              st.order() < st.embedded_order() ? st.order() : 0),
        h_max_(h_max > 0 ? h_max : std::numeric_limits<double>::infinity()) {
    if (st.needs_linear_solver() && !sys.linear)
      throw std::invalid_argument("integrator: " + st.name() + " is implicit and needs a linear solver; the system has none");
    st_->attach(ctl_);
    const int n = sys.problem->size();
    f_.resize(n), y1_.resize(n), f1_.resize(n), err_.resize(n), y_prev_.resize(n), f_prev_.resize(n);
  }
  std::string name() const override { return st_->name(); }

  void start(double t, const Eigen::VectorXd& y) override {
    t_ = t_prev_ = t;
    y_ = y;
    sys_.problem->rhs(t, y_.data(), f_.data());
    sys_.problem->counters.rhs++;
    if (const std::string bad = sys_.problem->check(t, y_.data()); !bad.empty())
      throw DivergenceError(t, "the state at t = " + rounded_text(t, 9) + " s: " + bad);
    y_prev_ = y_, f_prev_ = f_;
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
      // sliver of a step is left between (at most 10 % longer than the controller asked)
      if (t_ + kLandStretch * h >= t_land - kLandSlack * std::max(1.0, std::abs(t_land))) h = t_land - t_, lands = true;
      const bool ok = st_->step(sys_, t_, y_, f_, h, y1_, err_);
      int worst = worst_;
      const double e = ok ? ctl_.error_norm(lands ? t_land : t_ + h, y_, y1_, err_, &worst) : 1e300;
      worst_ = worst;
      const double ulp = std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(t_));
      if (!(e <= 1.0)) {
        sys_.problem->counters.rejected++;
        if (!ok) {
          cap_ = 0.5 * h;
          sys_.problem->counters.warnings.add(WarningKind::failed_step, t_);
          ++failed_in_a_row_;
        }
        h_ = ctl_.propose(h, ok ? e : 1e300);
        if (!ok && failed_in_a_row_ >= kFailedInARow)
          throw DivergenceError(t_, "no progress at t = " + rounded_text(t_, 9) + " s: the implicit iteration failed " +
                                        std::to_string(failed_in_a_row_) + " times in a row (step size now " +
                                        rounded_text(h_, 9) + " s); " + largest_error(worst) + "; " +
                                        kDivergenceHint);
        if (!(h_ >= 16 * ulp))
          throw DivergenceError(t_, "the step size collapsed to " + rounded_text(h_, 9) + " s at t = " + rounded_text(t_, 9) +
                                        " s; " + largest_error(worst) + "; " + kDivergenceHint);
        continue;
      }
      failed_in_a_row_ = 0;
      if (h <= kFloorUlps * ulp && !lands) {
        if (++at_floor_ >= kFloorSteps)
          throw DivergenceError(t_, "no progress at t = " + rounded_text(t_, 9) + " s: the step size has stayed at the "
                                    "rounding floor of t (" + rounded_text(h, 9) + " s) for " + std::to_string(at_floor_) +
                                    " steps; " + largest_error(worst) + "; " + kDivergenceHint);
      } else {
        at_floor_ = 0;
      }
      const double t1 = lands ? t_land : t_ + h;
      sys_.problem->rhs(t1, y1_.data(), f1_.data());
      sys_.problem->counters.rhs++;
      sys_.problem->counters.steps++;
      if (const std::string bad = sys_.problem->check(t1, y1_.data()); !bad.empty())
        throw DivergenceError(t1, "the run diverged at t = " + rounded_text(t1, 9) + " s: " + bad);
      t_prev_ = t_, t_ = t1;
      y_prev_.swap(y_), y_.swap(y1_);
      f_prev_.swap(f_), f_.swap(f1_);
      h_used_ = t1 - t_prev_;
      // After a step that could not be taken (an implicit method's iteration did not converge)
      // the step size is capped below the failed one; the cap relaxes by 5 % per accepted step,
      // so the controller does not keep walking back into the size at which the iteration fails.
      cap_ *= 1.05;
      h_ = std::min({ctl_.propose(h_used_, e), h_max_, cap_});
      return;
    }
  }

  // "the largest error is in <component>" for the stop messages; before any error estimate (every
  // step failed from the start) no component can be named
  std::string largest_error(int worst) const {
    return worst < 0 ? "no step was taken, so no component has an error estimate (the forces of the initial state, "
                       "or their Jacobian, are beyond what the iteration solves: check the largest parameters)"
                     : "the largest error is in " + sys_.problem->describe(worst);
  }

  void dense(double t, Eigen::VectorXd& out) const override {
    if (t >= t_) {
      out = y_;
    } else if (t <= t_prev_) {
      out = y_prev_;
    } else {
      hermite((t - t_prev_) / (t_ - t_prev_), t_ - t_prev_, y_prev_, f_prev_, y_, f_, out);
    }
  }

  // The last step and the next as step() and start() make them, from a run that began at t = 0:
  // the last one's length is the distance of its ends (unless a restart put both ends at its
  // end); it was at most kGrowMax times the one before it, which lay in [0, t_prev], or the
  // first step, and a landing stretched it by at most kLandStretch; the next is at most kGrowMax
  // times the last, or a first step after a restart. A step's end far past the checkpoint's time
  // (its dense output spanning it) is refused so.
  void check_steps(CheckpointReader& r, int h_line) const {
    if (t_ != t_prev_ && h_used_ != t_ - t_prev_)
      r.fail("the last step's length must be the distance between its ends, integrator.t - integrator.t_prev = " +
             number_text(t_ - t_prev_) + " s (got " + number_text(h_used_) + " s)");
    const double longest =
        kLandStretch * std::max(kFirstStepMax, StepController::kGrowMax * t_prev_) + kLandSlack * std::max(1.0, t_);
    if (!(h_used_ <= longest))
      r.fail("a step of " + number_text(h_used_) + " s from t = " + number_text(t_prev_) +
             " s is longer than any this integrator takes from there (" + number_text(longest) + " s)");
    const double next = std::max(kFirstStepMax, StepController::kGrowMax * h_used_);
    if (!(h_ <= next))
      r.fail_at(h_line, "integrator.h",
                "a next step of " + number_text(h_) + " s after one of " + number_text(h_used_) +
                    " s is longer than this integrator proposes (at most " + number_text(next) + " s)");
  }

  WorkCounters work() const override { return sys_.problem->counters; }
  std::string stiffest() const override { return worst_ < 0 ? std::string() : sys_.problem->describe(worst_); }

  bool can_save() const override { return true; }
  void save(CheckpointWriter& w) const override {
    w.line("integrator.state", st_->name());
    w.line("integrator.t", t_);
    w.line("integrator.t_prev", t_prev_);
    w.line("integrator.h", h_);
    w.line("integrator.h_used", h_used_);
    w.line("integrator.h_cap", cap_);
    w.line("integrator.started", started_);
    auto vec = [&](const char* k, const Eigen::VectorXd& v) { w.line(k, v.data(), static_cast<size_t>(v.size())); };
    vec("integrator.y", y_), vec("integrator.f", f_), vec("integrator.y_prev", y_prev_), vec("integrator.f_prev", f_prev_);
    // the one kind of warning a one-step method counts
    const WorkCounters& c = sys_.problem->counters;
    const WarningStat& failed = c.warnings[WarningKind::failed_step];
    w.line("integrator.counters",
           std::vector<long>{c.steps, c.rejected, c.rhs, c.jacobians, c.factorizations, c.solves, failed.count});
    w.line("integrator.failed_first_t", failed.first_t);
  }
  void load(CheckpointReader& r) override {
    if (r.line_str("integrator.state") != st_->name()) r.fail("the state of another integrator than " + st_->name());
    t_ = r.line_num("integrator.t");
    t_prev_ = r.line_num("integrator.t_prev");
    if (!(t_prev_ >= 0)) r.fail("a run starts at t = 0 s: no step starts before it");
    if (!(t_prev_ <= t_)) r.fail("the step's start lies after its end");
    h_ = r.line_num("integrator.h");
    const int h_line = r.line_number();
    if (!(h_ >= 0)) r.fail("a step size must be >= 0");
    h_used_ = r.line_num("integrator.h_used");
    if (!(h_used_ >= 0)) r.fail("a step size must be >= 0");
    check_steps(r, h_line);
    r.open("integrator.h_cap");
    cap_ = r.num_or_infinity();
    r.close();
    if (!(cap_ > 0)) r.fail("a step size cap must be > 0");
    started_ = r.line_bool("integrator.started");
    const size_t n = static_cast<size_t>(sys_.problem->size());
    auto vec = [&](const char* k, Eigen::VectorXd& v) {
      const std::vector<double> x = r.line_doubles(k, n);
      if (x.size() != n) r.fail(std::to_string(x.size()) + " values for a state of " + std::to_string(n));
      v = Eigen::Map<const Eigen::VectorXd>(x.data(), static_cast<Eigen::Index>(n));
    };
    vec("integrator.y", y_), vec("integrator.f", f_), vec("integrator.y_prev", y_prev_), vec("integrator.f_prev", f_prev_);
    const std::vector<long> c = r.line_longs("integrator.counters", 0, LONG_MAX, 7);
    if (c.size() != 7) r.fail("7 counts expected");
    WorkCounters& w = sys_.problem->counters;
    WarningStat& failed = w.warnings[WarningKind::failed_step];
    w.steps = c[0], w.rejected = c[1], w.rhs = c[2], w.jacobians = c[3], w.factorizations = c[4], w.solves = c[5];
    failed.count = c[6];
    failed.first_t = r.line_num("integrator.failed_first_t");
    if (failed.count == 0 ? failed.first_t != -1 : !(failed.first_t >= 0 && failed.first_t <= t_))
      r.fail(failed.count == 0 ? "-1 expected: no step failed"
                               : "the first failed step must lie in [0 s, integrator.t]");
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
