#include "script/live_feed.hpp"

#include <cstdio>

namespace beltsim::script {

void LiveFeed::watch(const Simulation* sim, const char* at_end) {
  if (!server_) return;
  if (!sim) {
    if (!sim_) return;
    try {
      publish(0);
    } catch (const std::exception& e) {  // a Lua law that fails on reading: the run's error says it
      std::fprintf(stderr, "beltsim: live view: %s\n", e.what());
    }
    server_->set_status(at_end_);
    sim_ = nullptr;
    return;
  }
  sim_ = sim, at_end_ = at_end;
  std::vector<std::string> columns = sim->columns();
  if (!columns.empty() && columns.front() == "t") columns.erase(columns.begin());
  server_->begin_run(sim, sim->out_dir(), std::move(columns));
  last_t_ = sim->now(), last_wall_ = -1;
}
void LiveFeed::publish(double wall) {
  live::Sample s;
  s.t = sim_->now();
  s.ratio = s.t > 0 ? (sim_->wall() + wall) / s.t : 0;
  s.h = h_;
  s.values = sim_->sample_row();
  if (!s.values.empty()) s.values.erase(s.values.begin());  // t
  server_->publish(std::move(s));
}

RunProgress LiveFeed::callback(RunProgress inner) {
  if (!server_) return inner;
  return [this, inner](double t, double target, const WorkCounters& w, double wall) {
    if (inner) inner(t, target, w, wall);
    h_ = t - last_t_, last_t_ = t;
    if (sim_ && wall - last_wall_ >= kInterval) {
      last_wall_ = wall;
      publish(wall);
    }
  };
}

}  // namespace beltsim::script
