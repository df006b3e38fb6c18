// The owning loop's side of the live view (live/live_server.hpp): a run's progress callback that
// also publishes the simulation's sample to the page, at most 20 times a wall second whatever the
// step rate. It runs on the thread that runs the simulation, between steps; the server's threads
// never touch the simulation.
#pragma once

#include "live/live_server.hpp"
#include "sim/simulation.hpp"

namespace beltsim::script {

class LiveFeed {
 public:
  // server null: no feed (callback() returns inner)
  explicit LiveFeed(live::LiveServer* server) : server_(server) {}
  ~LiveFeed() { watch(nullptr); }
  LiveFeed(const LiveFeed&) = delete;
  LiveFeed& operator=(const LiveFeed&) = delete;

  // a run of sim starts (for the page a new run, its history cleared, unless the server fed this
  // simulation last); at_end: the page's status after it ("paused", "finished"). watch(nullptr):
  // the run has ended, publishes where it stands (the simulation must still exist)
  void watch(const Simulation* sim, const char* at_end = "finished");
  // inner, and the feed
  RunProgress callback(RunProgress inner);

  static constexpr double kInterval = 0.05;  // [s] of wall time between two samples

 private:
  void publish(double wall);
  live::LiveServer* server_;
  const Simulation* sim_ = nullptr;
  const char* at_end_ = "finished";
  double last_wall_ = -1, last_t_ = 0, h_ = 0;
};

}  // namespace beltsim::script
