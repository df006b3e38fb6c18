#include "script/live_feed.hpp"

#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "io/number_text.hpp"
#include "io/suggest.hpp"
#include "media/jpeg_writer.hpp"
#include "render/recorder.hpp"
#include "scene/law_text.hpp"
#include "scene/validate.hpp"
#include "script/console_print.hpp"
#include "script/lua_run.hpp"
#include "script/progress.hpp"

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
  std::vector<live::ElementAt> at(scene.sites.size());
  for (const ElementSite& site : scene.sites) at.at(site.index).s = site.s;
  const double length = scene.sites.empty() ? 0 : scene.sites[0].length;
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
      const auto start = std::chrono::steady_clock::now();
      // JPEG at quality 90: a fifth of PNG's CPU (jpeg_writer.hpp), the picture as sharp to the eye
      std::string jpeg = encode_jpeg(drawer.draw(s.t, s.y.data(), s.drive, &s.obs), 90, "live view frame");
      const std::vector<render::ElementDraw>& drawn = drawer.drawn_elements();
      for (size_t i = 0; i < drawn.size() && i < at.size(); ++i)
        at[i].x = drawn[i].centre.x(), at[i].y = drawn[i].centre.y();
      server_->set_frame(std::move(jpeg), s.t, at, length);
      cost_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
  } catch (const std::exception& e) {  // no GL: the page goes on without pictures
    say("beltsim: live view: no frames: %s\n", e.what());
  }
}

void LiveFeed::watch(Simulation* sim, const char* at_end) {
  if (!server_) return;
  if (!sim) {
    if (!sim_) return;
    try {
      publish(0);
      offer_frame();                     // the picture where it stands
    } catch (const std::exception& e) {  // a Lua law that fails on reading: the run's error says it
      say("beltsim: live view: %s\n", e.what());
    }
    server_->set_status(at_end_ + end_note_);
    end_note_.clear();
    frames_.reset();  // the last offered drawn, before the simulation (its scene) goes
    sim_ = nullptr;
    return;
  }
  sim_ = sim, at_end_ = at_end;
  std::vector<std::string> columns = sim->columns();
  if (!columns.empty() && columns.front() == "t") columns.erase(columns.begin());
  std::vector<std::string> pulleys;
  for (const Pulley& p : sim->model().pulleys) pulleys.push_back(p.name);
  server_->begin_run(sim->id(), sim->out_dir(), std::move(columns), std::move(pulleys));
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

void LiveFeed::offer_frame() {
  if (!frames_ && server_->clients() > 0) frames_ = std::make_unique<FrameThread>(sim_->scene(), server_);
  if (frames_) frames_->offer(*sim_);
}

void LiveFeed::record(double t, const std::string& call) {
  changed_ = true;
  if (record_) record_->push_back({key_, t, call});
}

std::string LiveFeed::apply(const live::Command& c) {
  Simulation& s = *sim_;
  const double t = s.now();
  done_ = c.what + " applied";
  try {
    if (c.what == "torque") {
      const int j = s.scene().find_pulley(c.pulley);
      if (j < 0) {  // the server refuses it at once (400); a run begun since it came may lack it
        std::vector<std::string> names;
        for (const Pulley& p : s.model().pulleys) names.push_back(p.name);
        return "torque: " + no_such("pulley", c.pulley, names);
      }
      TimeSpeedLaw law;
      law.constant = c.value;
      s.set_torque(j, law, law_text(law));  // in events.csv, as sim:set_torque writes it
      record(t, "set_torque(" + quoted(c.pulley.data(), c.pulley.size()) + ", " + number_text(c.value) + ")");
    } else if (c.what == "wet") {  // as sim:wet{ from, to, mu } (lua_sim.cpp)
      std::string key;
      if (const std::string bad = range_problem(s.scene(), c.from, c.to, "wet", &key); !bad.empty())
        return key + ": " + bad;
      std::vector<double> mu(s.scene().sites.size(), std::nan(""));
      for (const ElementSite& site : s.scene().sites) {  // as sim:wet checks and says it (mu_over)
        if (!in_stretch(site, c.from, c.to)) continue;
        if (const std::string bad = mu_problem(c.value, site.index); !bad.empty()) return "wet.mu: " + bad;
        mu[site.index] = c.value;
      }
      const std::vector<double> before = s.drive().mu;
      if (changes_mu(before, mu)) {  // a change that changes nothing is not recorded, as at the prompt
        s.set_mu(mu, "wet", wet_text(c.value, c.from, c.to, std::nullopt));
        record(t, "wet { from = " + number_text(c.from) + ", to = " + number_text(c.to) +
                      ", mu = " + number_text(c.value) + " }");
      }
      done_ = mu_change_text(s, before, mu, "wet");
    } else if (c.what == "save") {  // as sim:save(name): a bare name, in the run's folder
      const std::string path = output_path(s.settings(), c.name);
      s.save(path);
      const std::string note = "checkpoint " + c.name + " saved from the live view";
      s.log_event("note", note);  // as sim:log writes it
      record(t, "save(" + quoted(c.name.data(), c.name.size()) + ")");
      record(t, "log(" + quoted(note.data(), note.size()) + ")");
    }
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

void LiveFeed::apply_controls(bool paused) {
  for (;;) {
    const std::optional<live::Command> c = server_->take(paused);
    if (stop_ && stop_->load()) return;
    if (!c) {
      if (!paused || server_->stopping()) return;
      if (!frames_ && server_->clients() > 0) offer_frame();  // a page opened during the pause
      continue;
    }
    std::string said;
    if (c->what == "pause") {
      paused = true;
    } else if (c->what == "continue") {
      paused = false;
    } else if (c->what == "run_to") {
      if (c->value > sim_->now())
        target_ = c->value, paused = false;
      else
        said = "run to " + rounded_text(c->value, 6) + " s: not after now, t = " + rounded_text(sim_->now(), 6) + " s";
    } else {
      said = apply(*c);
    }
    report(*c, said, paused);
    if (!paused && !server_->commands_pending()) return;
  }
}

void LiveFeed::report(const live::Command& c, const std::string& said, bool paused) {
  publish(wall_);  // the page's t, plot and picture where the run stands
  offer_frame();
  const std::string at = " at t = " + rounded_text(sim_->now(), 6) + " s";
  if (!said.empty())
    server_->set_status("refused: " + said);
  else if (c.what == "pause" || c.what == "continue" || c.what == "run_to")
    server_->set_status(paused ? "paused" + at : "running");
  else
    server_->set_status((paused ? "paused" : "running") + at + " (" + done_ + ")");
}

void LiveFeed::apply_waiting(Simulation* sim) {
  if (!server_) return;
  while (const std::optional<live::Command> c = server_->take(false)) {
    if (!sim) {
      server_->set_status("refused: " + c->what + ": no simulation to change (the run has ended)");
      continue;
    }
    sim_ = sim;
    std::string said;
    if (c->what == "continue" || c->what == "run_to")
      said = c->what + ": the console runs the simulation (sim:run_to at its prompt)";
    else if (c->what != "pause")
      said = apply(*c);
    try {
      report(*c, said, true);
    } catch (const std::exception& e) {  // a Lua law that fails on reading: the next run's error says it
      say("beltsim: live view: %s\n", e.what());
    }
    // the console says it too, as it says its own changes (a user's trial saw a live view's wet
    // reach the console only as a warning on the prompt's line)
    if (c->what != "pause")
      say("beltsim: live view: %s\n",
          (said.empty() ? done_ + " at t = " + rounded_text(sim->now(), 6) + " s" : "refused: " + said).c_str());
  }
  // a page opened while no run goes on: the picture where the simulation stands (a frame drawn
  // at the end of a run may be older: a change at the prompt since, or none drawn with no page)
  if (sim && server_->take_page_opened()) {
    sim_ = sim;
    try {
      offer_frame();
    } catch (const std::exception& e) {
      say("beltsim: live view: %s\n", e.what());
    }
  }
  frames_.reset();  // the picture drawn, before the simulation can go
  sim_ = nullptr;
}

void LiveFeed::show(Simulation& sim) {
  if (!server_) return;
  watch(&sim, "paused");
  watch(nullptr);  // the sample and the picture of now, the status
}

Simulation::Advance LiveFeed::run_to(Simulation& sim, double t, const RunProgress& inner, const char* at_end) {
  if (!server_) return sim.run_to(t, stop_, inner);
  watch(&sim, at_end);
  const struct Unwatch {
    LiveFeed& f;
    ~Unwatch() { f.watch(nullptr); }
  } unwatch{*this};
  const RunProgress progress = callback(inner);
  Simulation::Advance total;
  wall_ = 0, changed_ = false;
  // what came before this run (a console's prompt, a script's start): applied where it stands
  if (server_->commands_pending()) apply_controls(false);
  for (;;) {
    halt_ = pause_ = false, pause_asked_ = -1;
    const bool to_target = target_ > sim.now() && target_ < t;
    const Simulation::Advance a = sim.run_to(to_target ? target_ : t, &halt_, progress, &pause_);
    total.t = a.t, total.steps += a.steps, total.wall += a.wall, wall_ = total.wall;
    if (a.over_wall_limit || (stop_ && stop_->load())) {
      total.interrupted = a.interrupted, total.over_wall_limit = a.over_wall_limit;
      break;
    }
    const bool at_target = to_target && a.t >= target_;
    if (at_target) target_ = 0, publish(wall_), offer_frame();  // the page's t and picture where it pauses
    if (!at_target && a.t >= t) break;
    server_->set_status(at_target ? "paused at t = " + rounded_text(a.t, 6) + " s" : "running");
    apply_controls(at_target);
    if (stop_ && stop_->load()) {  // Ctrl-C during a pause: the run stops where it stands
      total.interrupted = true;
      break;
    }
  }
  if (changed_ && record_) record_->push_back({key_, total.t, ""});
  // a run to a later t asked from the page: this run_to (the console's, the script's) ends first;
  // the status says so, and a later run_to does not stop there
  if (target_ > total.t)
    end_note_ = " at t = " + rounded_text(total.t, 6) + " s: the page's run to " + rounded_text(target_, 6) +
                " s lies past the end of this run_to",
    target_ = 0;
  return total;
}

RunProgress LiveFeed::callback(RunProgress inner) {
  return [this, inner](double t, double target, const WorkCounters& w, double wall) {
    if (inner) inner(t, target, w, wall);
    wall += wall_;  // this run's wall time across the run_to calls a control split it into
    h_ = t - last_t_, last_t_ = t;
    if (stop_ && stop_->load()) halt_ = true;
    if (server_->commands_pending()) {
      if (pause_asked_ < 0) pause_asked_ = wall;
      pause_ = true;
      if (wall - pause_asked_ >= kPauseWait) halt_ = true;
    }
    if (wall - last_wall_ >= kInterval) {
      last_wall_ = wall;
      publish(wall);
    }
    // a frame when a page is open and has taken the last one, at most 15 a wall second and with
    // at most kFrameShare of the wall time spent drawing them
    const double cost = frames_ ? frames_->cost() : 0;
    if (wall - last_frame_ >= std::max(kFrameInterval, cost / kFrameShare)) {
      last_frame_ = wall;
      if (server_->clients() > 0 && server_->frame_wanted()) offer_frame();
    }
  };
}

Simulation::Advance run_feed(Context* ctx, LiveFeed& feed, Simulation& sim, double t, const RunProgress& progress,
                             const char* at_end) {
  if (!ctx->stop_at || !(*ctx->stop_at < t)) return feed.run_to(sim, t, progress, at_end);
  const double x = std::max(*ctx->stop_at, sim.now());
  ctx->stop_at.reset();
  Simulation::Advance a = feed.run_to(sim, x, progress, at_end);
  if (!a.interrupted && !a.over_wall_limit) {
    // ended as Ctrl-C ends it (parameters.csv's end.status "interrupted"): a run of no steps, its stop raised
    static const std::atomic<bool> raised{true};
    sim.run_to(t, &raised, {});
    a.interrupted = true, ctx->stop_made = true;
  }
  return a;
}

}  // namespace beltsim::script
