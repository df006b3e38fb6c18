// The owning loop's side of the live view (live/live_server.hpp): a run's progress callback that
// also publishes the simulation's sample to the page, at most 20 times a wall second whatever the
// step rate. It runs on the thread that runs the simulation, between steps; the server's threads
// never touch the simulation.
#pragma once

#include <condition_variable>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "live/live_server.hpp"
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
  std::thread thread_;
};

class LiveFeed {
 public:
  // server null: no feed (callback() returns inner); stop: Ctrl-C and the signals, which end a
  // pause from the page too
  LiveFeed(live::LiveServer* server, const std::atomic<bool>* stop) : server_(server), stop_(stop) {}
  ~LiveFeed() { watch(nullptr); }
  LiveFeed(const LiveFeed&) = delete;
  LiveFeed& operator=(const LiveFeed&) = delete;

  // a run of sim starts (for the page a new run, its history cleared, unless the server fed this
  // simulation last); at_end: the page's status after it ("paused", "finished"). watch(nullptr):
  // the run has ended, publishes where it stands (the simulation must still exist)
  void watch(Simulation* sim, const char* at_end = "finished");
  // inner, and the feed
  RunProgress callback(RunProgress inner);

  static constexpr double kInterval = 0.05;           // [s] of wall time between two samples
  static constexpr double kFrameInterval = 1.0 / 15;  // [s] between two frames (while a page is open)

 private:
  void publish(double wall);
  // the page's controls, between two steps: a pause holds the run here (the controls that come
  // meanwhile applied) until continue, or Ctrl-C, or the server's end
  void apply_controls(double wall);
  // one control; "" or why it was refused
  std::string apply(const live::Command& c);
  live::LiveServer* server_;
  const std::atomic<bool>* stop_;
  Simulation* sim_ = nullptr;
  const char* at_end_ = "finished";
  double last_wall_ = -1, last_frame_ = -1, last_t_ = 0, h_ = 0;
  std::unique_ptr<FrameThread> frames_;  // made when a page is first open during a run
};

}  // namespace beltsim::script
