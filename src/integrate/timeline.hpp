// The one schedule of a run, the same for every integrator: what happens at which simulated time.
//
//   streams    outputs at t0 + k·dt (samples, frames), read from the dense output; a stream added
//              as landed (the samples) is one the integrator lands on as on a landing, so each of
//              its outputs is a step's end, whose error the step control measures
//   every      actions at t0 + k·dt, k >= 1 (a controller); they may change the system
//   landings   known times the integrator lands on exactly (kinks and jumps of the laws, timed
//              changes such as wetting), each with an optional action
//   when       conditions checked at every step's end; when one turns true, the first time it
//              holds is located by bisection on the dense output and its action runs there
//
// The integrator takes its own steps; run_to(T) reads the state at T from the step that crosses
// it and stops there without shortening that step, so pausing changes nothing: run_to(a) then
// run_to(b) gives exactly what run_to(b) gives. A change of the system at the current time (an
// action's, or one made at a pause) restarts the integrator there (Integrator::start).
//
// At one time the order is: every-actions, landings, when-actions; then, if any of them changed
// the system, the restart; then the streams (in the order added), so that an output at the time
// of a change shows the system after it (a sample at a law's step has the value the law takes
// from then on, a frame at a timed wetting shows the wet stretch), as the system reads at a pause
// there. Everything at or before now() has been delivered.
//
// A companion (optional): a second integrator of the same system, at another tolerance, driven by
// this schedule in lockstep with the main one (a run's error check, sim/run_check.hpp). Before
// anything is delivered at a time p it is brought to p (its own steps, landing on the same
// landings); when the main integrator (re)starts, it restarts at the same time, from its own state
// with the components the restart's state changed (a jump of the state: set_arm, set_speed)
// taken from that state. Its steps depend on the schedule only, not on where a run pauses.
#pragma once

#include <atomic>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "integrate/integrator.hpp"

namespace beltsim {

// The k-th time of a stream that starts at t0 and repeats every dt (samples, frames, snapshots,
// every-actions): t0 + k/R when dt is 1/R for a whole number R (a rate: 1e-3 s is 1000 Hz, a frame
// every 1/300 s is 300 Hz), so that the times are the doubles nearest the decimals a user types
// (180/300 is 0.6 where 180·(1/300) is 0.6000000000000001, past a t_end of 0.6, and 350/1000 is
// 0.35 where 350·0.001 is 0.35000000000000003); t0 + k·dt otherwise.
inline double stream_time(double t0, double dt, long k) {
  const double rate = 1.0 / dt;
  const double r = std::round(rate);
  if (r >= 1 && std::abs(rate - r) <= 1e-9 * r) return t0 + static_cast<double>(k) / r;
  return t0 + static_cast<double>(k) * dt;
}

class Timeline {
 public:
  using Output = std::function<void(double t, const Eigen::VectorXd& y)>;
  using Action = std::function<void(double t)>;
  using Condition = std::function<bool(double t, const Eigen::VectorXd& y)>;
  using Progress = std::function<void(double t, const WorkCounters& w)>;
  struct Landing {
    double t;       // [s]
    Action action;  // may be empty: a kink of a law, nothing to do but land on it
  };
  struct Result {
    double t = 0;            // [s] where the run stands now
    long steps = 0;          // accepted steps taken by this call
    double wall = 0;         // [s] wall time of this call
    bool interrupted = false;
  };

  explicit Timeline(Integrator& integ) : integ_(integ) {}
  // starts the integrator at (t0, y0) and delivers what is due at t0
  void start(double t0, const Eigen::VectorXd& y0);
  // ids are > 0 and never reused; landed: the integrator's steps end on the stream's times
  int add_stream(double t0, double dt, Output fn, bool landed = false);
  int add_times(std::vector<double> times, Output fn);  // outputs at these times (sorted)
  int add_every(double dt, Action fn);  // first at now() + dt
  int add_when(Condition cond, Action action);
  bool remove(int id);
  // called with the time the run has reached inside the held step just before that step is
  // replaced (the next step is taken, or a restart): integrals over the steps (interval means)
  // cover each step up to there
  void set_step_hook(std::function<void(double t)> hook) { step_hook_ = std::move(hook); }
  // called at the end of a time's processing, everything due there delivered (its actions, the
  // restart, its outputs): where a pause at that time stands, a state run_to(t) also stops at
  // (a checkpoint a callback asked for is written there, Simulation::save)
  void set_time_done(std::function<void(double t)> fn) { time_done_ = std::move(fn); }
  void set_landings(std::vector<Landing> landings);  // those at or before now() are dropped
  // the system (or, with y, the state) changed at now(): restart there; deferred to the end of
  // the current time's actions while they run
  void changed(const Eigen::VectorXd* y = nullptr);
  // integrates until T (>= now()), delivering everything due on the way; stops early when *stop
  // is set or poll() returns true: at the last finished step, or between two outputs inside a
  // step (many samples or frames in one step), so now() may then lie inside the held step, as
  // after run_to of that time. When *pause is set it stops right after the next output (a
  // sample, frame, landing or located crossing), where run_to of that output's time stands too, so
  // a change made there is replayed exactly as run_to(t) and the change. Throws DivergenceError
  // (everything before it delivered).
  using Poll = std::function<bool()>;
  Result run_to(double T, const std::atomic<bool>* stop = nullptr, const Progress& progress = {}, const Poll& poll = {},
                const std::atomic<bool>* pause = nullptr);

  double now() const { return now_; }
  const Eigen::VectorXd& state() const { return y_now_; }
  const Integrator& integrator() const { return integ_; }

  // The schedule's state, as plain data (a run's state, sim/sim_state.hpp): where it stands, the
  // next index of every stream and every-action and each condition's value and located crossing,
  // in the order added. The actions, outputs and conditions themselves are not state.
  struct WhenState {
    bool last = false;                                           // its value at now
    double crossing = std::numeric_limits<double>::quiet_NaN();  // in the held step, NaN: none
  };
  struct State {
    double now = 0;               // [s]
    std::vector<long> next;       // of every stream and every-action
    std::vector<WhenState> when;  // of every condition
  };
  State get_state() const;
  // refuses (StateError naming "now", "streams" or "when") a state that does not fit an integrator
  // holding the step [t_prev, t]: now inside it, each index the one due next at now, a crossing
  // after now in it. Entries past those added are ignored (a resumed run's script adds its
  // callbacks after).
  void check_state(const State& s, double t_prev, double t) const;
  // the state set (after check_state, once the integrator holds its state): the solution at now
  // from the integrator's held step; a condition added but not in the state is evaluated there
  void set_state(const State& s);
  // called with the time just before the integrator (re)starts there (start, a change, an
  // action's restart): the system learns which side of a jump at that time it starts on
  void on_restart(std::function<void(double t)> fn) { on_restart_ = std::move(fn); }
  // the companion (null: none); set before start(). A DivergenceError of its own does not stop
  // the run: the companion stops where it failed (companion_failed() says why)
  void set_companion(Integrator* c) { companion_ = c; }
  // its state at now() when it is due there (inside an output of now(): brought to now());
  // null without a companion or after its failure
  const Eigen::VectorXd* companion_state() const;
  const std::string& companion_failed() const { return companion_failed_; }

 private:
  struct Periodic {
    int id;
    bool output;  // a stream; else an every-action
    bool landed;  // a stream the integrator lands on
    double t0, dt;
    long k;       // next index
    Output out;
    Action act;
    bool listed = false;       // at the times in `at` rather than t0 + k·dt
    std::vector<double> at;
    double time() const {
      if (!listed) return stream_time(t0, dt, k);
      return k < static_cast<long>(at.size()) ? at[static_cast<size_t>(k)] : std::numeric_limits<double>::infinity();
    }
  };
  struct When {
    int id;
    Condition cond;
    Action action;
    bool last = false;                                       // its value at now()
    double crossing = std::numeric_limits<double>::quiet_NaN();  // located crossing in the held step
  };
  void process(double p);
  void restart(double p, const Eigen::VectorXd& y);
  void check_conditions();
  void companion_to(double p);  // brings the companion to p (no-op once it failed)
  // where integ's next step is to land: the first landing after its time, or a landed stream's
  // next time when the stream's interval holds two of integ's last step or more
  double next_landing(const Integrator& integ) const;

  Integrator& integ_;
  std::vector<Periodic> periodic_;
  std::vector<Landing> landings_;  // sorted, all after now()
  std::vector<When> when_;
  int next_id_ = 1;
  double now_ = 0;
  Eigen::VectorXd y_now_, scratch_;
  bool started_ = false, in_actions_ = false, dirty_ = false;
  Eigen::VectorXd new_state_;
  bool have_new_state_ = false;
  std::function<void(double)> on_restart_;
  std::function<void(double)> step_hook_;
  std::function<void(double)> time_done_;
  Integrator* companion_ = nullptr;
  Eigen::VectorXd y_companion_;  // its state at companion_at_
  double companion_at_ = -std::numeric_limits<double>::infinity();
  std::string companion_failed_;
};

}  // namespace beltsim
