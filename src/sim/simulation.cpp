#include "sim/simulation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <limits>
#include <sstream>

#include "integrate/belt_system.hpp"
#include "integrate/make_integrator.hpp"
#include "integrate/timeline.hpp"
#include "io/csv_writer.hpp"
#include "io/output_dir.hpp"
#include "model/forces.hpp"

namespace beltsim {

namespace {

std::string span_name(const Scene& sc, size_t k) {
  return "span_" + sc.route_names[k] + "_" + sc.route_names[(k + 1) % sc.route_names.size()];
}

void write_parameters(const Scene& sc, const RunSettings& rs, const OutputDir& dir) {
  const Model& m = sc.model;
  const Belt& b = m.belt;
  std::ostringstream f;  // written whole at the end (io/row_file.hpp)
  // numbers as in timeseries.csv: the shortest decimal that reads back as the same double
  // source: "given" by the scenario, "default" taken, "derived" by the build from those, or "run"
  f << "name,value,unit,source,note\n";
  auto row = [&](const std::string& name, double v, const std::string& unit, const std::string& note) {
    f << csv_text(name) << ',' << csv_number(v) << ',' << csv_text(unit) << ",derived," << csv_text(note) << '\n';
  };
  auto text = [&](const std::string& name, const std::string& v, const std::string& note) {
    f << csv_text(name) << ',' << csv_text(v) << ",,derived," << csv_text(note) << '\n';
  };
  for (const SceneInput& in : sc.inputs) {
    f << csv_text(in.name) << ',';
    if (in.text.empty())
      f << csv_number(in.value);
    else
      f << csv_text(in.text);
    f << ',' << csv_text(in.unit) << ',' << (in.given ? "given" : "default") << ',' << csv_text(in.note) << '\n';
  }
  text("stiffness_reading", sc.reading == StiffnessReading::rigidity ? "rigidity" : "per_sde",
       sc.reading == StiffnessReading::rigidity
           ? "the paper's c_tra = EA [N] and c_tor = EI [N·m²] are rigidities, b_tra is per unit length; "
             "per SDE k = EA/l0, k_t = EI/l0, c = b_tra/l0 with l0 the rest length of an element"
           : "per-SDE stiffness and damping as given");
  row("belt.pitch", b.pitch, "m", "l: route length / elements");
  row("belt.rigid_length", b.rigid_length, "m",
      "l0: an element's rest length (its rod; the SDE is unstretched at zero gap)");
  row("belt.rest_length_total", b.rigid_length * b.n, "m", "the belt's stress-free length, n·l0");
  row("belt.strain_at_rest", b.pitch / b.rigid_length - 1, "", "route length / rest length - 1");
  row("belt.mass", b.mass, "kg", "per element, rho·l0");
  row("belt.rot_inertia", b.rot_inertia, "kg·m²", "per element, m·l0²/12");
  row("belt.k", b.k, "N/m", "longitudinal SDE stiffness");
  row("belt.c", b.c, "N·s/m", "longitudinal SDE damping");
  row("belt.kt", b.kt, "N·m/rad", "torsional SDE stiffness");
  row("belt.ct", b.ct, "N·m·s/rad", "torsional SDE damping");
  row("belt.static_tension", sc.static_tension, "N", "mean span tension of the initial state");
  row("belt.static_residual", sc.static_residual, "m/s²", "largest acceleration of the initial state");
  double mu_min = 1e300, mu_max = -1;
  for (double mu : sc.drive.mu) mu_min = std::min(mu_min, mu), mu_max = std::max(mu_max, mu);
  row("belt.mu_min", mu_min, "", "");
  row("belt.mu_max", mu_max, "", "");
  row("contact.element_c1", m.contact.c1, "N/m²", "per element");
  row("contact.element_c2", m.contact.c2, "N/m", "per element");
  row("contact.element_damping", m.contact.b, "N·s/m", "per element");
  for (size_t k = 0; k < sc.route_names.size(); ++k) {
    const int j = sc.route_pulleys[k];
    const Pulley& p = m.pulleys[j];
    const std::string pre = "pulley." + p.name + ".";
    row(pre + "centre_x", p.centre.x(), "m", "");
    row(pre + "centre_y", p.centre.y(), "m", "");
    text(pre + "drive", sc.drive.kinematic(j) ? "kinematic" : "torque", "");
    row(pre + "wrap_angle", sc.route.arcs[k].angle * 180 / M_PI, "deg", "of the pitch line");
    row(pre + "static_penetration", sc.penetration[j], "m", "p0 of the initial state");
  }
  row("route.length", sc.route.length, "m", "pitch-line length");
  for (size_t k = 0; k < rs.probes.size(); ++k) {
    const std::string name = rs.probes.size() == 1 ? std::string("probe") : "probe" + std::to_string(k + 1);
    f << name << ".element," << rs.probes[k] << ",,run,"
      << csv_text("a selected element; " + name + ".sde_force is its left SDE") << '\n';
  }
  // the run's settings (source "run")
  f << "run.integrator," << csv_text(rs.integrator) << ",,run,\n";
  f << "run.rtol," << csv_number(rs.rtol) << ",,run,\n";
  f << "run.atol," << csv_number(rs.atol < 0 ? rs.rtol : rs.atol) << ",,run,"
    << csv_text("per natural unit: 0.1 m, 1 rad, 1 m/s, 10 rad/s, 1 J") << "\n";
  f << "run.sample_dt," << csv_number(rs.sample_dt) << ",s,run,\n";
  write_file_whole(dir, "parameters.csv", f.str());
}

std::string num(double v) {
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

}  // namespace

std::vector<std::string> timeseries_columns(const Scene& sc, size_t probes) {
  std::vector<std::string> c{"t"};
  for (const Pulley& p : sc.model.pulleys)
    for (const char* q : {".omega", ".torque", ".belt_torque", ".hub_load", ".torque_mean", ".belt_torque_mean",
                          ".contact_arc", ".slip_arc", ".stick_arc", ".creep"})
      c.push_back(p.name + q);
  for (const Pulley& p : sc.model.pulleys)
    if (p.arm >= 0) c.push_back(p.name + ".arm_angle"), c.push_back(p.name + ".arm_rate");
  for (size_t k = 0; k < sc.route.spans.size(); ++k)
    for (const char* q : {".tension", ".tension_mean"}) c.push_back(span_name(sc, k) + q);
  for (size_t k = 0; k < probes; ++k)
    for (const char* q : {".sde_force", ".normal_force", ".friction_force", ".slip_velocity"})
      c.push_back((probes == 1 ? std::string("probe") : "probe" + std::to_string(k + 1)) + q);
  if (sc.model.track_energy)
    for (const char* q : {"energy.mechanical", "energy.work_torques", "energy.dissipated_axial",
                          "energy.dissipated_bending", "energy.dissipated_contact", "energy.dissipated_friction"})
      c.push_back(q);
  return c;
}

void check_volume(const Scene& sc, const RunSettings& rs, double t0, double t1) {
  if (rs.allow_large || !(t1 > t0)) return;
  constexpr double kMaxRows = 1e7, kMaxFrames = 1e5;
  const double rows = (t1 - t0) / rs.sample_dt;
  std::ostringstream m;
  if (rows > kMaxRows) {
    const double bytes = rows * static_cast<double>(timeseries_columns(sc, rs.probes.size()).size()) * 13;
    m << "sample: " << num(t1 - t0) << " s at a sample every " << num(rs.sample_dt) << " s would write " << num(rows)
      << " rows (about " << num(bytes / 1e9) << " GB of timeseries.csv); the limit is " << num(kMaxRows)
      << " rows: sample less often, or set allow_large = true";
    throw std::invalid_argument(m.str());
  }
  const double snaps = static_cast<double>(rs.snapshot_times.size()) +
                       (rs.snapshot_every > 0 ? (t1 - t0) / rs.snapshot_every : 0.0);
  if (snaps * sc.model.n_el() > kMaxRows) {
    m << "snapshots: " << num(snaps) << " snapshots of " << sc.model.n_el() << " elements would write "
      << num(snaps * sc.model.n_el()) << " rows of snapshots.csv; the limit is " << num(kMaxRows)
      << ": take fewer, or set allow_large = true";
    throw std::invalid_argument(m.str());
  }
  if (rs.frames) {
    const double frames = std::max(0.0, t1 - std::max(t0, rs.frames->t_start)) / rs.frames->frame_dt();
    if (frames > kMaxFrames) {
      m << "frames: " << num(t1 - t0) << " s at " << num(rs.frames->fps) << " fps and slowdown "
        << num(rs.frames->slowdown) << " would render " << num(frames) << " frames (" << num(frames / rs.frames->fps / 3600)
        << " h of video); the limit is " << num(kMaxFrames) << ": lower the slowdown, or set allow_large = true";
      throw std::invalid_argument(m.str());
    }
  }
}

Simulation::Simulation(const Scene& sc, const RunSettings& rs) : Simulation(sc, rs, true) {}

Simulation::Simulation(const Scene& sc, const RunSettings& rs, bool fresh) : scene_(sc), rs_(rs), drive_(sc.drive) {
  const Model& m = model_;
  if (!(rs_.sample_dt > 0 && std::isfinite(rs_.sample_dt)))
    throw std::invalid_argument("sample: the sample interval must be > 0 s and finite (got " + num(rs_.sample_dt) + " s)");
  if (rs_.probes.empty()) throw std::invalid_argument("probe: at least one element to probe");
  for (size_t k = 0; k < rs_.probes.size(); ++k)
    if (rs_.probes[k] < 0 || rs_.probes[k] >= m.n_el())
      throw std::invalid_argument("probe: the probe element must be in 0.." + std::to_string(m.n_el() - 1) + " (got " +
                                  std::to_string(rs_.probes[k]) +
                                  (rs_.probes.size() > 1 ? " for probe " + std::to_string(k + 1) : std::string()) + ")");
  for (size_t k = 0; k < rs_.snapshot_times.size(); ++k) {
    const double t = rs_.snapshot_times[k];
    if (!(t >= 0 && std::isfinite(t)))
      throw std::invalid_argument("snapshots.times[" + std::to_string(k + 1) + "]: must be >= 0 s and finite (got " +
                                  num(t) + " s)");
    if (k > 0 && !(t > rs_.snapshot_times[k - 1]))
      throw std::invalid_argument("snapshots.times[" + std::to_string(k + 1) + "]: the times must increase (got " +
                                  num(t) + " s after " + num(rs_.snapshot_times[k - 1]) + " s)");
  }
  if (!(rs_.snapshot_every >= 0 && std::isfinite(rs_.snapshot_every)))
    throw std::invalid_argument("snapshots.every: must be > 0 s and finite (got " + num(rs_.snapshot_every) + " s)");
  for (const MuEvent& ev : rs_.mu_events) {
    if (!(ev.t > 0 && std::isfinite(ev.t)))
      throw std::invalid_argument("events: an event time must be > 0 s and finite (got " + num(ev.t) + " s)");
    if (static_cast<int>(ev.mu.size()) != m.n_el())
      throw std::invalid_argument("events: an event's μ needs one value per element");
  }
  sense_ = scene_.senses();
  sys_ = std::make_unique<BeltSystem>(model_, drive_);
  integ_ = make_integrator(rs_.integrator, *sys_, Tolerances{rs_.rtol, rs_.atol});
  tl_ = std::make_unique<Timeline>(*integ_);
  tl_->on_restart([this](double t) { drive_.restart_time = t; });
  if (rs_.frames) {
    FrameSettings& f = *rs_.frames;
    validate(f);
    if (!rs_.frame_factory) throw std::invalid_argument("frames: asked for, but this program has no renderer");
    auto inside = [&](std::string& p) {
      if (!p.empty() && std::filesystem::path(p).is_relative()) p = (std::filesystem::path(rs_.out_dir) / p).string();
    };
    inside(f.png_dir);
    inside(f.video_path);
  }
  mean_acc_.assign(2 * m.n_p() + scene_.route.spans.size(), 0.0);
  tl_->set_step_hook([this](double t) { cover(t); });
  pending_ = rs_.mu_events;
  std::stable_sort(pending_.begin(), pending_.end(), [](const MuEvent& a, const MuEvent& b) { return a.t < b.t; });
  E0_ = beltsim::energy(model_, drive_, 0.0, scene_.y0.data()).total();
  if (!fresh) return;  // resume() fills in the rest

  open_outputs(false);
  add_streams();
  set_landings();
  try {
    tl_->start(0.0, scene_.y0);
  } catch (...) {
    close();
    throw;
  }
}

Simulation::~Simulation() {
  try {
    close();
  } catch (...) {
  }
}

// the output folder, made when missing and held by this simulation alone (io/output_dir.hpp: a
// second simulation on it is refused before it writes anything; never through a link)
void Simulation::claim_out_dir() {
  if (out_) return;
  auto dir = std::make_unique<OutputDir>(rs_.out_dir);
  dir->lock();
  out_ = std::move(dir);
}

void Simulation::open_outputs(bool append) {
  claim_out_dir();
  // the renderer first (it opens the video file and the PNG folder): a bad frames path stops the
  // run before any CSV is written. It exists only when frames are asked for (no GL context, no
  // encoder otherwise).
  if (rs_.frames) sink_ = rs_.frame_factory(scene_, *rs_.frames);
  if (!append) write_parameters(scene_, rs_, *out_);
  csv_ = std::make_unique<CsvWriter>(*out_, "timeseries.csv", columns(), append);
  events_ = std::make_unique<RowFile>(*out_, "events.csv", append);
  if (!append) events_->write("t,what,value\n");
  if (has_snapshots()) {
    snapshots_ = std::make_unique<RowFile>(*out_, "snapshots.csv", append);
    if (!append) snapshots_->write("t,element,s,x,y,tension,normal,friction,slip,mu,pulley,state\n");
  }
}

// the outputs' streams, in an order checkpoints rely on: samples, frames, snapshots every dt,
// snapshots at listed times
void Simulation::add_streams() {
  tl_->add_stream(0.0, rs_.sample_dt, [this](double t, const Eigen::VectorXd& y) { sample(t, y); });
  if (sink_)
    tl_->add_stream(rs_.frames->t_start, rs_.frames->frame_dt(),
                    [this](double t, const Eigen::VectorXd& y) { frame(t, y); });
  if (rs_.snapshot_every > 0)
    tl_->add_stream(0.0, rs_.snapshot_every, [this](double t, const Eigen::VectorXd& y) { snapshot(t, y); });
  if (!rs_.snapshot_times.empty())
    tl_->add_times(rs_.snapshot_times, [this](double t, const Eigen::VectorXd& y) { snapshot(t, y); });
}

bool Simulation::has_snapshots() const { return rs_.snapshot_every > 0 || !rs_.snapshot_times.empty(); }

std::string Simulation::csv_path() const { return (std::filesystem::path(rs_.out_dir) / "timeseries.csv").string(); }
std::string Simulation::snapshots_path() const {
  return (std::filesystem::path(rs_.out_dir) / "snapshots.csv").string();
}
std::string Simulation::events_path() const { return (std::filesystem::path(rs_.out_dir) / "events.csv").string(); }
long Simulation::frames_written() const { return frames_before_ + (sink_ ? sink_->frames_written() : 0); }
const std::string& Simulation::integrator_name() const { return rs_.integrator; }

// the kinks of the laws, their jumps and the timed μ changes ahead: the integrator lands on each
void Simulation::set_landings() {
  std::vector<Timeline::Landing> l;
  for (double t : drive_.breakpoints()) l.push_back({t, {}});
  // a step of a law: the step that ends here saw the value before it; the integrator restarts
  // here after it (Drive::restart_time). A kinematic pulley's state speed, which nothing reads
  // (its prescribed one is used), is kept equal to it.
  for (double t : drive_.jumps())
    l.push_back({t, [this](double at) {
                   Eigen::VectorXd y = state();
                   drive_.restart_time = at;
                   for (int j = 0; j < model_.n_p(); ++j)
                     if (drive_.kinematic(j))
                       y[model_.n_coord() + model_.pulley_coord(j)] =
                           drive_.omega(model_, j, at, y.data() + model_.n_coord());
                   changed(&y);
                 }});
  for (size_t k = 0; k < pending_.size(); ++k)
    l.push_back({pending_[k].t, [this](double t) {
                   // every μ event due now, in the order given
                   while (!pending_.empty() && pending_.front().t <= t) {
                     const MuEvent ev = pending_.front();
                     pending_.erase(pending_.begin());
                     for (int i = 0; i < model_.n_el(); ++i)
                       if (!std::isnan(ev.mu[i])) drive_.mu[i] = ev.mu[i];
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
  if (c.t == t && c.serial == serial_ && c.step_end == integ_->t() && !view_y_) return c.obs;
  observe(model_, drive_, sense_, t, state().data(), c.obs);
  const double a = integ_->t_prev(), b = integ_->t();
  if (t > a && t < b) {
    // end_b_ of one step is end_a_ of the next: swap rather than observe again
    if (end_b_.t == a && end_b_.serial == serial_) std::swap(end_a_, end_b_);
    const Observation& A = observe_end(end_a_, a, integ_->y_prev());
    const Observation& B = observe_end(end_b_, b, integ_->y());
    blend_contact(model_, drive_, (t - a) / (b - a), A, B, c.obs);
  }
  c.t = view_y_ ? -1 : t, c.serial = serial_, c.step_end = b;  // a when-condition's view is not kept
  return c.obs;
}

std::vector<double> Simulation::sample_row() const {
  const Model& m = model_;
  const double t = now();
  const Eigen::VectorXd& y = state();
  const double* q = y.data();
  const Observation& o = observation();
  // the interval means since the last sample (NaN in the first row: no interval yet)
  const std::vector<double> integral = integral_to(t);
  const double dt = t - mean_from_;
  auto mean = [&](size_t k) { return dt > 0 ? integral[k] / dt : std::numeric_limits<double>::quiet_NaN(); };
  std::vector<double> row;
  row.push_back(t);
  for (size_t j = 0; j < o.pulleys.size(); ++j) {
    const PulleyObs& p = o.pulleys[j];
    row.insert(row.end(), {p.omega, p.torque, p.belt_torque, p.hub_load, mean(2 * j), mean(2 * j + 1), p.contact_arc,
                           p.slip_arc, p.stick_arc, p.creep});
  }
  for (size_t j = 0; j < o.pulleys.size(); ++j)
    if (m.pulleys[j].arm >= 0) row.insert(row.end(), {o.pulleys[j].arm_angle, o.pulleys[j].arm_rate});
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
  }
  return row;
}

// ---- interval means ---------------------------------------------------------------------------
// A force sampled at an instant aliases the element-passing frequency; the mean over the sample
// interval [t_{k-1}, t_k] does not. It is integrated over the integrator's accepted steps: in a
// step [a, b] each quantity is the straight line between its step-end values (exactly what
// blend_contact shows inside the step), so over [c, d] ⊂ [a, b]
//   ∫_c^d f dt = (d − c)·(f(c) + f(d))/2,   f(τ) = f_a + (τ − a)/(b − a)·(f_b − f_a)
// (the trapezoid rule on the step-end values). mean_acc_ holds ∫ from the last sample to
// mean_covered_ (inside the held step); cover() moves it on before the step is replaced (a new step
// or a restart, Timeline's step hook) and the sample reads it. Averaged: each pulley's torque and
// belt torque, each span's tension (at a free pulley I·dΩ/dt = M + M_belt, so over an interval
// mean(M) + mean(M_belt) = I·ΔΩ/Δt to the integrator's accuracy: tested).

const std::vector<double>& Simulation::step_values(StepEnd& c, double t, const Eigen::VectorXd& y) const {
  if (c.t == t && c.serial == serial_) return c.v;
  c.v.clear();
  observe_pulleys(model_, drive_, t, y.data(), c.pairs, c.pulleys);
  for (const PulleyObs& p : c.pulleys) {
    c.v.push_back(p.torque);
    c.v.push_back(p.belt_torque);
  }
  for (const Route::Span& sp : scene_.route.spans) c.v.push_back(span_force(model_, sp, y.data()));
  c.t = t, c.serial = serial_;
  return c.v;
}

std::vector<double> Simulation::integral_to(double t) const {
  std::vector<double> out = mean_acc_;
  const double a = integ_->t_prev(), b = integ_->t();
  const double c = std::max(mean_covered_, a), d = std::min(t, b);
  if (!(b > a) || !(d > c)) return out;
  // the last step's end is this step's start
  if (!(step_a_.t == a && step_a_.serial == serial_) && step_b_.t == a && step_b_.serial == serial_)
    std::swap(step_a_, step_b_);
  const std::vector<double>& fa = step_values(step_a_, a, integ_->y_prev());
  const std::vector<double>& fb = step_values(step_b_, b, integ_->y());
  const double tc = (c - a) / (b - a), td = (d - a) / (b - a);
  for (size_t k = 0; k < out.size(); ++k) {
    const double f_c = fa[k] + tc * (fb[k] - fa[k]), f_d = fa[k] + td * (fb[k] - fa[k]);
    out[k] += 0.5 * (d - c) * (f_c + f_d);
  }
  return out;
}

void Simulation::cover(double t) {
  if (t <= mean_covered_) return;
  mean_acc_ = integral_to(t);
  mean_covered_ = t;
}

void Simulation::frame(double t, const Eigen::VectorXd& y) {
  view_t_ = t, view_y_ = &y;
  try {
    sink_->frame(t, y.data(), drive_, &observation());
  } catch (...) {
    view_y_ = nullptr;
    throw;
  }
  view_y_ = nullptr;
}

void Simulation::sample(double t, const Eigen::VectorXd& y) {
  view_t_ = t, view_y_ = &y;
  std::vector<double> row;
  try {
    row = sample_row();
  } catch (...) {
    view_y_ = nullptr;
    throw;
  }
  view_y_ = nullptr;
  csv_->row(row);
  // the next interval starts here
  std::fill(mean_acc_.begin(), mean_acc_.end(), 0.0);
  mean_covered_ = mean_from_ = t;
  rows_++;
  if (rs_.keep_samples) samples_.push_back(std::move(row));
}

// one row per element, all written by one write(2) (io/row_file.hpp): the file holds whole
// snapshots. Columns (SI, docs/outputs.md): t [s], element, s [m] (where it started along the
// belt), x, y [m], tension, normal, friction [N], slip [m/s], mu, pulley (name, empty when free),
// state (free, stick, slip: model/observables.hpp)
void Simulation::snapshot(double t, const Eigen::VectorXd& y) {
  view_t_ = t, view_y_ = &y;
  std::string rows;
  try {
    const Observation& o = observation();
    for (size_t i = 0; i < o.elements.size(); ++i) {
      const ElementObs& e = o.elements[i];
      append_csv_number(rows, t);
      rows += ',' + std::to_string(i) + ',';
      for (double v : {scene_.sites[i].s, e.x, e.y, e.tension, e.normal, e.friction, e.slip, e.mu}) {
        append_csv_number(rows, v);
        rows += ',';
      }
      if (e.pulley >= 0) rows += csv_text(model_.pulleys[e.pulley].name);
      rows += ',';
      rows += contact_state_name(e.state);
      rows += '\n';
    }
  } catch (...) {
    view_y_ = nullptr;
    throw;
  }
  view_y_ = nullptr;
  snapshots_->write(rows);
}

double Simulation::now() const { return view_y_ ? view_t_ : tl_->now(); }
const Eigen::VectorXd& Simulation::state() const { return view_y_ ? *view_y_ : tl_->state(); }

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
  if (closed_) throw std::logic_error(std::string(what) + ": the simulation is closed");
  if (!failed_.empty()) throw std::logic_error(std::string(what) + ": the simulation cannot continue: " + failed_);
}

Simulation::Advance Simulation::run_to(double t, const std::atomic<bool>* stop, const RunProgress& progress) {
  require_open("run_to");
  if (!std::isfinite(t)) throw std::invalid_argument("run_to: the time must be finite (got " + num(t) + " s)");
  if (t < now()) throw std::invalid_argument("run_to: " + num(t) + " s is before now (" + num(now()) + " s)");
  if (running_) throw std::logic_error("run_to: the simulation is already running (called from a callback?)");
  check_volume(scene_, rs_, now(), t);
  struct Running {
    bool& r;
    explicit Running(bool& b) : r(b) { r = true; }
    ~Running() { r = false; }
  } running(running_);
  const auto steady = [] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  };
  const std::function<double()> clock = rs_.wall_clock ? rs_.wall_clock : std::function<double()>(steady);
  const double start = clock();
  Timeline::Progress pr;
  if (progress) pr = [&](double tt, const WorkCounters& w) { progress(tt, t, w, clock() - start); };
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
        throw DivergenceError(tt, "no progress at t = " + num(tt) + " s: " + num(tt - win_t) + " s simulated in the last " +
                                      num(wall - win_wall) + " s of wall time, against " + num(best_rate_) +
                                      " s per second earlier in this run; the largest error is in " +
                                      (worst.empty() ? std::string("a component the integrator does not name") : worst) +
                                      "; try an implicit integrator (esdirk32, or cvode), a looser rtol or atol, "
                                      "or more damping of that component");
      }
      best_rate_ = std::max(best_rate_, rate);
      win_wall = wall, win_t = tt;
    }
    return false;
  };
  try {
    const Timeline::Result r = tl_->run_to(t, stop, pr, poll);
    a.t = r.t, a.steps = r.steps, a.wall = r.wall, a.interrupted = r.interrupted;
  } catch (const DivergenceError& e) {
    failed_ = e.what();
    wall_ += clock() - start;
    close();  // CSV flushed, video finalised so it plays
    throw;
  } catch (const LawError& e) {
    // a law's code failed (a Lua law raised or returned no number): the run cannot go on
    failed_ = e.what();
    wall_ += clock() - start;
    close();
    throw;
  } catch (...) {
    wall_ += clock() - start;
    csv_->flush();
    throw;
  }
  wall_ += a.wall;
  csv_->flush();
  return a;
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
    if (st.count == 0) continue;
    s += (s.empty() ? "" : ", ") + std::string(i.name) + " " + std::to_string(st.count) + (st.count == 1 ? " time" : " times") +
         " (first at t = " + num(st.first_t) + " s)";
  }
  if (s.empty()) return s;
  return "warnings: " + s + "; these fallbacks are described in " +
         (std::filesystem::path(rs_.out_dir) / "parameters.csv").string() + " (warning.*)";
}

void Simulation::close() {
  if (closed_) return;
  closed_ = true;
  // each output is closed whatever happened to the one before; the first failure is thrown at
  // the end (each is recorded, io/output_dir.hpp, so the program's exit status says so)
  std::exception_ptr failed;
  try {
    if (sink_) sink_->finish();  // first: a full disk below must not leave the video unfinished
  } catch (...) {
    failed = std::current_exception();
  }
  try {
    if (csv_) {  // the fallbacks, beside the parameters they qualify (whole rows, one write)
      std::ostringstream f;
      const Warnings w = warnings();
      for (const WarningKindInfo& i : warning_kinds()) {
        const WarningStat& s = w[i.kind];
        f << "warning." << i.name << ".count," << s.count << ",,derived," << csv_text(i.description) << '\n'
          << "warning." << i.name << ".first_t," << (s.count > 0 ? csv_number(s.first_t) : std::string())
          << ",s,derived," << "simulated time it first fired (empty: never)\n";
      }
      RowFile(*out_, "parameters.csv", true).write(f.str());
    }
  } catch (...) {
    if (!failed) failed = std::current_exception();
  }
  out_.reset();  // the folder is free for another simulation: this one writes nothing more
  if (failed) std::rethrow_exception(failed);
}

void Simulation::write_event(double t, const std::string& what, const std::string& text) {
  if (!events_) return;
  events_->write(csv_number(t) + ',' + csv_text(what) + ',' + csv_text(text) + '\n');
}

void Simulation::log_event(const std::string& what, const std::string& text) {
  require_open("log");
  write_event(now(), what, text);
}

void Simulation::changed(const Eigen::VectorXd* y) {
  cover(now());  // the held step, as it was, up to the change
  serial_++;
  set_landings();
  tl_->changed(y);
}

void Simulation::set_torque(int j, const TimeSpeedLaw& law, const std::string& text) {
  require_open("set_torque");
  PulleyDrive& p = drive_.pulleys.at(j);
  p.torque = law;
  const bool was_kinematic = p.kinematic;
  p.kinematic = false;
  write_event(now(), model_.pulleys[j].name + ".torque", text);
  if (was_kinematic) {
    // it turns freely from here, at the speed it was driven at
    Eigen::VectorXd y = state();
    y[model_.n_coord() + model_.pulley_coord(j)] = p.speed.eval(now(), 0.0, true);
    changed(&y);
  } else {
    changed();
  }
}

void Simulation::set_speed(int j, const TimeSpeedLaw& law, const std::string& text) {
  require_open("set_speed");
  PulleyDrive& p = drive_.pulleys.at(j);
  p.speed = law;
  p.speed.per_speed = 0;
  p.kinematic = true;
  write_event(now(), model_.pulleys[j].name + ".speed", text);
  Eigen::VectorXd y = state();
  y[model_.n_coord() + model_.pulley_coord(j)] = p.speed.eval(now(), 0.0, true);  // it restarts here
  changed(&y);
}

void Simulation::set_arm(int j, std::optional<double> angle, std::optional<double> rate) {
  require_open("set_arm");
  const int a = model_.pulleys.at(j).arm;
  if (a < 0) throw std::invalid_argument("pulley '" + model_.pulleys[j].name + "' has no tensioner arm");
  Eigen::VectorXd y = state();
  const int k = model_.arm_coord(a);
  std::string text;
  if (angle) y[k] = *angle, text += "angle " + std::to_string(*angle) + " rad";
  if (rate) y[model_.n_coord() + k] = *rate, text += std::string(text.empty() ? "" : ", ") + "rate " + std::to_string(*rate) + " rad/s";
  write_event(now(), model_.pulleys[j].name + ".arm", text);
  changed(&y);
}

void Simulation::set_mu(const std::vector<double>& mu, const std::string& what, const std::string& text) {
  require_open(what.c_str());
  if (static_cast<int>(mu.size()) != model_.n_el())
    throw std::invalid_argument(what + ": one μ per element expected (" + std::to_string(model_.n_el()) + "), got " +
                                std::to_string(mu.size()));
  for (size_t i = 0; i < mu.size(); ++i)
    if (!std::isnan(mu[i]) && !(mu[i] >= 0 && std::isfinite(mu[i])))
      throw std::invalid_argument(what + ": μ must be >= 0 and finite (got " + num(mu[i]) + " for element " +
                                  std::to_string(i) + ")");
  for (size_t i = 0; i < mu.size(); ++i)
    if (!std::isnan(mu[i])) drive_.mu[i] = mu[i];
  write_event(now(), what, text);
  changed();
}

int Simulation::every(double dt, std::function<void()> fn) {
  require_open("every");
  if (!(dt > 0 && std::isfinite(dt))) throw std::invalid_argument("every: the interval must be > 0 s and finite (got " + num(dt) + " s)");
  callbacks_++;
  return tl_->add_every(dt, [fn = std::move(fn)](double) { fn(); });
}

int Simulation::when(std::function<bool()> cond, std::function<void()> action) {
  require_open("when");
  callbacks_++;
  auto c = [this, cond = std::move(cond)](double t, const Eigen::VectorXd& y) {
    const double saved_t = view_t_;
    const Eigen::VectorXd* saved_y = view_y_;
    view_t_ = t, view_y_ = &y;
    struct Restore {
      Simulation* s;
      double t;
      const Eigen::VectorXd* y;
      ~Restore() { s->view_t_ = t, s->view_y_ = y; }
    } restore{this, saved_t, saved_y};
    return cond();
  };
  return tl_->add_when(std::move(c), [action = std::move(action)](double) { action(); });
}

bool Simulation::cancel(int id) {
  const bool removed = tl_->remove(id);
  if (removed) callbacks_--;
  return removed;
}

std::vector<std::string> drop_events_after_end(RunSettings& rs) {
  std::vector<std::string> notes;
  std::vector<MuEvent> kept;
  for (const MuEvent& ev : rs.mu_events) {
    if (ev.t < rs.t_end || !std::isfinite(ev.t)) {
      kept.push_back(ev);
      continue;
    }
    notes.push_back("events: the event at " + num(ev.t) + " s (" + ev.what + ") is at or after t_end = " +
                    num(rs.t_end) + " s: skipped");
  }
  rs.mu_events = std::move(kept);
  return notes;
}

RunResult run(const Scene& sc, const RunSettings& settings, const std::atomic<bool>* stop,
              const RunProgress& progress) {
  RunSettings rs = settings;
  std::vector<std::string> skipped = drop_events_after_end(rs);
  if (!(rs.t_end > 0 && std::isfinite(rs.t_end)))
    throw std::invalid_argument("t_end: must be > 0 s and finite (got " + num(rs.t_end) + " s)");
  if (rs.frames && rs.frames->t_start > rs.t_end)
    throw std::invalid_argument("frames.t_start: must be <= t_end = " + num(rs.t_end) + " s (got " +
                                num(rs.frames->t_start) + " s)");
  for (size_t k = 0; k < rs.snapshot_times.size(); ++k)
    if (rs.snapshot_times[k] > rs.t_end)
      throw std::invalid_argument("snapshots.times[" + std::to_string(k + 1) + "]: must be <= t_end = " + num(rs.t_end) +
                                  " s (got " + num(rs.snapshot_times[k]) + " s)");
  for (const MuEvent& ev : rs.mu_events)
    if (!(ev.t > 0 && ev.t < rs.t_end))
      throw std::invalid_argument("events: an event time must be inside (0, t_end) (got " + num(ev.t) + " s)");
  check_volume(sc, rs, 0.0, rs.t_end);
  Simulation sim(sc, rs);
  RunResult res;
  res.skipped = std::move(skipped);
  res.csv_path = sim.csv_path();
  res.parameters_path = (std::filesystem::path(rs.out_dir) / "parameters.csv").string();
  // the wall-time limit stops the run as Ctrl-C does (Simulation::run_to)
  const Simulation::Advance a = sim.run_to(rs.t_end, stop, progress);
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
  for (int j = 0; j < sc.model.n_p(); ++j) res.omega.push_back(sim.pulley(j).omega);
  return res;
}

}  // namespace beltsim
