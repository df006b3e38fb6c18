// The owning loop's side of the live view (live/live_server.hpp): a run's progress callback that
// also publishes the simulation's sample to the page, at most 20 times a wall second whatever the
// step rate. It runs on the thread that runs the simulation, between steps; the server's threads
// never touch the simulation.
#pragma once

#include <atomic>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "live/live_server.hpp"
#include "script/context.hpp"
#include "sim/simulation.hpp"

namespace beltsim::script {

// The renderer on a thread of its own: draws the latest snapshot offered (t, state, μ, spray
// zones, observation: copies taken by the owning loop, never the live simulation) into a PNG for
// the server; a snapshot not yet drawn when the next comes is dropped. Its GL context is made,
// used and destroyed on that thread. The scene must outlive it.
class FrameThread {
 public:
  FrameThread(const Scene& scene, live::LiveServer* server);
  ~FrameThread();  // draws the snapshot offered last if not yet drawn, stops, joins
  FrameThread(const FrameThread&) = delete;
  FrameThread& operator=(const FrameThread&) = delete;
  void offer(const Simulation& sim);  // on the owning loop: a snapshot of now
  // [s] of wall time the last frame took to draw and encode (0 before the first)
  double cost() const { return cost_.load(std::memory_order_relaxed); }

 private:
  struct Snapshot {
    double t = 0;
    Eigen::VectorXd y;
    Drive drive;  // μ and spray only: a law (Lua code) is never copied to this thread
    Observation obs;
  };
  void loop(const Scene& scene);
  live::LiveServer* server_;
  std::mutex m_;
  std::condition_variable cv_;
  std::optional<Snapshot> next_;
  bool stop_ = false;
  std::atomic<double> cost_{0};
  std::thread thread_;
};

class LiveFeed {
 public:
  // server null: no feed (run_to is Simulation::run_to); stop: Ctrl-C and the signals, which end a
  // pause from the page too; record (when set): the page's changes and the run's end, for the
  // console's session.lua, on the simulation whose userdata is key (null: a scene:run{}'s)
  LiveFeed(live::LiveServer* server, const std::atomic<bool>* stop, std::vector<PageChange>* record = nullptr,
           const void* key = nullptr)
      : server_(server), stop_(stop), record_(record), key_(key) {}
  ~LiveFeed() { watch(nullptr); }
  LiveFeed(const LiveFeed&) = delete;
  LiveFeed& operator=(const LiveFeed&) = delete;

  // sim.run_to(t, stop, inner) with the page fed (samples, frames) and its controls applied on
  // this thread, between two run_to calls, as a console's commands are: a control stops the run
  // at its last step (Simulation::run_to's stop), is applied, and the run goes on to t unless a
  // pause holds it (pause, run to a time: paused there; a torque, a wet stretch, a checkpoint: as
  // sim:set_torque, sim:wet, sim:save). at_end: the page's status after it ("paused", "finished")
  Simulation::Advance run_to(Simulation& sim, double t, const RunProgress& inner, const char* at_end = "finished");
  // the controls that came while no run goes on (a console waiting at its prompt), applied now on
  // the thread that owns sim, where it stands: a torque, a wet stretch, a checkpoint as in a pause;
  // continue and run to t are refused (the console runs it), as is everything when sim is null
  // (the run the page showed has ended). A page that has opened since gets the picture of now
  void apply_waiting(Simulation* sim);
  // sim, which is not running, becomes what the page shows (a simulation just started, or just
  // served): its name, columns and pulleys, the sample of now, the status "paused", and its picture
  // when a page is open; apply_waiting draws it for a page that opens later
  void show(Simulation& sim);

  static constexpr double kInterval = 0.05;           // [s] of wall time between two samples
  static constexpr double kFrameInterval = 1.0 / 15;  // [s] between two frames (while a page is open)
  // [s] of wall time a control waits for the run's next output before it stops the run at its
  // last step instead (a run with samples far apart against its steps' pace)
  static constexpr double kPauseWait = 0.5;
  // at most this share of the wall time goes to drawing frames while the run goes on: a frame that
  // takes longer (a loaded machine, a large belt) spaces the next ones out
  static constexpr double kFrameShare = 0.04;

 private:
  // a run of sim starts (for the page a new run, its history cleared, unless the server fed this
  // simulation last); watch(nullptr): the run has ended, publishes where it stands (the
  // simulation must still exist)
  void watch(Simulation* sim, const char* at_end = "finished");
  // inner, the feed, and the stop when a control or Ctrl-C came
  RunProgress callback(RunProgress inner);
  void publish(double wall);
  // the picture where the run stands, when a page is open
  void offer_frame();
  // the page's controls, between two run_to calls: a pause holds the run here (the controls that
  // come meanwhile applied) until continue, a run to a time, Ctrl-C or the server's end
  void apply_controls(bool paused);
  // the page's picture, plot and status after the control c (said: "" or why it was refused)
  void report(const live::Command& c, const std::string& said, bool paused);
  // one change (torque, wet, save); "" or why it was refused. What an applied change did is in
  // done_ (a wet's as sim:wet says it: how many elements' μ changed, where, from and to)
  std::string apply(const live::Command& c);
  void record(double t, const std::string& call);
  live::LiveServer* server_;
  const std::atomic<bool>* stop_;
  std::vector<PageChange>* record_;
  const void* key_;
  // a control came: the run_to under way stops right after its next output (pause_), where a
  // replay's run_to of that time stands too, or at its last step (halt_) on Ctrl-C or when no
  // output came within kPauseWait of wall time
  std::atomic<bool> pause_{false}, halt_{false};
  double pause_asked_ = -1;  // [s] the wall time the control came (-1: none)
  Simulation* sim_ = nullptr;
  const char* at_end_ = "finished";
  double target_ = 0;  // the page's run to t (0: none)
  std::string end_note_;  // said after at_end_ in the status when the run ends (a page's run to past it)
  double wall_ = 0;    // [s] of the run_to calls before the one under way
  double last_wall_ = -1, last_frame_ = -1, last_t_ = 0, h_ = 0;
  bool changed_ = false;                 // the page changed the simulation during run_to
  std::string done_;                     // what the last change applied did (apply)
  std::unique_ptr<FrameThread> frames_;  // made when a page is first open during a run
};

// every run of a script (scene:run, sim:run_to, sim:advance): feed.run_to(sim, t, ...), or, where
// beltsim.stop_at(x) asked for a stop at x before t, feed.run_to(sim, x, ...) and the run then
// interrupted, as Ctrl-C leaves it there (a console's replay: docs/console.md)
Simulation::Advance run_feed(Context* ctx, LiveFeed& feed, Simulation& sim, double t, const RunProgress& progress,
                             const char* at_end = "finished");

}  // namespace beltsim::script
