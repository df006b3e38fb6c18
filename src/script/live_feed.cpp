#include "script/live_feed.hpp"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cstdio>

#include "io/number_text.hpp"
#include "io/png_writer.hpp"
#include "render/recorder.hpp"
#include "scene/law_text.hpp"

namespace beltsim::script {

FrameThread::FrameThread(const Scene& scene, live::LiveServer* server)
    : server_(server), thread_([this, &scene] { loop(scene); }) {}

FrameThread::~FrameThread() {
  {
    const std::lock_guard<std::mutex> lock(m_);
    stop_ = true;
  }
  cv_.notify_all();
  thread_.join();
}

void FrameThread::offer(const Simulation& sim) {
  Snapshot s{sim.now(), sim.state(), Drive(), sim.observation()};
  s.drive.mu = sim.drive().mu;
  s.drive.spray = sim.drive().spray;
  {
    const std::lock_guard<std::mutex> lock(m_);
    next_ = std::move(s);  // the one not drawn yet is dropped
  }
  cv_.notify_all();
}

void FrameThread::loop(const Scene& scene) {
  // below the run on a busy machine: the pictures give way (fewer of them), not the run. Linux
  // gives each thread its own nice value; a failure leaves it as it was
  setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), 10);
  FrameSettings fs;
  fs.width = 960, fs.height = 540;
  try {
    render::FrameDrawer drawer(scene, fs);
    for (;;) {
      Snapshot s;
      {
        std::unique_lock<std::mutex> lock(m_);
        cv_.wait(lock, [&] { return stop_ || next_; });
        if (!next_) return;  // stopped, all drawn
        s = std::move(*next_);
        next_.reset();
      }
      server_->set_frame(encode_png(drawer.draw(s.t, s.y.data(), s.drive, &s.obs), "live view frame"));
    }
  } catch (const std::exception& e) {  // no GL: the page goes on without pictures
    std::fprintf(stderr, "beltsim: live view: no frames: %s\n", e.what());
  }
}

void LiveFeed::watch(Simulation* sim, const char* at_end) {
  if (!server_) return;
  if (!sim) {
    if (!sim_) return;
    try {
      publish(0);
      if (frames_) frames_->offer(*sim_);  // the picture where it stands
    } catch (const std::exception& e) {    // a Lua law that fails on reading: the run's error says it
      std::fprintf(stderr, "beltsim: live view: %s\n", e.what());
    }
    server_->set_status(at_end_);
    frames_.reset();  // the last offered drawn, before the simulation (its scene) goes
    sim_ = nullptr;
    return;
  }
  sim_ = sim, at_end_ = at_end;
  std::vector<std::string> columns = sim->columns();
  if (!columns.empty() && columns.front() == "t") columns.erase(columns.begin());
  std::vector<std::string> pulleys;
  for (const Pulley& p : sim->model().pulleys) pulleys.push_back(p.name);
  server_->begin_run(sim, sim->out_dir(), std::move(columns), std::move(pulleys));
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

std::string LiveFeed::apply(const live::Command& c) {
  if (c.what != "torque") return "";
  const int j = sim_->scene().find_pulley(c.pulley);
  if (j < 0) return "no pulley '" + c.pulley + "'";
  TimeSpeedLaw law;
  law.constant = c.value;
  try {
    sim_->set_torque(j, law, law_text(law));  // in events.csv, as sim:set_torque writes it
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

void LiveFeed::apply_controls(double wall) {
  bool paused = false;
  for (;;) {
    const std::optional<live::Command> c = server_->take(paused);
    if (stop_ && stop_->load()) break;
    if (!c) {
      if (!paused || server_->stopping()) break;
      continue;
    }
    std::string said;
    if (c->what == "pause") {
      paused = true;
    } else if (c->what == "continue") {
      paused = false;
    } else {
      said = apply(*c);
    }
    publish(wall);  // the page's t, plot and picture where the run stands
    if (frames_) frames_->offer(*sim_);
    const std::string at = " at t = " + rounded_text(sim_->now(), 6) + " s";
    if (!said.empty())
      server_->set_status("refused: " + said);
    else
      server_->set_status(paused ? "paused" + at : c->what == "torque" ? "running (torque set" + at + ")" : "running");
    if (!paused && !server_->commands_pending()) break;
  }
}

RunProgress LiveFeed::callback(RunProgress inner) {
  if (!server_) return inner;
  return [this, inner](double t, double target, const WorkCounters& w, double wall) {
    if (inner) inner(t, target, w, wall);
    h_ = t - last_t_, last_t_ = t;
    if (sim_ && server_->commands_pending()) apply_controls(wall);
    if (sim_ && wall - last_wall_ >= kInterval) {
      last_wall_ = wall;
      publish(wall);
    }
    if (sim_ && wall - last_frame_ >= kFrameInterval) {
      last_frame_ = wall;
      if (server_->clients() > 0) {
        if (!frames_) frames_ = std::make_unique<FrameThread>(sim_->scene(), server_);
        frames_->offer(*sim_);
      }
    }
  };
}

}  // namespace beltsim::script
