#include "sim/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <utility>

#include "integrate/belt_system.hpp"
#include "integrate/make_integrator.hpp"
#include "integrate/stepper.hpp"
#include "integrate/timeline.hpp"
#include "io/csv_writer.hpp"
#include "io/number_text.hpp"
#include "io/output_dir.hpp"
#include "io/suggest.hpp"
#include "model/forces.hpp"
#include "model/laws.hpp"
#include "scene/validate.hpp"
#include "sim/interval_means.hpp"
#include "sim/scoped.hpp"
#include "sim/settings_check.hpp"

namespace beltsim {

namespace {

// Simulation::id(): from 1, never reused (the live view keys a run by it: live/live_server.hpp)
std::uint64_t next_id() {
  static std::atomic<std::uint64_t> last{0};
  return ++last;
}

}  // namespace

Simulation::Simulation(const Scene& sc, const RunSettings& rs) : Simulation(sc, rs, true) {}

Simulation::Simulation(const Scene& sc, const RunSettings& rs, bool fresh)
    : scene_(sc), rs_(rs), drive_(sc.drive), id_(next_id()), from_start_(fresh) {
  check(scene_, rs_, false);
  warn_contract_misses();
  sense_ = scene_.senses();
  sys_ = std::make_unique<BeltSystem>(model_, drive_);
  sys_->problem.set_spans(scene_.route.span_middles());  // the answer's span tensions
  integ_ = make_integrator(rs_.integrator, *sys_, Tolerances{rs_.rtol, rs_.atol});
  if (rs_.keep_states && !integ_->can_save())
    throw std::invalid_argument("keep_states: " + cannot_save(rs_.integrator));
  // a kept state is a checkpoint, which holds no Lua code: refused before anything is written
  // (the first kept state, at t = 0, failed after the run had begun its outputs)
  for (size_t j = 0; j < drive_.pulleys.size(); ++j) {
    keep_states_law(static_cast<int>(j), "torque", drive_.pulleys[j].torque);
    keep_states_law(static_cast<int>(j), "speed", drive_.pulleys[j].speed);
  }
  tl_ = std::make_unique<Timeline>(*integ_);
  if (rs_.check) {
    check_ = std::make_unique<RunCheck>(scene_, drive_, rs_);
    tl_->set_companion(&check_->integrator());
  }
  tl_->on_restart([this](double t) { drive_.restart_time = t; });
  means_ = std::make_unique<IntervalMeans>(model_, drive_, scene_.route, *integ_);
  tl_->set_step_hook([this](double t) { means_->cover(t, serial_); });
  tl_->set_time_done([this](double) { write_saves_due(); });
  out_ = std::make_unique<Outputs>(scene_, rs_);
  pending_ = rs_.mu_events;
  std::stable_sort(pending_.begin(), pending_.end(), [](const MuEvent& a, const MuEvent& b) { return a.t < b.t; });
  E0_ = beltsim::energy(model_, drive_, 0.0, scene_.y0.data()).total();
  if (drive_.spray.any()) {
    // an element entering or leaving a spray zone: the first time the zones in the state differ
    // from the elements' records, located on the dense output
    const int n = model_.n_el();
    tl_->add_when([this, n](double, const Eigen::VectorXd& y) { return spray_changed(drive_.spray, n, y.data()); },
                  [this](double t) { spray_at(t); });
  }
  add_streams();
  if (!fresh) return;  // a checkpoint's load sets the state (checkpoint.cpp)

  out_->open(false);
  warn_earlier_outputs();
  for (size_t z = 0; z < drive_.spray.zones.size(); ++z)
    if (drive_.spray.zones[z].on) write_event(0.0, spray_name(static_cast<int>(z)), "on");
  set_landings();
  try {
    tl_->start(0.0, scene_.y0);
  } catch (...) {
    close();
    throw;
  }
}

void Simulation::warn_earlier_outputs() const {
  if (const std::vector<std::string> left = out_->earlier_outputs(); !left.empty() && rs_.on_warning) {
    // the checkpoints apart (they come last): resumed after this run, each is refused
    const auto ckpt = std::find_if(left.begin(), left.end(), [](const std::string& n) {
      return n.size() > 5 && n.compare(n.size() - 5, 5, ".ckpt") == 0;
    });
    const std::vector<std::string> files(left.begin(), ckpt), checkpoints(ckpt, left.end());
    const std::string own = "give each run its own --out or out = ..., or remove ";
    std::string held;
    if (!files.empty())
      held = and_list(files) + ", which this run does not write: they are not this run's outputs (" + own + "them)";
    if (!checkpoints.empty()) {
      const bool one = checkpoints.size() == 1;
      held += std::string(files.empty() ? "" : "; and its ") + (one ? "checkpoint " : "checkpoints ") +
              and_list(checkpoints) + ": this run replaces the outputs " + (one ? "it continues" : "they continue") +
              ", so beltsim.resume will refuse " + (one ? "it" : "them") + " unless this run saves its own over " +
              (one ? "it" : "them") + (files.empty() ? " (" + own + (one ? "it)" : "them)") : "");
    }
    rs_.on_warning("the output folder " + rs_.out_dir + " holds an earlier run's " + held);
  }
}

Simulation::~Simulation() {
  try {
    close();
  } catch (...) {
  }
}

// the outputs' streams, the timeline's first (a state holds their positions in this order, the
// one place it is written): samples, frames, snapshots every dt, snapshots at listed times. The
// samples are landed on: every row of timeseries.csv is a step's end, whose error the step control
// measures (docs/integration.md, Samples at step ends); frames and snapshots read the dense output,
// so drawing a run does not change its steps
void Simulation::add_streams() {
  tl_->add_stream(
      0.0, rs_.sample_dt, [this](double t, const Eigen::VectorXd& y) { sample(t, y); }, true);
  if (const std::optional<FrameSettings> f = frame_times(rs_))
    tl_->add_stream(f->t_start, f->frame_dt(), [this](double t, const Eigen::VectorXd& y) { frame(t, y); });
  if (rs_.snapshot_every > 0)
    tl_->add_stream(0.0, rs_.snapshot_every, [this](double t, const Eigen::VectorXd& y) { snapshot(t, y); });
  if (!rs_.snapshot_times.empty())
    tl_->add_times(rs_.snapshot_times, [this](double t, const Eigen::VectorXd& y) { snapshot(t, y); });
  n_streams_ = tl_->get_state().next.size();
}

bool Simulation::has_snapshots() const { return out_->has_snapshots(); }
std::string Simulation::csv_path() const { return out_->path("timeseries.csv"); }
std::string Simulation::snapshots_path() const { return out_->path("snapshots.csv"); }
long Simulation::frames_written() const { return out_->frames_written(); }
const std::vector<std::vector<double>>& Simulation::samples() const { return out_->samples(); }
const std::string& Simulation::integrator_name() const { return rs_.integrator; }

// the kinks of the laws, their jumps and the timed μ changes ahead: the integrator lands on each
void Simulation::set_landings() {
  std::vector<Timeline::Landing> l;
  for (double t : drive_.breakpoints()) l.push_back({t, {}});
  // a step of a law: the step that ends here saw the value before it; the integrator restarts
  // here after it (Drive::restart_time). A kinematic pulley's state speed, which nothing reads
  // (its prescribed one is used), is kept equal to it. Each change here covers the interval
  // means up to now first, with the drive as it was (before_change), as the changes made at a
  // pause do: the outputs of this time come after it (integrate/timeline.hpp), and the step's end
  // read with the law's new value would count it in the interval before.
  for (double t : drive_.jumps())
    l.push_back({t, [this](double at) {
                   Eigen::VectorXd y = state();
                   before_change();
                   drive_.restart_time = at;
                   for (int j = 0; j < model_.n_p(); ++j)
                     if (drive_.kinematic(j))
                       y[model_.n_coord() + model_.pulley_coord(j)] =
                           drive_.omega(model_, j, at, y.data() + model_.n_coord());
                   changed(&y);
                 }});
  // spray zones starting or stopping, and wetted elements dry (a kink of μ: nothing changes there)
  for (const SprayZone& z : drive_.spray.zones)
    for (double t : {z.from, z.to}) l.push_back({t, [this](double at) { spray_at(at); }});
  for (const ElementSpray& e : drive_.spray.el)
    if (e.drying) l.push_back({e.t_dry(), [this](double at) { spray_dry(drive_.spray, at); }});
  for (size_t k = 0; k < pending_.size(); ++k)
    l.push_back({pending_[k].t, [this](double t) {
                   // every μ event due now, in the order given
                   before_change();
                   while (!pending_.empty() && pending_.front().t <= t) {
                     const MuEvent ev = pending_.front();
                     pending_.erase(pending_.begin());
                     for (int i = 0; i < model_.n_el(); ++i)
                       if (!std::isnan(ev.mu[i]))
                         drive_.mu[i] = ev.share.empty() ? ev.mu[i] : drive_.mu[i] + ev.share[i] * (ev.mu[i] - drive_.mu[i]);
                     write_event(t, ev.what, ev.text.empty() ? "scheduled" : ev.text);
                     changed();
                   }
                 }});
  tl_->set_landings(std::move(l));
}

std::vector<std::string> Simulation::columns() const { return timeseries_columns(scene_, rs_.probes.size()); }

const Observation& Simulation::observe_end(Cached& c, double t, const Eigen::VectorXd& y) const {
  if (c.t != t || c.serial != serial_) {
    observe(model_, drive_, sense_, t, y.data(), c.obs);
    c.t = t, c.serial = serial_;
  }
  return c.obs;
}

const Observation& Simulation::observation() const {
  const double t = now();
  Cached& c = now_obs_;
  if (c.t == t && c.serial == serial_ && c.step_end == integ_->t() && !view_.y) return c.obs;
  observe(model_, drive_, sense_, t, state().data(), c.obs);
  const double a = integ_->t_prev(), b = integ_->t();
  if (t > a && t < b) {
    // end_b_ of one step is end_a_ of the next: swap rather than observe again
    if (end_b_.t == a && end_b_.serial == serial_) std::swap(end_a_, end_b_);
    const Observation& A = observe_end(end_a_, a, integ_->y_prev());
    const Observation& B = observe_end(end_b_, b, integ_->y());
    blend_contact(model_, drive_, sense_, (t - a) / (b - a), A, B, c.obs);
  }
  c.t = view_.y ? -1 : t, c.serial = serial_, c.step_end = b;  // a when-condition's view is not kept
  return c.obs;
}

std::vector<double> Simulation::sample_row() const {
  const Model& m = model_;
  const double t = now();
  const Eigen::VectorXd& y = state();
  const double* q = y.data();
  const Observation& o = observation();
  // the interval means since the last sample (NaN in the first row: no interval yet)
  const std::vector<double> means = means_->means_to(t, serial_);
  auto mean = [&](size_t k) { return means[k]; };
  std::vector<double> row;
  row.push_back(t);
  for (size_t j = 0; j < o.pulleys.size(); ++j) {
    const PulleyObs& p = o.pulleys[j];
    row.insert(row.end(), {p.omega, p.torque, p.belt_torque, p.hub_load, mean(2 * j), mean(2 * j + 1), p.contact_arc,
                           p.slip_arc, p.stick_arc, p.creep, p.slip_speed, p.creep_pitch, p.slip_pitch, p.mu});
  }
  for (size_t j = 0; j < o.pulleys.size(); ++j)
    if (m.pulleys[j].arm >= 0) row.insert(row.end(), {o.pulleys[j].arm_angle, o.pulleys[j].arm_rate});
  for (size_t j = 0; j < o.pulleys.size(); ++j) {
    const PulleyObs& p = o.pulleys[j];
    if (m.pulleys[j].coupling >= 0) row.insert(row.end(), {p.rotor_angle, p.rotor_speed, p.windup, p.coupling_torque});
  }
  for (size_t k = 0; k < scene_.route.spans.size(); ++k)
    row.insert(row.end(), {span_tension(static_cast<int>(k)), mean(2 * o.pulleys.size() + k)});
  for (int i : rs_.probes) {
    const ElementObs& e = o.elements[i];
    row.insert(row.end(), {e.sde_force, e.normal, e.friction, e.slip});
  }
  if (m.track_energy) {
    const double* en = q + 2 * m.n_coord();
    row.insert(row.end(), {beltsim::energy(m, drive_, t, q).total() - E0_, en[kWorkTorques], en[kDissSdeAxial],
                           en[kDissSdeBending], en[kDissContact], en[kDissFriction]});
    if (m.n_arm() > 0) row.push_back(en[kDissArms]);
    if (m.n_coupling() > 0) row.push_back(en[kDissCouplings]);
  }
  return row;
}

// the frame drawn at t and/or the state kept there (its number the frame's: t_start + number·frame_dt)
void Simulation::frame(double t, const Eigen::VectorXd& y) {
  const Scoped<View> at(view_, {t, &y});
  if (out_->has_frames()) out_->frame(t, y, drive_, observation());
  if (rs_.keep_states) {
    const FrameSettings f = *frame_times(rs_);
    char name[40];
    std::snprintf(name, sizeof name, "state_%05lld.ckpt", std::llround((t - f.t_start) / f.frame_dt()));
    out_->keep_state(name, checkpoint_text());
  }
}

void Simulation::sample(double t, const Eigen::VectorXd& y) {
  std::vector<double> row;
  {
    const Scoped<View> at(view_, {t, &y});
    row = sample_row();
  }
  watch_ripple(row);
  out_->sample(std::move(row));
  means_->start(t);  // the next interval starts here
  // a one-way clutch overrunning at a sample: the summary counts an overrun there (docs/summary.md)
  for (int c = 0; c < static_cast<int>(model_.couplings.size()) && decoupler_warned_ && !overran_; ++c) {
    const Coupling& cp = model_.couplings[c];
    if (cp.one_way &&
        cp.sense * coupling_state(model_, drive_, t, y.data(), y.data() + model_.n_coord(), c).transmitted < 0)
      overran_ = true;
  }
  if (check_) check_->sample(t, y, tl_->companion_state(), tl_->companion_failed(), sys_->problem.counters.steps);
}

// the span tensions' ripple (sim/ripple_watch.hpp), from the row as timeseries.csv gets it: where
// the accuracy contract is promised and the run does not estimate its own error
void Simulation::watch_ripple(const std::vector<double>& row) {
  if (rs_.check || !rs_.on_warning || rs_.rtol > kContractRtol) return;
  if (span_cols_.empty()) {
    const std::vector<std::string> c = columns();
    for (size_t k = 0; k < scene_.route.spans.size(); ++k) {
      const std::string name = span_name(scene_, k);
      span_cols_.push_back(static_cast<size_t>(std::find(c.begin(), c.end(), name + ".tension") - c.begin()));
      span_names_.push_back(name);
    }
  }
  std::vector<double> tension, mean;
  for (size_t i : span_cols_)
    if (i + 1 < row.size()) tension.push_back(row[i]), mean.push_back(row[i + 1]);
  if (const std::string why = ripple_.add(tension, mean, span_names_); !why.empty())
    rs_.on_warning("at rtol " + rounded_text(rs_.rtol) + " this drive may not keep " + std::string(kContractText) +
                   why + ". check = true (--check) has the run estimate its own error and say whether it does");
}

void Simulation::snapshot(double t, const Eigen::VectorXd& y) {
  const Scoped<View> at(view_, {t, &y});
  out_->snapshot(t, observation());
}

double Simulation::now() const { return view_.y ? view_.t : tl_->now(); }
const Eigen::VectorXd& Simulation::state() const { return view_.y ? *view_.y : tl_->state(); }

ElementObs Simulation::element(int i) const { return observation().elements.at(i); }
PulleyObs Simulation::pulley(int j) const { return observation().pulleys.at(j); }

double Simulation::span_tension(int k) const {
  return span_force(model_, scene_.route.spans[k], state().data());
}

Energy Simulation::energy() const { return beltsim::energy(model_, drive_, now(), state().data()); }

std::vector<double> Simulation::energy_integrals() const {
  if (!model_.track_energy) return {};
  const double* e = state().data() + 2 * model_.n_coord();
  return std::vector<double>(e, e + kEnergyCount);
}

WorkCounters Simulation::stats() const { return integ_->work(); }

void Simulation::require_open(const char* what) const {
  // (a run that failed is closed too: why it cannot go on first)
  if (!failed_.empty()) throw std::logic_error(std::string(what) + ": the simulation cannot continue: " + failed_);
  if (closed_) throw std::logic_error(std::string(what) + ": the simulation is closed");
}

Simulation::Advance Simulation::run_to(double t, const std::atomic<bool>* stop, const RunProgress& progress,
                                       const std::atomic<bool>* pause) {
  require_open("run_to");
  if (!std::isfinite(t)) throw std::invalid_argument("run_to: the time must be finite (got " + rounded_text(t) + " s)");
  if (t < now())
    throw std::invalid_argument("run_to: " + rounded_text(t) + " s is before now (" + rounded_text(now()) + " s)");
  if (running_) throw std::logic_error("run_to: the simulation is already running (called from a callback?)");
  check_volume(scene_, rs_, now(), t);
  for (const auto& [id, dt] : every_dt_) check_calls(rs_, now(), t, dt);
  warn_volume(t);
  const Scoped<bool> running(running_, true);
  const auto steady = [] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  };
  const std::function<double()> clock = rs_.wall_clock ? rs_.wall_clock : std::function<double()>(steady);
  const double start = clock();
  Timeline::Progress pr;
  if (progress) pr = [&](double tt, const WorkCounters& w) { progress(tt, t, w, clock() - start); };
  const Scoped<std::function<double()>> so_far(call_wall_, [&] { return clock() - start; });
  // a checkpoint a callback asked for at a time whose processing an error cut short is not written
  struct DropSaves {
    std::vector<std::string>& due;
    ~DropSaves() { due.clear(); }
  } drop_saves{saves_due_};
  // polled between steps and between outputs: the wall-time limit, and the no-progress watchdog
  // (simulated time per wall second over windows of kRateWindow against the best window so far).
  // The threshold, measured (windows of 1 s) on scripts/paper_dry.lua, paper_wet.lua and
  // automotive_wet.lua as they stand (esdirk32, rtol 1e-4: the slowest window ran at 0.12 of the
  // best) and cut to 0.3 s with rkf45 at 1e-2, trbdf2 and ros34pw2 at 1e-6 (slowest 6e-4 of the
  // best, ros34pw2): 1e-9 is six orders of magnitude below any working run, and a run whose
  // steps sit at the rounding floor (~1e-13 s per step) falls far below it.
  constexpr double kRateWindow = 10, kRateCollapse = 1e-9;
  Advance a;
  double win_wall = 0, win_t = now();
  const Timeline::Poll poll = [&] {
    const double wall = clock() - start;
    if (rs_.wall_limit > 0 && wall > rs_.wall_limit) return a.over_wall_limit = true;
    if (wall - win_wall >= kRateWindow) {
      const double tt = tl_->now(), rate = (tt - win_t) / (wall - win_wall);
      if (best_rate_ > 0 && rate < kRateCollapse * best_rate_) {
        const std::string worst = integ_->stiffest();
        throw DivergenceError(
            tt, "no progress at t = " + rounded_text(tt) + " s: " + rounded_text(tt - win_t) +
                    " s simulated in the last " + rounded_text(wall - win_wall) + " s of wall time, against " +
                    rounded_text(best_rate_) + " s per second earlier in this run; the largest error is in " +
                    (worst.empty() ? std::string("a component the integrator does not name") : worst) + "; " +
                    divergence_hint(integ_->implicit()));
      }
      best_rate_ = std::max(best_rate_, rate);
      win_wall = wall, win_t = tt;
    }
    return false;
  };
  const long steps0 = stats().steps;
  std::string stopped_in;  // the Lua code Ctrl-C interrupted inside the run, which stopped there
  try {
    const Timeline::Result r = tl_->run_to(t, stop, pr, poll, pause);
    a.t = r.t, a.steps = r.steps, a.wall = clock() - start, a.interrupted = r.interrupted;
  } catch (const StoppedInCode& e) {  // (a law's step is not taken; a callback's time is reached)
    a.t = now(), a.steps = stats().steps - steps0, a.wall = clock() - start, a.interrupted = true;
    stopped_in = e.what();
  } catch (const DivergenceError& e) {
    failed_ = e.what();
    end_status_ = "diverged", end_note_ = e.what();
    wall_ += clock() - start;
    close();  // CSV flushed, video finalised so it plays
    throw;
  } catch (const LawError& e) {
    // a law's code failed (a Lua law raised or returned no number): the run cannot go on
    failed_ = e.what();
    end_status_ = "failed", end_note_ = e.what();
    wall_ += clock() - start;
    close();
    throw;
  } catch (const OutputError& e) {
    // an output could not be written (a full disk, a file-size limit): the files hold whole rows
    // (the part of the row that got in was taken out again) but miss this one, so the run cannot
    // go on. Closed, as a stop closes it (the end rows find the room parameters.csv kept); a
    // failure there is recorded for the exit status
    const double row_t = out_->last_row_t();
    const std::string m =
        std::string(e.what()) + "; the run stopped at t = " + rounded_text(now()) + " s of " + rounded_text(t) +
        " s, and the outputs written so far are kept, their rows whole" +
        (std::isnan(row_t) ? std::string() : " (timeseries.csv up to t = " + rounded_text(row_t) + " s)");
    failed_ = m;
    end_status_ = "failed", end_note_ = m;
    wall_ += clock() - start;
    try {
      close();
    } catch (const std::exception&) {
    }
    throw OutputError(m);
  } catch (const std::exception& e) {  // a callback raised: the simulation may go on
    end_status_ = "failed", end_note_ = e.what();
    wall_ += clock() - start;
    throw;
  } catch (...) {
    end_status_ = "failed", end_note_ = "an error in a callback";
    wall_ += clock() - start;
    throw;
  }
  wall_ += a.wall;
  end_status_ = a.over_wall_limit ? "wall_limit" : a.interrupted ? "interrupted" : "ok";
  end_note_ = a.over_wall_limit     ? "stopped by run.max_wall at the last finished step"
              : !stopped_in.empty() ? "stopped (Ctrl-C or SIGTERM) in the Lua code of " + stopped_in
              : a.interrupted       ? "stopped at the last finished step (Ctrl-C, SIGTERM or a live view's control)"
                                    : "";
  return a;
}

void Simulation::warn_volume(double t) {
  if (volume_warned_ || !rs_.on_warning) return;
  if (rs_.keep_states && state_bytes_ < 0) state_bytes_ = kept_state_bytes();
  const OutputVolume v = output_volume(scene_, rs_, now(), t, std::max(0.0, state_bytes_));
  const std::string m = volume_warning(v, t, out_->written_bytes(), out_->free_bytes(), rs_.out_dir);
  if (m.empty()) return;
  volume_warned_ = true;
  rs_.on_warning(m);
}

Warnings Simulation::warnings() const {
  Warnings w = integ_->work().warnings;
  if (scene_.static_retried) {  // counted by the scene build, at the start
    Warnings s;
    s[WarningKind::static_retry] = WarningStat{1, 0.0};
    w.merge(s);
  }
  return w;
}

std::vector<std::string> Simulation::notes() const {
  std::vector<std::string> n;
  const Warnings w = warnings();
  for (const WarningKindInfo& i : warning_kinds())
    if (w[i.kind].count > 0) n.push_back(describe(i.kind, w[i.kind]));
  return n;
}

std::string Simulation::warning_summary() const {
  const Warnings w = warnings();
  std::string s;
  for (const WarningKindInfo& i : warning_kinds()) {
    const WarningStat& st = w[i.kind];
    if (st.count == 0 || !i.closing_line) continue;  // (WarningKindInfo::closing_line)
    s += (s.empty() ? "" : ", ") + std::string(i.name) + " " + std::to_string(st.count) +
         (st.count == 1 ? " time" : " times") + " (first at t = " + rounded_text(st.first_t) + " s)";
  }
  if (s.empty()) return s;
  return "warnings: " + s + "; these fallbacks are described in " +
         (std::filesystem::path(rs_.out_dir) / "parameters.csv").string() + " (warning.*)";
}

CheckEstimate Simulation::check_estimate() const { return check_ ? check_->estimate() : CheckEstimate{}; }

std::string Simulation::check_line() const { return check_ ? check_->line() : std::string(); }

std::string Simulation::unapplied_warnings() const {
  if (!decoupler_warned_ || !from_start_ || overran_) return "";
  std::vector<std::string> names;
  for (const Coupling& c : model_.couplings)
    if (c.one_way) names.push_back("'" + model_.pulleys[c.pulley].name + "'");
  return "the start's warning of an overrunning decoupler's accuracy did not apply to this run: the clutch of " +
         std::string(names.size() > 1 ? "pulleys " : "pulley ") + and_list(names) +
         " never overran up to t = " + rounded_text(now()) + " s (overrun_count 0 in its summary, docs/summary.md)";
}

void Simulation::close() {
  if (closed_) return;
  closed_ = true;
  // how the run ended, last in parameters.csv: a folder read later tells a finished run from a
  // stopped one (a run killed outright has no end.* rows). Two times: the run's state's, where it
  // stopped, and the time series' last row's, which a stop between samples leaves behind it
  const double last_row = out_->last_row_t();
  const std::string end =
      "end.t," + value_text(now()) +
      ",s,derived,the simulated time the run reached: where it stopped (result.t; a checkpoint saved then continues "
      "from it)\n" +
      "end.last_row_t," + (std::isnan(last_row) ? std::string() : value_text(last_row)) +
      ",s,derived,the time of timeseries.csv's last row: the time series reaches it (at most one sample interval "
      "before end.t; empty: no row)\n" +
      "end.status," + end_status_ + ",,derived," +
      csv_text(end_note_.empty() ? "how the run ended: ok, interrupted, wall_limit, diverged or failed" : end_note_) +
      "\n";
  out_->close(warnings(), (check_ ? check_->parameter_rows() : std::string()) + end);
}

void Simulation::write_event(double t, const std::string& what, const std::string& text) {
  out_->event(t, what, text);
}

void Simulation::log_event(const std::string& what, const std::string& text) {
  require_open("log");
  write_event(now(), what, text);
}

void Simulation::before_change() { means_->cover(now(), serial_); }

void Simulation::changed(const Eigen::VectorXd* y) {
  before_change();  // the held step, as it was, up to the change
  serial_++;
  set_landings();
  tl_->changed(y);
  warn_contract_misses();
}

void Simulation::warn_contract_misses() {
  if (!rs_.on_warning) return;
  const std::string contract = kContractText;
  std::vector<std::string> misses;
  if (!rs_.check) decoupler_warned_ = decoupler_warned_ || decoupler_contract_miss(model_, rs_.rtol);
  if (const std::string why = contract_miss(rs_.integrator, rs_.rtol); !why.empty() && !rs_.check)
    misses.push_back("integrator " + rs_.integrator + " does not keep " + contract + why +
                     ". trbdf2 (the default) keeps it; check = true (--check) has this run estimate its own error");
  // (said with --check too: the run's check estimates the speeds' and tensions' error, not the energies')
  if (const std::string why = energy_miss(rs_.integrator); !why.empty() && model_.track_energy)
    misses.push_back("integrator " + rs_.integrator + ": " + why + " (docs/integration.md); trbdf2 (the default) " +
                     "balances them within about the tolerance");
  for (const std::string& why :
       rs_.check ? std::vector<std::string>{} : scene_contract_misses(model_, drive_, rs_.rtol))
    misses.push_back("at rtol " + rounded_text(rs_.rtol) + " this drive may not keep " + contract + why +
                     ". check = true (--check) has the run estimate its own error and say whether it does");
  for (const std::string& m : misses) {
    if (std::find(misses_warned_.begin(), misses_warned_.end(), m) != misses_warned_.end()) continue;
    misses_warned_.push_back(m);
    rs_.on_warning(m);
  }
}

RunResult run(const Scene& sc, const RunSettings& settings, const std::atomic<bool>* stop,
              const RunProgress& progress, const Advancer& advance) {
  RunSettings rs = settings;
  std::vector<std::string> skipped = drop_after_end(rs);
  check(sc, rs, true);
  check_volume(sc, rs, 0.0, rs.t_end);
  Simulation sim(sc, rs);
  RunResult res;
  res.skipped = std::move(skipped);
  res.csv_path = sim.csv_path();
  res.parameters_path = (std::filesystem::path(rs.out_dir) / "parameters.csv").string();
  // the wall-time limit stops the run as Ctrl-C does (Simulation::run_to)
  const Simulation::Advance a = advance ? advance(sim, rs.t_end) : sim.run_to(rs.t_end, stop, progress);
  sim.close();
  res.t_reached = a.t;
  res.over_wall_limit = a.over_wall_limit;
  res.interrupted = a.interrupted && !a.over_wall_limit;
  res.wall_seconds = a.wall;
  res.work = sim.stats();
  res.frames = sim.frames_written();
  res.samples = sim.samples();
  res.notes = sim.notes();
  res.warning_summary = sim.warning_summary();
  res.check = sim.check_estimate();
  res.check_line = sim.check_line();
  res.unapplied = sim.unapplied_warnings();
  for (int j = 0; j < sc.model.n_p(); ++j) res.omega.push_back(sim.pulley(j).omega);
  return res;
}

}  // namespace beltsim
