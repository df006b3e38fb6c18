// A live simulation's state (sim/sim_state.hpp): taken from each part, checked against this run,
// and set back: Simulation's get_state, check_state, apply_state and set_state (sim/simulation.hpp).
#include <cmath>

#include "integrate/belt_system.hpp"
#include "io/number_text.hpp"
#include "sim/sim_state.hpp"
#include "sim/simulation.hpp"

namespace beltsim {

SimState Simulation::get_state() const {
  if (!integ_->can_save()) throw std::invalid_argument("get_state: " + cannot_save(rs_.integrator));
  SimState s;
  s.drive = drive_;
  s.pending = pending_;
  s.schedule = tl_->get_state();
  s.integrator = integ_->get_state();
  s.means = means_->get_state();
  s.outputs = out_->get_state();
  s.callbacks = callbacks_;
  s.wall = wall_;
  return s;
}

void Simulation::check_state(const SimState& s) const {
  const size_t n = static_cast<size_t>(model_.n_el());
  auto each = [](size_t got, size_t want, const std::string& what) {
    return std::to_string(got) + " " + what + " for " + std::to_string(want);
  };
  const Drive& d = s.drive;
  if (d.pulleys.size() != model_.pulleys.size())
    throw StateError("pulley.drive", each(d.pulleys.size(), model_.pulleys.size(), "drives") + " pulleys");
  if (d.mu.size() != n) throw StateError("belt.mu", each(d.mu.size(), n, "values") + " elements");
  if (d.spray.zones.size() != scene_.drive.spray.zones.size())
    throw StateError(
        "spray", each(d.spray.zones.size(), scene_.drive.spray.zones.size(), "spray zones") + " zones of the scene");
  if (d.spray.el.size() != (d.spray.zones.empty() ? 0 : n))
    throw StateError("spray.element.zone", each(d.spray.el.size(), n, "records") + " elements");
  for (const MuEvent& ev : s.pending) {
    if (!(ev.t >= s.now())) throw StateError("event.t", "an event still ahead must come at or after now");
    if (ev.mu.size() != n) throw StateError("event.mu", each(ev.mu.size(), n, "values") + " elements");
    if (!ev.share.empty() && ev.share.size() != n)
      throw StateError("event.share", each(ev.share.size(), n, "shares") + " elements");
  }
  if (s.means.integral.size() != means_->size())
    throw StateError("mean_acc", each(s.means.integral.size(), means_->size(), "integrals") + " means of the scene");
  if (!(s.means.from <= s.means.covered && s.means.covered <= s.now()))
    throw StateError("mean_covered", "the interval means must cover a time up to now");
  // the output streams, then one every-action per callback at most (a resumed run's script adds
  // its callbacks after the state is set)
  const size_t k = s.schedule.next.size();
  if (k < n_streams_ || k > n_streams_ + static_cast<size_t>(std::max(s.callbacks, 0)))
    throw StateError("streams", std::to_string(k) + " positions for the " + std::to_string(n_streams_) +
                                    " output streams of its settings and " + std::to_string(s.callbacks) +
                                    " callbacks");
  tl_->check_state(s.schedule, s.integrator.t_prev, s.integrator.t);
  // what was written by now: at most the samples and frame times due by then (the streams'
  // positions, in add_streams' order: samples, then frames when the run draws them)
  if (s.outputs.rows > s.schedule.next[0])
    throw StateError("rows", std::to_string(s.outputs.rows) + " samples written by t = " + number_text(s.now()) +
                                 " s, at most " + std::to_string(s.schedule.next[0]) + " at a sample every " +
                                 number_text(rs_.sample_dt) + " s");
  const long frame_count = frame_times(rs_) ? s.schedule.next[1] : 0;
  if (s.outputs.frames > frame_count)
    throw StateError("frames_written", std::to_string(s.outputs.frames) + " frames written by t = " +
                                           number_text(s.now()) + " s, at most the " + std::to_string(frame_count) +
                                           " frame times by then");
}

void Simulation::apply_state(const SimState& s) {
  drive_ = s.drive;
  pending_ = s.pending;
  wall_ = s.wall;
  means_->set_state(s.means);
  out_->set_state(s.outputs);
  tl_->set_state(s.schedule);
  serial_++;  // no observation kept from before holds
  set_landings();
}

void Simulation::set_state(const SimState& s) {
  require_open("set_state");
  if (running_ || view_.y) throw std::logic_error("set_state: not inside a callback (set it between run_to calls)");
  if (check_) throw std::logic_error("set_state: a checked run's companion integrator has no state to set");
  check_state(s);
  out_->check_state(s.outputs);
  integ_->set_state(s.integrator);  // (its own checks first: a refusal changes nothing)
  apply_state(s);
  write_event(s.now(), "set_state", "");
}

}  // namespace beltsim
