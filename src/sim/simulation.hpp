// A live simulation: Scene → integrator → observers (time-series CSV, events CSV, parameters
// file, frames), advanced in pieces, read and changed between them. A batch run (`beltsim run`,
// Lua `scene:run{}`) is the special case start + run_to(t_end) + close: one code path.
//
// Pausing changes nothing: run_to(a) then run_to(b) writes exactly the samples, frames and final
// state of one run_to(b) (integrate/timeline.hpp). A change of the drive (torque or speed law,
// friction coefficients) applies at the current time, restarts the integrator there and is
// written to events.csv.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "integrate/integrator.hpp"
#include "integrate/system.hpp"
#include "model/observables.hpp"
#include "model/rhs.hpp"
#include "scene/scene.hpp"
#include "sim/frames.hpp"
#include "sim/outputs.hpp"
#include "sim/ripple_watch.hpp"
#include "sim/run_check.hpp"
#include "sim/run_settings.hpp"
#include "sim/sim_state.hpp"

namespace beltsim {

class BeltSystem;
class IntervalMeans;
class Timeline;

// progress of a long integration: simulated time reached, the target, counters, wall time of
// this call (printing it is the caller's business, src/script/progress)
using RunProgress = std::function<void(double t, double t_target, const WorkCounters& w, double wall)>;

struct RunResult {
  double t_reached = 0;
  bool interrupted = false;
  double wall_seconds = 0;
  WorkCounters work;
  std::vector<double> omega;          // final pulley speeds [rad/s], in the model's order
  std::string csv_path, parameters_path;
  bool over_wall_limit = false;       // stopped by RunSettings::wall_limit
  std::vector<std::vector<double>> samples;  // with keep_samples: the CSV rows
  long frames = 0;                    // frames rendered
  std::vector<std::string> notes;     // Simulation::notes()
  std::vector<std::string> skipped;   // events after t_end (drop_after_end)
  std::string warning_summary;        // Simulation::warning_summary()
  CheckEstimate check;                // the error estimate (check.on with RunSettings::check)
  std::string check_line;             // Simulation::check_line()
  std::string unapplied;              // Simulation::unapplied_warnings()
};

class Simulation {
 public:
  // Validates the settings (std::invalid_argument naming the key, the reason and the value),
  // writes DIR/parameters.csv, opens DIR/timeseries.csv and DIR/events.csv, and delivers what is
  // due at t = 0 (the first sample and frame) from the scene's initial static state.
  Simulation(const Scene& scene, const RunSettings& settings);
  ~Simulation();  // close()
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  struct Advance {
    double t = 0;        // [s] where it stands now
    long steps = 0;      // accepted steps of this call
    double wall = 0;     // [s] wall time of this call
    bool interrupted = false;     // stopped by *stop or by the wall-time limit
    bool over_wall_limit = false;  // stopped by RunSettings::wall_limit
  };
  // integrates to t (>= now) delivering samples, frames and callbacks on the way; stops early at
  // the last finished step or output when *stop is set or this call's wall time passes
  // RunSettings::wall_limit, right after the next output when *pause is set (Timeline::run_to). A run that makes no
  // progress (simulated time per wall second below kRateCollapse of its own best over a window of kRateWindow) throws
  // DivergenceError, as the integrators do for a step size stuck at the rounding floor or a failing implicit iteration
  // (integrate/one_step.cpp). Throws DivergenceError after flushing the outputs
  // (the simulation cannot continue after it), std::invalid_argument for t < now or not finite.
  Advance run_to(double t, const std::atomic<bool>* stop = nullptr, const RunProgress& progress = {},
                 const std::atomic<bool>* pause = nullptr);
  // flushes the CSV files and finalises the video (idempotent); a closed simulation can be read
  // but not advanced
  void close();
  bool closed() const { return closed_; }
  // the fallbacks taken so far (integrate/warnings.hpp: the static start's trust-region retry,
  // steps that could not be taken, CVODE's failures): counts and first times; close() lists every
  // kind in parameters.csv (warning.<name>.count and .first_t)
  Warnings warnings() const;
  // one line per kind that fired: its name, count, first time and description
  std::vector<std::string> notes() const;
  // the one line a run prints when any fired ("warnings: failed_step 15 times (first at t =
  // 0.036 s), ...; ... parameters.csv"), "" when none did
  std::string warning_summary() const;
  // the run's estimate of its own error so far (sim/run_check.hpp; on = false unless checked)
  CheckEstimate check_estimate() const;
  // the closing line of a checked run ("check: estimated error of the pulley speeds ..."), ""
  // unless checked
  std::string check_line() const;
  // the line a run's end adds when a warning of its start did not apply to it: the overrunning
  // decoupler's (warn_contract_misses) when no one-way clutch overran at any sample since t = 0
  // (the summary's overrun_count 0, docs/summary.md); "" otherwise, and for a resumed run (its
  // samples before the checkpoint are not seen)
  std::string unapplied_warnings() const;

  // ---- reading (at now(), or at the time a when-condition is evaluated) ----------------------
  double now() const;
  const Eigen::VectorXd& state() const;
  const Scene& scene() const { return scene_; }
  const Model& model() const { return scene_.model; }
  const Drive& drive() const { return drive_; }  // the laws and μ now
  const RunSettings& settings() const { return rs_; }
  // the wall-time limit of each later run_to call [s] (0: none), RunSettings::wall_limit: a
  // checkpoint does not keep it, so a resumed simulation is given one (beltsim.resume's max_wall,
  // --max-wall)
  void set_wall_limit(double seconds) { rs_.wall_limit = seconds; }
  const std::string& integrator_name() const;
  // what is observed now (model/observables.hpp; inside a step its contact forces come from the
  // step's ends): the CSV, the frames and the Lua reads all take it from here
  const Observation& observation() const;
  ElementObs element(int i) const;
  PulleyObs pulley(int j) const;
  double span_tension(int k) const;        // [N] route span k (Scene::find_span)
  Energy energy() const;                   // mechanical energy now [J]
  std::vector<double> energy_integrals() const;  // EnergyIndex order [J]; empty unless tracked
  WorkCounters stats() const;
  double wall() const { return wall_; }    // [s] integration wall time so far
  std::vector<std::string> columns() const;  // of timeseries.csv
  std::vector<double> sample_row() const;    // the row timeseries.csv would get now
  const std::string& out_dir() const { return rs_.out_dir; }
  // a branch's source (resume's out): the folder whose outputs up to the checkpoint it copied; "" for any other
  const std::string& branched_from() const { return branched_from_; }
  // a number no other simulation of this process has had, from 1: its identity where its address
  // is not one (a simulation gone leaves its address to the next, e.g. scene:run{}'s on the stack)
  std::uint64_t id() const { return id_; }
  std::string csv_path() const;
  std::string snapshots_path() const;  // written only when snapshots are asked for
  bool has_snapshots() const;
  long frames_written() const;
  const std::vector<std::vector<double>>& samples() const;  // with keep_samples: the CSV rows

  // ---- changes at now() (each restarts the integrator there and is written to events.csv) ----
  // the law replaces the pulley's drive: a torque law makes it free, a speed law kinematic
  // (its speed jumps to the law's value now)
  // (a Lua law is refused with keep_states, std::invalid_argument: a kept state cannot hold it)
  void set_torque(int j, const TimeSpeedLaw& law, const std::string& text);
  void set_speed(int j, const TimeSpeedLaw& law, const std::string& text);
  // moves pulley j's tensioner arm to `angle` [rad] and/or sets its rate [rad/s] now (a jump of
  // the state, in events.csv); throws std::invalid_argument when the pulley has no arm
  void set_arm(int j, std::optional<double> angle, std::optional<double> rate);
  // sets pulley j's coupled rotor's angle [rad] and/or speed [rad/s] now (a jump of the state, in
  // events.csv); throws std::invalid_argument when the pulley has no coupling
  void set_rotor(int j, std::optional<double> angle, std::optional<double> speed);
  // one μ per element (NaN keeps the old one); what/text describe it in events.csv
  void set_mu(const std::vector<double>& mu, const std::string& what, const std::string& text);
  // switches spray zone z (0-based) on or off now (its time window still applies): elements it
  // held start drying, those inside it are wetted; throws std::invalid_argument for no such zone
  void set_spray(int z, bool enabled);
  // a line in events.csv without a change (a note from a script)
  void log_event(const std::string& what, const std::string& text);

  // ---- callbacks --------------------------------------------------------------------------
  // fn runs at now + k·dt exactly (k >= 1); a change it makes restarts the integrator there
  int every(double dt, std::function<void()> fn);
  // cond is evaluated at every step's end; when it turns true the first time it holds is found
  // by bisection on the dense output (to 1e-10 s), action runs there and the integrator restarts
  int when(std::function<bool()> cond, std::function<void()> action);
  bool cancel(int id);
  int callbacks() const { return callbacks_; }

  // ---- the state (sim/sim_state.hpp; MuJoCo's mj_getState, mj_setState) ---------------------
  // Everything a continuation needs, as plain data, at now(): at a pause, or inside a callback or
  // an output (a kept state is taken inside its frame's output). Throws std::invalid_argument
  // (cannot_save) for an integrator whose state cannot be exported.
  SimState get_state() const;
  // Puts a state of this run (its scene, settings and callbacks) back, between run_to calls:
  // continuing from it gives, bit for bit, what continuing from where it was taken gave. Checks
  // first that it fits (StateError naming the field: the sizes, each stream's position at its
  // time, now inside the integrator's held step, the integrator's method) and that the outputs can
  // be cut back to it (std::runtime_error naming the file: shorter than the state's size, a size
  // not at a row's end, not the bytes the state's run wrote, frames drawn since), and changes
  // nothing when it refuses; then cuts the CSV files back to the state's sizes and notes
  // "set_state" in events.csv. A checked run
  // (RunSettings::check) is refused (std::logic_error): its companion's state is not part of it.
  void set_state(const SimState& s);

  // ---- checkpoints (the settings, the scene and the state in text: sim/state_io.hpp) ---------
  // "" when the simulation can be saved as far as its laws go, else the first law held by Lua
  // code, which no checkpoint can hold: "pulley 'driven'.torque (function at x.lua:6)" (the law
  // now, or the scene's at the start: "the scene's pulley 'driven'.torque ...")
  std::string lua_law() const;
  // state, integrator state, laws, μ, pending events, output positions. Callbacks are not saved
  // (their count is): the resumed simulation needs them registered again by the script. Throws
  // std::invalid_argument (cannot_save) for an integrator whose state cannot be saved, and naming
  // the pulley and the law (lua_law) for a law held by Lua code.
  void save(const std::string& path) const;
  // continues a saved simulation: its outputs are continued in place (the CSV files truncated to
  // the saved rows; frames numbered on, the video in a new file <name>_resumed_<t>.mp4). Results
  // written after the checkpoint (the run went on, or a kept state of a finished run) are cut only
  // with rewind; without it the resume is refused, naming what it would drop.
  // callbacks (if not null) receives the number of callbacks the saved simulation had.
  // vet (if set) sees the saved settings (outputs resolved) before any output is touched, and may
  // throw to refuse them (a sandboxed script's checkpoint naming files outside its folders).
  // The folder must be there (a folder moved away is refused, and none is made) and its files up
  // to the checkpoint the ones its run wrote: parameters.csv's start, the last row's time and every
  // byte up to the cuts (a later run into the folder is refused, naming what differs). warn (if
  // set) hears what could not be checked (a version 12 checkpoint holds no fingerprints).
  // out (when given and not the checkpoint's own folder) branches the run into that folder: the
  // checkpoint's folder is only read (checked as above, never claimed or cut, so its run may still
  // be going on), its files up to the checkpoint are copied into out (parameters.csv written anew,
  // run.out naming out) and the run goes on there; rewind is not needed, as nothing is cut. Its
  // frames, numbered on, and its states go into out too; a checkpoint whose frames go to an absolute
  // path (which the branch would share with the run) is refused.
  static std::unique_ptr<Simulation> resume(const std::string& path, const FrameSinkFactory& factory,
                                            int* callbacks = nullptr,
                                            const std::function<void(const RunSettings&)>& vet = {},
                                            bool rewind = false,
                                            const std::function<void(const std::string&)>& warn = {},
                                            const std::string& out = {});
  // a saved simulation at its time, to read (state, drive, observation) and draw: no output is
  // opened or touched, and it cannot run (it is closed). Throws std::runtime_error as resume does.
  static std::unique_ptr<Simulation> open_checkpoint(const std::string& path);

 private:
  Simulation(const Scene& scene, const RunSettings& settings, bool fresh);
  // resume (outputs: continue them) or open_checkpoint (no outputs)
  static std::unique_ptr<Simulation> load(const std::string& path, const FrameSinkFactory& factory, int* callbacks,
                                          const std::function<void(const RunSettings&)>& vet, bool outputs,
                                          bool rewind = false, const std::function<void(const std::string&)>& warn = {},
                                          const std::string& out = {});
  // the warning (rs_.on_warning) of the outputs an earlier run left in the folder (earlier_outputs)
  void warn_earlier_outputs() const;
  // set_state's parts: whether the state fits (StateError; the integrator's state and the outputs'
  // files are checked by Integrator::set_state and Outputs::check_state), and the state set but
  // the integrator's
  void check_state(const SimState& s) const;
  void apply_state(const SimState& s);
  // the checkpoint of now (save, and a kept state at a frame time: inside the frame stream's
  // output, now() is that time and the integrator holds the step that crosses it)
  std::string checkpoint_text() const;
  // about the bytes of a state kept in motion (keep_states), from the checkpoint of now
  double kept_state_bytes() const;
  // warns once, before a run_to to t, of outputs that will be large or more than the disk has
  // room for (volume_warning, sim/settings_check.hpp)
  void warn_volume(double t);
  void set_landings();
  void sample(double t, const Eigen::VectorXd& y);
  void frame(double t, const Eigen::VectorXd& y);
  void snapshot(double t, const Eigen::VectorXd& y);
  void add_streams();
  void write_event(double t, const std::string& what, const std::string& text);
  void changed(const Eigen::VectorXd* y = nullptr);
  // warns, once each, that the run's integrator (contract_miss) or what the drive now has
  // (scene_contract_misses) was measured not to keep the accuracy contract at this rtol, unless
  // the run checks its own error
  void warn_contract_misses();
  void watch_ripple(const std::vector<double>& row);  // a sample's row: warns once of a ripple (ripple_watch.hpp)
  // the interval means up to now with the drive as it is: called before a change touches the
  // drive (the held step's ends not yet observed would be observed with the new drive)
  void before_change();
  // with keep_states, std::invalid_argument naming keep_states when pulley j's law `what` (torque,
  // speed) is Lua code, which no kept state can hold
  void keep_states_law(int j, const char* what, const TimeSpeedLaw& law) const;
  // the spray zones at t: each zone on or off by its window, the elements' records brought to the
  // state (events.csv has the zones switching); restarts the integrator when something changed
  void spray_at(double t);
  static std::string spray_name(int z);  // "spray1", as events.csv names zone 0
  void require_open(const char* what) const;

  Scene scene_;
  RunSettings rs_;
  const Model& model_ = scene_.model;  // constant
  Drive drive_;               // the scene's drive, as changed since (set_torque, set_mu, μ events)
  std::vector<int> sense_;
  std::unique_ptr<BeltSystem> sys_;
  std::unique_ptr<Integrator> integ_;
  std::unique_ptr<Timeline> tl_;
  std::unique_ptr<IntervalMeans> means_;
  std::unique_ptr<Outputs> out_;
  std::unique_ptr<RunCheck> check_;  // with RunSettings::check
  size_t n_streams_ = 0;             // the output streams (add_streams), the timeline's first
  std::vector<MuEvent> pending_;  // timed μ changes still ahead
  double E0_ = 0;
  double wall_ = 0;
  double best_rate_ = 0;          // [s/s] the best simulated time per wall second over a window
  int callbacks_ = 0;
  std::map<int, double> every_dt_;  // the period of each every() callback, by id (for run_to's volume check)
  bool closed_ = false;
  std::string branched_from_;  // branched_from()
  bool running_ = false;  // inside run_to (callbacks may read and change, not run)
  // inside a callback's function (every, when's action): a checkpoint it asks for (save) is
  // written once everything due at its time is done (write_saves_due), where run_to(t) stops too
  bool in_action_ = false;
  mutable std::vector<std::string> saves_due_;
  std::function<double()> call_wall_;  // inside run_to: its wall time so far [s]
  // writes the checkpoints asked for at the time just done (Timeline::set_time_done)
  void write_saves_due();
  std::string failed_;            // why it cannot continue (a divergence)
  // how its last run_to ended, for parameters.csv's end.status and its note (close): ok,
  // interrupted, wall_limit, diverged or failed (a law or a callback raised)
  std::string end_status_ = "ok", end_note_;
  std::vector<std::string> misses_warned_;  // warn_contract_misses()' warnings given
  bool decoupler_warned_ = false;           // the overrunning decoupler's among them
  bool volume_warned_ = false;              // warn_volume's warning given
  double state_bytes_ = -1;                 // kept_state_bytes(), once measured
  RippleWatch ripple_;                      // the span tensions' ripple at the samples (sim/ripple_watch.hpp)
  std::vector<size_t> span_cols_;           // each span's .tension column in sample_row (its mean follows)
  std::vector<std::string> span_names_;     // and its name there
  const std::uint64_t id_;
  bool from_start_ = true;                  // its samples since t = 0 were seen here (not resumed)
  bool overran_ = false;                    // a one-way clutch overran at one of them (σ < 0, model/coupling.cpp)
  // the state the reads see when it is not the integrator's now: an output's time, or the time a
  // when-condition is evaluated at (set for a scope by a guard, simulation.cpp)
  struct View {
    double t = 0;
    const Eigen::VectorXd* y = nullptr;
  };
  View view_;
  // observations: of the held step's two ends, and of the state read now (each with the time and
  // the change count it was taken at)
  struct Cached {
    Observation obs;
    double t = -1;
    long serial = -1;
    double step_end = -1;
  };
  const Observation& observe_end(Cached& c, double t, const Eigen::VectorXd& y) const;
  mutable Cached end_a_, end_b_, now_obs_;
  long serial_ = 0;  // counts the changes of the model or state
};

// why a run with this integrator cannot be saved (a multistep history SUNDIALS cannot export)
std::string cannot_save(const std::string& integrator);

// A batch run: start, run_to(t_end), close. Throws as Simulation does; first drops the events
// after t_end (drop_after_end) and checks the settings (check). advance (when set) runs the
// simulation to t_end in place of run_to(t_end, stop, progress): the live view's feed, which
// applies the page's controls between run_to calls (script/live_feed.hpp).
using Advancer = std::function<Simulation::Advance(Simulation& sim, double t_end)>;
RunResult run(const Scene& scene, const RunSettings& settings, const std::atomic<bool>* stop = nullptr,
              const RunProgress& progress = {}, const Advancer& advance = {});

}  // namespace beltsim
