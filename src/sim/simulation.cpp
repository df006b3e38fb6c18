#include "sim/simulation.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "integrate/belt_system.hpp"
#include "integrate/cvode.hpp"
#include "integrate/driver.hpp"
#include "integrate/stepper.hpp"
#include "io/csv_writer.hpp"
#include "model/forces.hpp"
#include "model/rhs.hpp"

namespace beltsim {

namespace {

std::string span_name(const Scene& sc, size_t k) {
  return "span_" + sc.route_names[k] + "_" + sc.route_names[(k + 1) % sc.route_names.size()];
}

void write_parameters(const Scene& sc, const RunSettings& rs, const std::string& path) {
  const Model& m = sc.model;
  const Belt& b = m.belt;
  std::ofstream f(path);
  if (!f) throw std::runtime_error("cannot write " + path);
  f.precision(10);
  f << "name,value,unit,note\n";
  auto row = [&](const std::string& name, double v, const std::string& unit, const std::string& note) {
    f << csv_text(name) << ',' << v << ',' << csv_text(unit) << ',' << csv_text(note) << '\n';
  };
  auto text = [&](const std::string& name, const std::string& v, const std::string& note) {
    f << csv_text(name) << ',' << csv_text(v) << ",," << csv_text(note) << '\n';
  };
  text("stiffness_reading", sc.reading == StiffnessReading::rigidity ? "rigidity" : "per_sde",
       sc.reading == StiffnessReading::rigidity
           ? "DESIGN §2: c_tra = EA [N] and c_tor = EI [N·m²] are rigidities, b_tra is per unit length: "
             "k = EA/l, k_t = EI/l, c = b_tra/l; b_tor per SDE as printed"
           : "per-SDE stiffness and damping as given");
  row("belt.elements", b.n, "", "");
  row("belt.pitch", b.pitch, "m", "l: route length / elements");
  row("belt.rigid_length", b.rigid_length, "m", "l_e: chosen so the spans carry the pretension at rest");
  row("belt.mass", b.mass, "kg", "per element, rho·l");
  row("belt.rot_inertia", b.rot_inertia, "kg·m²", "per element, m·l_e²/12");
  row("belt.k", b.k, "N/m", "longitudinal SDE stiffness");
  row("belt.c", b.c, "N·s/m", "longitudinal SDE damping");
  row("belt.kt", b.kt, "N·m/rad", "torsional SDE stiffness");
  row("belt.ct", b.ct, "N·m·s/rad", "torsional SDE damping");
  row("belt.e_tra", b.e_tra, "", "exponent of the longitudinal spring (ours: 1, DESIGN §2)");
  row("belt.e_tor", b.e_tor, "", "exponent of the torsional spring (ours: 1, DESIGN §2)");
  row("belt.static_tension", sc.static_tension, "N", "mean span tension of the initial state");
  row("belt.static_residual", sc.static_residual, "m/s²", "largest acceleration of the initial state");
  double mu_min = 1e300, mu_max = -1;
  for (double mu : m.mu) mu_min = std::min(mu_min, mu), mu_max = std::max(mu_max, mu);
  row("belt.mu_min", mu_min, "", "");
  row("belt.mu_max", mu_max, "", "");
  row("contact.c1", m.contact.c1, "N/m²", "");
  row("contact.c2", m.contact.c2, "N/m", "");
  row("contact.damping", m.contact.b, "N·s/m", "");
  row("contact.p_max", m.contact.p_max, "m", "");
  row("friction.dv", m.friction.dv, "m/s", "");
  row("gravity", m.gravity, "m/s²", "acts along -y");
  for (size_t k = 0; k < sc.route_names.size(); ++k) {
    const int j = sc.route_pulleys[k];
    const Pulley& p = m.pulleys[j];
    const std::string pre = "pulley." + p.name + ".";
    row(pre + "centre_x", p.centre.x(), "m", "");
    row(pre + "centre_y", p.centre.y(), "m", "");
    row(pre + "radius", p.radius, "m", "");
    row(pre + "inertia", p.inertia, "kg·m²", "");
    text(pre + "wrap", p.wrap == WrapSide::inside ? "inside" : "back", "");
    text(pre + "drive", p.kinematic ? "kinematic" : "torque", "");
    row(pre + "wrap_angle", sc.route.arcs[k].angle * 180 / M_PI, "deg", "of the pitch line");
    row(pre + "static_penetration", sc.penetration[j], "m", "p0 of the initial state");
  }
  row("route.length", sc.route.length, "m", "pitch-line length");
  row("probe.element", rs.probe_element, "", "the selected element; probe.sde_force is its left SDE");
  text("run.integrator", rs.integrator, "");
  row("run.rtol", rs.rtol, "", "");
  row("run.atol", rs.atol < 0 ? rs.rtol : rs.atol, "", "per natural unit: 0.1 m, 1 rad, 1 m/s, 10 rad/s, 1 J");
  row("run.t_end", rs.t_end, "s", "");
  row("run.sample_dt", rs.sample_dt, "s", "");
}

std::string duration(double s) {
  char b[32];
  if (s < 120)
    std::snprintf(b, sizeof b, "%.0f s", s);
  else
    std::snprintf(b, sizeof b, "%.0f min %02.0f s", std::floor(s / 60), std::fmod(s, 60));
  return b;
}

}  // namespace

std::vector<std::string> timeseries_columns(const Scene& sc) {
  std::vector<std::string> c{"t"};
  for (const Pulley& p : sc.model.pulleys)
    for (const char* q : {".omega", ".torque", ".belt_torque", ".hub_load"}) c.push_back(p.name + q);
  for (size_t k = 0; k < sc.route.spans.size(); ++k) c.push_back(span_name(sc, k) + ".tension");
  for (const char* q : {"probe.sde_force", "probe.normal_force", "probe.friction_force", "probe.slip_velocity"})
    c.push_back(q);
  if (sc.model.track_energy)
    for (const char* q : {"energy.mechanical", "energy.work_torques", "energy.dissipated_axial",
                          "energy.dissipated_bending", "energy.dissipated_contact", "energy.dissipated_friction"})
      c.push_back(q);
  return c;
}

RunResult run(const Scene& sc, const RunSettings& rs, const std::atomic<bool>* stop) {
  Model m = sc.model;  // a copy: events may change μ while running
  if (!(rs.t_end > 0)) throw std::invalid_argument("run: t_end must be > 0 (got " + std::to_string(rs.t_end) + " s)");
  if (!(rs.rtol > 0 && rs.rtol < 1)) throw std::invalid_argument("run: rtol must be in (0, 1)");
  if (!(rs.sample_dt > 0)) throw std::invalid_argument("run: sample interval must be > 0");
  for (const MuEvent& ev : rs.mu_events) {
    if (!(ev.t > 0 && ev.t < rs.t_end))
      throw std::invalid_argument("run: an event time must be inside (0, t_end) (got " + std::to_string(ev.t) + " s)");
    if (static_cast<int>(ev.mu.size()) != m.n_el())
      throw std::invalid_argument("run: an event's μ needs one value per element");
  }
  if (rs.probe_element < 0 || rs.probe_element >= m.n_el())
    throw std::invalid_argument("run: probe element must be in 0.." + std::to_string(m.n_el() - 1));
  check_integrator(rs.integrator);
  const bool peer = is_cvode(rs.integrator);
  auto stepper = peer ? nullptr : make_stepper(rs.integrator);
  std::optional<FrameSettings> frames = rs.frames;
  if (frames) {
    validate(*frames);
    if (!rs.frame_factory) throw std::invalid_argument("run: frames asked for, but this program has no renderer");
    if (frames->t_start > rs.t_end)
      throw std::invalid_argument("run.frames.t_start: must be <= t_end = " + std::to_string(rs.t_end) + " s (got " +
                                  std::to_string(frames->t_start) + " s)");
    auto inside = [&](std::string& p) {
      if (!p.empty() && std::filesystem::path(p).is_relative()) p = (std::filesystem::path(rs.out_dir) / p).string();
    };
    inside(frames->png_dir);
    inside(frames->video_path);
  }

  std::filesystem::create_directories(rs.out_dir);
  RunResult res;
  res.csv_path = (std::filesystem::path(rs.out_dir) / "timeseries.csv").string();
  res.parameters_path = (std::filesystem::path(rs.out_dir) / "parameters.csv").string();
  write_parameters(sc, rs, res.parameters_path);
  CsvWriter csv(res.csv_path, timeseries_columns(sc));

  BeltSystem sys(m);
  const int N = m.n_coord();
  const double E0 = energy(m, 0.0, sc.y0.data()).total();
  std::vector<double> row;
  auto sample = [&](double t, const Eigen::VectorXd& y) {
    const double* q = y.data();
    const double* v = q + N;
    row.clear();
    row.push_back(t);
    for (int j = 0; j < m.n_p(); ++j) {
      Vec2 hub;
      const double belt = belt_torque(m, t, q, v, j, &hub);
      const Pulley& p = m.pulleys[j];
      const double applied = p.kinematic ? p.inertia * p.speed.table_slope(t) - belt : applied_torque(m, t, v, j);
      row.insert(row.end(), {m.omega(j, t, v), applied, belt, hub.norm()});
    }
    for (const Route::Span& sp : sc.route.spans)
      row.push_back(sde_axial_force(m, q, v, sde_nearest(m, q, 0.5 * (sp.from + sp.to))));
    const ElementContact c = element_contact(m, t, q, v, rs.probe_element);
    row.insert(row.end(), {sde_axial_force(m, q, v, rs.probe_element), c.normal, c.friction, c.slip});
    if (m.track_energy) {
      const double* e = q + 2 * N;
      row.insert(row.end(), {energy(m, t, q).total() - E0, e[kWorkTorques], e[kDissSdeAxial], e[kDissSdeBending],
                             e[kDissContact], e[kDissFriction]});
    }
    csv.row(row);
    if (rs.keep_samples) res.samples.push_back(row);
  };

  // progress on stderr once the run has taken more than a second
  using clock = std::chrono::steady_clock;
  const auto start = clock::now();
  auto last_report = start;
  const bool tty = isatty(STDERR_FILENO);
  bool reported = false;
  std::atomic<bool> halt{false};
  auto progress = [&](double t, const WorkCounters& w) {
    const auto now = clock::now();
    const double elapsed = std::chrono::duration<double>(now - start).count();
    if (stop && stop->load()) halt.store(true);
    if (rs.wall_limit > 0 && elapsed > rs.wall_limit) halt.store(true), res.over_wall_limit = true;
    if (!rs.progress) return;
    const double since = std::chrono::duration<double>(now - last_report).count();
    if (elapsed < 1.0 || since < (tty ? 0.5 : 10.0)) return;
    last_report = now;
    reported = true;
    const double left = t > 0 ? elapsed * (rs.t_end - t) / t : 0;
    std::fprintf(stderr, "%sbeltsim: t = %.4f s of %.4g s (%.0f %%), %s elapsed, about %s left, %ld steps%s",
                 tty ? "\r" : "", t, rs.t_end, 100 * t / rs.t_end, duration(elapsed).c_str(), duration(left).c_str(),
                 w.steps, tty ? "   " : "\n");
  };

  // the renderer exists only when frames are asked for (no GL context, no encoder otherwise)
  std::unique_ptr<FrameSink> sink;
  DriveOptions opt;
  if (frames) {
    sink = rs.frame_factory(sc, *frames);
    opt.frame_dt = frames->frame_dt();
    opt.frame_t0 = frames->t_start;
    // m: the model the integrator uses (the one events change, if any)
    opt.frame = [&](double t, const Eigen::VectorXd& y) { sink->frame(t, y.data(), m); };
  }
  opt.t_end = rs.t_end;
  opt.sample_dt = rs.sample_dt;
  opt.events = m.breakpoints();
  for (const MuEvent& ev : rs.mu_events) opt.events.push_back(ev.t);
  if (!rs.mu_events.empty())
    opt.on_event = [&](double t, Eigen::VectorXd&) {
      for (const MuEvent& ev : rs.mu_events)
        if (std::abs(ev.t - t) <= 1e-12 * std::max(1.0, t))
          for (int i = 0; i < m.n_el(); ++i)
            if (!std::isnan(ev.mu[i])) m.mu[i] = ev.mu[i];
    };
  opt.stop = &halt;
  Eigen::VectorXd y = sc.y0;
  try {
    const Tolerances tol{rs.rtol, rs.atol};
    const DriveResult dr = peer ? drive_cvode(sys, rs.integrator, tol, opt, y, sample, progress)
                                : drive(sys, *stepper, tol, opt, y, sample, progress);
    res.t_reached = dr.t_reached;
    res.interrupted = dr.interrupted && !res.over_wall_limit;
    res.wall_seconds = dr.wall_seconds;
    res.work = dr.work;
  } catch (...) {
    csv.flush();
    if (sink) {
      try {
        sink->finish();  // the video stays playable after an error or a divergence
      } catch (...) {
      }
    }
    if (reported && tty) std::fputc('\n', stderr);
    throw;
  }
  csv.flush();
  if (sink) {
    sink->finish();
    res.frames = sink->frames_written();
  }
  if (reported && tty) std::fputc('\n', stderr);
  for (int j = 0; j < m.n_p(); ++j) res.omega.push_back(m.omega(j, res.t_reached, y.data() + N));
  return res;
}

}  // namespace beltsim
