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

namespace beltsim {

class BeltSystem;
class CsvWriter;
class OutputDir;
class RowFile;
class Timeline;

// A change of the belt's friction coefficient at a known time (wetting, drying): the integrator
// lands exactly on t and restarts there. mu holds one value per element; NaN keeps the old one.
struct MuEvent {
  double t = 0;              // [s]
  std::vector<double> mu;
  std::string what = "mu";   // for events.csv: what changed, and how
  std::string text;
};

struct RunSettings {
  double t_end = 1.0;                 // [s] (batch runs only)
  std::string integrator = "esdirk32";
  double rtol = 1e-4;                 // relative tolerance of the error control
  double atol = -1;                   // absolute, per natural unit of each component; < 0: = rtol
  double sample_dt = 1e-3;            // [s] interval of the time-series samples
  std::string out_dir = "out";
  // the probed elements (the paper's "selected" one): columns probe.* for one, probe<k>.* (k = 1,
  // 2, ...) for several; an element's SDE joins it to its predecessor
  std::vector<int> probes{0};
  // per-element snapshots (snapshots.csv) at these times [s] (sorted, >= 0) and/or every
  // snapshot_every [s] from t = 0 (0: none)
  std::vector<double> snapshot_times;
  double snapshot_every = 0;
  // [s] wall time after which an integration call (a batch run, sim:run_to) stops at the last
  // finished step or output, Advance::over_wall_limit set (0: no limit); max_wall in Lua
  double wall_limit = 0;
  // [s] the clock run_to measures its wall time with (the wall-time limit, the no-progress
  // watchdog, Advance::wall); empty: std::chrono::steady_clock. Tests set a fake one, so that a
  // collapse of the rate happens at a known moment.
  std::function<double()> wall_clock;
  bool keep_samples = false;          // keep the rows of timeseries.csv in memory (samples())
  bool allow_large = false;           // past the output limits (check_volume)
  std::vector<MuEvent> mu_events;     // in any order
  // frames (PNG and/or video) at their own times; relative paths are taken inside out_dir. The
  // factory (the renderer's, src/render) is called only when frames are asked for.
  std::optional<FrameSettings> frames;
  FrameSinkFactory frame_factory;
};

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
  std::vector<std::string> skipped;   // events after t_end (drop_events_after_end)
  std::string warning_summary;        // Simulation::warning_summary()
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
  // RunSettings::wall_limit. A run that makes no progress (simulated time per wall second below
  // kRateCollapse of its own best over a window of kRateWindow) throws DivergenceError, as the
  // integrators do for a step size stuck at the rounding floor or a failing implicit iteration
  // (integrate/one_step.cpp). Throws DivergenceError after flushing the outputs
  // (the simulation cannot continue after it), std::invalid_argument for t < now or not finite.
  Advance run_to(double t, const std::atomic<bool>* stop = nullptr, const RunProgress& progress = {});
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

  // ---- reading (at now(), or at the time a when-condition is evaluated) ----------------------
  double now() const;
  const Eigen::VectorXd& state() const;
  const Scene& scene() const { return scene_; }
  const Model& model() const { return scene_.model; }
  const Drive& drive() const { return drive_; }  // the laws and μ now
  const RunSettings& settings() const { return rs_; }
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
  std::string csv_path() const;
  std::string events_path() const;
  std::string snapshots_path() const;  // written only when snapshots are asked for
  bool has_snapshots() const;
  long frames_written() const;
  const std::vector<std::vector<double>>& samples() const { return samples_; }

  // ---- changes at now() (each restarts the integrator there and is written to events.csv) ----
  // the law replaces the pulley's drive: a torque law makes it free, a speed law kinematic
  // (its speed jumps to the law's value now)
  void set_torque(int j, const TimeSpeedLaw& law, const std::string& text);
  void set_speed(int j, const TimeSpeedLaw& law, const std::string& text);
  // moves pulley j's tensioner arm to `angle` [rad] and/or sets its rate [rad/s] now (a jump of
  // the state, in events.csv); throws std::invalid_argument when the pulley has no arm
  void set_arm(int j, std::optional<double> angle, std::optional<double> rate);
  // one μ per element (NaN keeps the old one); what/text describe it in events.csv
  void set_mu(const std::vector<double>& mu, const std::string& what, const std::string& text);
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

  // ---- checkpoints ------------------------------------------------------------------------
  // state, integrator state, laws, μ, pending events, output positions. Callbacks are not saved
  // (their count is): the resumed simulation needs them registered again by the script.
  void save(const std::string& path) const;
  // continues a saved simulation: its outputs are continued in place (the CSV files truncated to
  // the saved rows; frames numbered on, the video in a new file <name>_resumed_<t>.mp4).
  // callbacks (if not null) receives the number of callbacks the saved simulation had.
  // vet (if set) sees the saved settings (outputs resolved) before any output is touched, and may
  // throw to refuse them (a sandboxed script's checkpoint naming files outside its folders).
  static std::unique_ptr<Simulation> resume(const std::string& path, const FrameSinkFactory& factory,
                                            int* callbacks = nullptr,
                                            const std::function<void(const RunSettings&)>& vet = {});

 private:
  Simulation(const Scene& scene, const RunSettings& settings, bool fresh);
  void claim_out_dir();
  void open_outputs(bool append);
  void set_landings();
  void sample(double t, const Eigen::VectorXd& y);
  void frame(double t, const Eigen::VectorXd& y);
  void snapshot(double t, const Eigen::VectorXd& y);
  void add_streams();
  void write_event(double t, const std::string& what, const std::string& text);
  void changed(const Eigen::VectorXd* y = nullptr);
  void require_open(const char* what) const;

  Scene scene_;
  RunSettings rs_;
  const Model& model_ = scene_.model;  // constant
  Drive drive_;               // the scene's drive, as changed since (set_torque, set_mu, μ events)
  std::vector<int> sense_;
  std::unique_ptr<BeltSystem> sys_;
  std::unique_ptr<Integrator> integ_;
  std::unique_ptr<Timeline> tl_;
  std::unique_ptr<OutputDir> out_;  // out_dir, locked while the simulation is open
  std::unique_ptr<CsvWriter> csv_;
  std::unique_ptr<RowFile> events_;  // events.csv, a row per write (io/row_file.hpp)
  std::unique_ptr<RowFile> snapshots_;  // snapshots.csv, a snapshot per write
  std::unique_ptr<FrameSink> sink_;
  std::vector<MuEvent> pending_;  // timed μ changes still ahead
  std::vector<std::vector<double>> samples_;
  double E0_ = 0;
  double wall_ = 0;
  double best_rate_ = 0;          // [s/s] the best simulated time per wall second over a window
  int callbacks_ = 0;
  long rows_ = 0;                 // samples written
  long frames_before_ = 0;        // frames written before a resume
  bool closed_ = false;
  bool running_ = false;          // inside run_to (callbacks may read and change, not run or save)
  std::string failed_;            // why it cannot continue (a divergence)
  // a when-condition is evaluated at a time other than now(): the state it reads
  double view_t_ = 0;
  const Eigen::VectorXd* view_y_ = nullptr;
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
  // interval means (simulation.cpp, "interval means"): the averaged quantities at the held step's
  // ends, their integral from the last sample (mean_from_) to mean_covered_
  struct StepEnd {
    std::vector<double> v;
    ContactList pairs;               // observe_pulleys' contact pass
    std::vector<PulleyObs> pulleys;
    double t = -1;
    long serial = -1;
  };
  const std::vector<double>& step_values(StepEnd& c, double t, const Eigen::VectorXd& y) const;
  std::vector<double> integral_to(double t) const;
  void cover(double t);
  mutable StepEnd step_a_, step_b_;
  std::vector<double> mean_acc_;
  double mean_from_ = 0, mean_covered_ = 0;
};

// A batch run: start, run_to(t_end), close. Throws as Simulation does.
// Timed μ events at or after settings.t_end cannot happen in a run that ends there (a quick
// `--t-end 0.05` check of a script whose events come later): they are removed from
// settings.mu_events, and one note per event says so ("events: the event at 0.1 s (wet) is at or
// after t_end = 0.05 s: skipped").
std::vector<std::string> drop_events_after_end(RunSettings& settings);

RunResult run(const Scene& scene, const RunSettings& settings, const std::atomic<bool>* stop = nullptr,
              const RunProgress& progress = {});

// Refuses (std::invalid_argument with the figures) to integrate from t0 to t1 when that would
// write more than 1e7 samples (a timeseries.csv of gigabytes) or render more than 1e5 frames (an
// hour of video at 30 fps), unless settings.allow_large.
void check_volume(const Scene& scene, const RunSettings& settings, double t0, double t1);

// the column names of timeseries.csv for a scene with that many probes (documented in docs/outputs.md)
std::vector<std::string> timeseries_columns(const Scene& scene, size_t probes = 1);

}  // namespace beltsim
