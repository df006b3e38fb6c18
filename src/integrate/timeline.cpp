#include "integrate/timeline.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "io/number_text.hpp"

namespace beltsim {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
// crossings of a when-condition are located to this width [s] (bisection on the dense output)
constexpr double kCrossingWidth = 1e-10;
}  // namespace

void Timeline::start(double t0, const Eigen::VectorXd& y0) {
  if (on_restart_) on_restart_(t0);
  integ_.start(t0, y0);
  if (companion_) companion_->start(t0, y0), y_companion_ = y0, companion_at_ = t0;
  started_ = true;
  now_ = t0;
  y_now_ = y0;
  for (Periodic& p : periodic_)
    if (p.output)
      while (p.time() < t0) p.k++;
  process(t0);
}

int Timeline::add_stream(double t0, double dt, Output fn, bool landed) {
  Periodic p{next_id_++, true, landed, t0, dt, 0, std::move(fn), {}, false, {}};
  if (started_)
    while (p.time() <= now_) p.k++;  // what was due before it was added is not delivered
  periodic_.push_back(std::move(p));
  return periodic_.back().id;
}

int Timeline::add_times(std::vector<double> times, Output fn) {
  Periodic p{next_id_++, true, false, 0.0, 0.0, 0, std::move(fn), {}, true, std::move(times)};
  if (started_)
    while (p.time() <= now_) p.k++;
  periodic_.push_back(std::move(p));
  return periodic_.back().id;
}

int Timeline::add_every(double dt, Action fn) {
  periodic_.push_back({next_id_++, false, false, now_, dt, 1, {}, std::move(fn), false, {}});
  return periodic_.back().id;
}

int Timeline::add_when(Condition cond, Action action) {
  When w{next_id_++, std::move(cond), std::move(action)};
  if (started_) w.last = w.cond(now_, y_now_);
  when_.push_back(std::move(w));
  return when_.back().id;
}

bool Timeline::remove(int id) {
  for (auto it = periodic_.begin(); it != periodic_.end(); ++it)
    if (it->id == id) return periodic_.erase(it), true;
  for (auto it = when_.begin(); it != when_.end(); ++it)
    if (it->id == id) return when_.erase(it), true;
  return false;
}

void Timeline::set_landings(std::vector<Landing> landings) {
  landings_.clear();
  for (Landing& l : landings)
    if (l.t > now_ && std::isfinite(l.t)) landings_.push_back(std::move(l));
  std::stable_sort(landings_.begin(), landings_.end(), [](const Landing& a, const Landing& b) { return a.t < b.t; });
}

void Timeline::changed(const Eigen::VectorXd* y) {
  if (y) new_state_ = *y, have_new_state_ = true;
  if (in_actions_) {
    dirty_ = true;
    return;
  }
  restart(now_, have_new_state_ ? new_state_ : y_now_);
}

void Timeline::restart(double p, const Eigen::VectorXd& y) {
  const Eigen::VectorXd start = y;  // y may alias y_now_ or new_state_
  const bool jumped = start != y_now_;  // a change of the state itself (else of laws, or none)
  have_new_state_ = false;
  if (step_hook_) step_hook_(p);  // the held step, as it was, up to the restart
  if (companion_ && companion_failed_.empty()) {
    // the companion restarts here too: its own state, with the components the restart changed
    // (y_now_ is still the main state before the change)
    companion_to(p);
    if (companion_failed_.empty())
      for (Eigen::Index i = 0; i < start.size(); ++i)
        if (start[i] != y_now_[i]) y_companion_[i] = start[i];
  }
  if (on_restart_) on_restart_(p);
  integ_.start(p, start);
  if (companion_ && companion_failed_.empty()) companion_->start(p, y_companion_), companion_at_ = p;
  now_ = p;
  y_now_ = start;
  // the crossings located in the discarded part of the step are gone; the conditions start
  // again from their values here. A condition true here keeps that value unless the state jumped:
  // read again at the same instant it may read otherwise, the contact observables coming from the
  // held step's ends before the restart and from the state at p after it (sim/observe), and a
  // `when` on a slip figure at its threshold (a user's trial: slip_arc > 0.2 m, 0.2215 in the
  // action, 0.1611 at the restart) re-armed at every restart and fired 1 714 times within 78 ns,
  // the steps falling to 1e-10 s. It re-arms where it reads false at a later step's end.
  for (When& w : when_) {
    w.crossing = std::numeric_limits<double>::quiet_NaN();
    if (jumped || !w.last) w.last = w.cond(p, y_now_);
  }
}

// everything due at time p (p inside the held step, after now_): the actions, then the outputs,
// which show the system after them
void Timeline::process(double p) {
  companion_to(p);
  integ_.dense(p, y_now_);
  now_ = p;
  in_actions_ = true;
  dirty_ = false;
  bool landed = false;
  try {
    // actions may add or remove entries: iterate over the ids due now
    std::vector<int> due;
    for (const Periodic& s : periodic_)
      if (!s.output && s.time() == p) due.push_back(s.id);
    for (int id : due)
      for (Periodic& s : periodic_)
        if (s.id == id) {
          s.k++;
          Action a = s.act;  // the action may remove itself
          a(p);
          break;
        }
    while (!landings_.empty() && landings_.front().t <= p) {
      Landing l = std::move(landings_.front());
      landings_.erase(landings_.begin());
      landed = true;
      if (l.action) l.action(p);
    }
    due.clear();
    for (const When& w : when_)
      if (w.crossing == p) due.push_back(w.id);
    for (int id : due)
      for (When& w : when_)
        if (w.id == id) {
          w.crossing = std::numeric_limits<double>::quiet_NaN();
          w.last = true;
          Action a = w.action;
          a(p);
          dirty_ = true;  // the integrator restarts where a condition's action ran
          break;
        }
  } catch (...) {
    in_actions_ = false;
    if (dirty_) restart(p, have_new_state_ ? new_state_ : y_now_);
    throw;
  }
  in_actions_ = false;
  const bool restarted = dirty_;
  if (dirty_)
    restart(p, have_new_state_ ? new_state_ : y_now_);
  else if (landed && p == integ_.t())
    integ_.kink();
  if (landed && !restarted && companion_ && companion_failed_.empty() && p == companion_->t()) companion_->kink();
  // the outputs due at p, after its actions and the restart: a sample, a frame or a snapshot at the
  // time of a law's step or a timed change shows the system after it, as a pause there does
  for (Periodic& s : periodic_)
    if (s.output && s.time() == p) s.k++, s.out(p, y_now_);
  if (time_done_) time_done_(p);
}

double Timeline::next_landing(const Integrator& integ) const {
  const double after = integ.t(), last = integ.t() - integ.t_prev();
  double land = kInf;
  for (const Landing& l : landings_)
    if (l.t > after) {
      land = l.t;
      break;
    }
  for (const Periodic& s : periodic_) {
    // a landed stream whose interval holds two of the last step or more: longer steps come near
    // or past its times, which their dense output gives; landing on each would make the stream,
    // not the tolerance, set the steps (up to twice as many)
    if (!s.landed || !(2 * last <= s.dt)) continue;
    long k = s.k;  // the stream's next time after `after` (the companion may be behind now_)
    while (stream_time(s.t0, s.dt, k) <= after) ++k;
    land = std::min(land, stream_time(s.t0, s.dt, k));
  }
  return land;
}

void Timeline::companion_to(double p) {
  if (!companion_ || !companion_failed_.empty() || p == companion_at_) return;
  try {
    // its own steps, landing where the main one lands (the landings ahead of now_ are those ahead of it)
    while (companion_->t() < p) companion_->step(next_landing(*companion_));
    companion_->dense(p, y_companion_);
    companion_at_ = p;
  } catch (const DivergenceError& e) {
    companion_failed_ = e.what();
  }
}

const Eigen::VectorXd* Timeline::companion_state() const {
  if (!companion_ || !companion_failed_.empty() || companion_at_ != now_) return nullptr;
  return &y_companion_;
}

// after a new step [a, b]: each condition that turned true in it gets its crossing located
void Timeline::check_conditions() {
  const double a = integ_.t_prev(), b = integ_.t();
  for (When& w : when_) {
    const bool v = w.cond(b, integ_.y());
    if (w.last || !v) {
      w.last = v;
      continue;
    }
    double lo = a, hi = b;
    while (hi - lo > kCrossingWidth) {
      const double mid = 0.5 * (lo + hi);
      if (mid <= lo || mid >= hi) break;
      integ_.dense(mid, scratch_);
      (w.cond(mid, scratch_) ? hi : lo) = mid;
    }
    w.crossing = hi;
  }
}

Timeline::Result Timeline::run_to(double T, const std::atomic<bool>* stop, const Progress& progress, const Poll& poll,
                                  const std::atomic<bool>* pause) {
  using clock = std::chrono::steady_clock;
  const auto t_start = clock::now();
  Result r;
  const long steps0 = integ_.work().steps;
  auto stopping = [&] { return (stop && stop->load(std::memory_order_relaxed)) || (poll && poll()); };
  for (;;) {
    const double b = integ_.t();
    // the earliest thing due in (now, min(b, T)]
    double p = kInf;
    for (const Periodic& s : periodic_) p = std::min(p, s.time());
    if (!landings_.empty()) p = std::min(p, landings_.front().t);
    for (const When& w : when_)
      if (!std::isnan(w.crossing)) p = std::min(p, w.crossing);
    if (p <= std::min(b, T)) {
      // between two outputs of one step too: a step may hold thousands of samples or frames
      if (p > now_ && stopping()) {
        r.interrupted = true;
        break;
      }
      process(p);
      if (pause && pause->load(std::memory_order_relaxed) && p < T) {
        r.interrupted = true;
        break;
      }
      continue;
    }
    if (b >= T) {
      if (T > now_) integ_.dense(T, y_now_), now_ = T;
      break;
    }
    // all due up to b is delivered: the run stands at b
    if (b > now_) now_ = b, y_now_ = integ_.y();
    if (stopping()) {
      r.interrupted = true;
      break;
    }
    if (step_hook_) step_hook_(now_);
    integ_.step(next_landing(integ_));
    if (!when_.empty()) check_conditions();
    if (progress) progress(integ_.t(), integ_.work());
  }
  r.t = now_;
  r.steps = integ_.work().steps - steps0;
  r.wall = std::chrono::duration<double>(clock::now() - t_start).count();
  return r;
}

Timeline::State Timeline::get_state() const {
  State s{now_, {}, {}};
  for (const Periodic& p : periodic_) s.next.push_back(p.k);
  for (const When& w : when_) s.when.push_back({w.last, w.crossing});
  return s;
}

void Timeline::check_state(const State& s, double t_prev, double t) const {
  if (companion_) throw std::logic_error("a schedule with a companion integrator cannot take a state");
  if (!(t_prev <= s.now && s.now <= t))
    throw StateError("now", "the time " + number_text(s.now) + " s lies outside the integrator's held step [" +
                                number_text(t_prev) + ", " + number_text(t) + "] s");
  for (size_t i = 0; i < periodic_.size() && i < s.next.size(); ++i) {
    // due next: everything before now delivered, and at most what falls at now still ahead
    Periodic p = periodic_[i];
    p.k = s.next[i];
    const double next = p.time();
    p.k--;
    if (s.next[i] < 0 || !(next >= s.now) || (s.next[i] > 0 && !(p.time() <= s.now)))
      throw StateError("streams", "position " + std::to_string(s.next[i]) + " of stream " + std::to_string(i + 1) +
                                      " does not fit the time " + number_text(s.now) + " s");
  }
  for (size_t i = 0; i < when_.size() && i < s.when.size(); ++i)
    if (const double c = s.when[i].crossing; !std::isnan(c) && !(c > s.now && c <= t))
      throw StateError("when.crossing", "a located crossing must lie after now in the held step");
}

void Timeline::set_state(const State& s) {
  started_ = true;
  in_actions_ = dirty_ = have_new_state_ = false;
  now_ = s.now;
  integ_.dense(now_, y_now_);
  for (size_t i = 0; i < periodic_.size() && i < s.next.size(); ++i) periodic_[i].k = s.next[i];
  for (size_t i = 0; i < when_.size(); ++i) {
    When& w = when_[i];
    if (i < s.when.size())
      w.last = s.when[i].last, w.crossing = s.when[i].crossing;
    else
      w.last = w.cond(now_, y_now_), w.crossing = std::numeric_limits<double>::quiet_NaN();
  }
}

}  // namespace beltsim
