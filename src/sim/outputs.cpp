#include "sim/outputs.hpp"

#include <sys/statvfs.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string_view>

#include "integrate/controller.hpp"
#include "io/csv_writer.hpp"
#include "io/number_text.hpp"
#include "io/output_dir.hpp"
#include "io/suggest.hpp"
#include "io/units.hpp"
#include "scene/law_text.hpp"
#include "scene/scene.hpp"
#include "sim/run_table.hpp"

namespace beltsim {

namespace {

// snapshots.csv's columns (Outputs::snapshot writes them in this order); pulley and state are text
constexpr const char* kSnapshotColumns[] = {"t",      "element",  "s",    "x",  "y",      "tension",
                                            "normal", "friction", "slip", "mu", "pulley", "state"};

// a probe's column prefix: "probe" when the run has one, "probe1", "probe2", ... when more
std::string probe_name(size_t k, size_t probes) {
  return probes == 1 ? std::string("probe") : "probe" + std::to_string(k + 1);
}

// parameters.csv as written at the run's start; returns its text
std::string write_parameters(const Scene& sc, const RunSettings& rs, const OutputDir& dir) {
  const Model& m = sc.model;
  const Belt& b = m.belt;
  std::ostringstream f;  // written whole at the end (io/row_file.hpp)
  // numbers as in timeseries.csv: the shortest decimal that reads back as the same double
  // source: "given" by the scenario, "preset" by its belt preset, "default" taken, "derived" by the
  // build from those, or "run"
  f << "name,value,unit,source,note\n";
  auto row = [&](const std::string& name, double v, const std::string& unit, const std::string& note) {
    f << csv_text(name) << ',' << value_text(v) << ',' << csv_text(unit) << ",derived," << csv_text(note) << '\n';
  };
  auto text = [&](const std::string& name, const std::string& v, const std::string& note,
                  const std::string& unit = "") {
    f << csv_text(name) << ',' << csv_text(v) << ',' << csv_text(unit) << ",derived," << csv_text(note) << '\n';
  };
  for (const SceneInput& in : sc.inputs) {
    f << csv_text(in.name) << ',';
    if (in.text.empty())
      f << value_text(in.value);
    else
      f << csv_text(in.text);
    f << ',' << csv_text(in.unit) << ','
      << (!in.derived.empty()  ? "derived"
          : !in.preset.empty() ? "preset"
          : in.given           ? "given"
                               : "default")
      << ',' << csv_text(in.preset.empty() ? in.note : in.note + "; from the " + in.preset + " preset") << '\n';
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
    const PulleyDrive& pd = sc.drive.pulleys[j];
    text(pre + "drive", pd.kinematic ? "kinematic" : "torque", "");
    // the law as the scene reads it (a pulley given none turns freely: torque 0)
    text(pre + (pd.kinematic ? "speed" : "torque"), law_text(pd.kinematic ? pd.speed : pd.torque),
         pd.kinematic ? "its law at the start of the run (docs/lua-api.md, Laws)"
                      : "its law at the start of the run (docs/lua-api.md, Laws); per_speed terms in N·m·s/rad",
         pd.kinematic ? "rad/s" : "N·m");
    row(pre + "wrap_angle", sc.route.arcs[k].angle * 180 / M_PI, "deg", "of the pitch line");
    row(pre + "static_penetration", sc.penetration[j], "m", "p0 of the initial state");
    if (p.arm >= 0) {
      const Arm& a = m.arms[p.arm];
      row(pre + "tensioner.pivot_x", a.pivot.x(), "m", "");
      row(pre + "tensioner.pivot_y", a.pivot.y(), "m", "");
      row(pre + "tensioner.length", a.length, "m", "the arm: pivot to the pulley's centre");
      row(pre + "tensioner.free_angle", a.free_angle, "rad",
          "psi_0, the spring's free angle (counter-clockwise from +x; the arm starts at "
          "atan2 of centre - pivot)");
    }
  }
  for (size_t k = 0; k < sc.drive.spray.zones.size(); ++k) {
    const std::string pre = "spray." + std::to_string(k + 1) + ".";
    row(pre + "centre_x", sc.drive.spray.zones[k].centre.x(), "m", "");
    row(pre + "centre_y", sc.drive.spray.zones[k].centre.y(), "m", "");
  }
  row("route.length", sc.route.length, "m", "pitch-line length");
  for (size_t k = 0; k < rs.probes.size(); ++k) {
    const std::string name = probe_name(k, rs.probes.size());
    f << name << ".element," << rs.probes[k] << ",,run,"
      << csv_text("a selected element; " + name + ".sde_force is its left SDE") << '\n';
  }
  // every setting the run used (source "run"), from the run-settings table (sim/run_table.hpp)
  for (const RunSetting& s : run_settings())
    f << "run." << s.key << "," << csv_text(run_value_text(s, rs)) << "," << s.unit << ",run,"
      << csv_text(std::string(s.note)) << '\n';
  std::string written = f.str();
  WholeFile file(dir, "parameters.csv");
  file.write(written);
  // the rows close() appends (the fallbacks, a check's, how the run ended: about 3 KB) find room
  // on a disk that has filled meanwhile: a run stopped by a full disk still says how it ended
  file.reserve(kParametersTail);
  file.commit();
  return written;
}

// a name PREFIX, at least five digits, SUFFIX (frame_00012.png, state_00003.ckpt): a run's
// numbered file (remove_numbered)
std::function<bool(const std::string&)> numbered(std::string prefix, std::string suffix) {
  return [prefix = std::move(prefix), suffix = std::move(suffix)](const std::string& n) {
    if (n.size() <= prefix.size() + suffix.size() || n.compare(0, prefix.size(), prefix) != 0 ||
        n.compare(n.size() - suffix.size(), suffix.size(), suffix) != 0)
      return false;
    const std::string digits = n.substr(prefix.size(), n.size() - prefix.size() - suffix.size());
    return digits.size() >= 5 && digits.find_first_not_of("0123456789") == std::string::npos;
  };
}

// the name of PATH in the folder DIR when it lies directly in it ("v.mp4" for out/v.mp4 and out
// "out"), else ""
std::string name_in(const std::string& dir, const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path p = fs::absolute(path, ec).lexically_normal(), d = fs::absolute(dir, ec).lexically_normal();
  return (p.parent_path() / "") == (d / "") ? p.filename().string() : std::string();
}

}  // namespace

std::string picture_name(const std::string& kind, double t, int k) {
  char b[32];
  std::snprintf(b, sizeof b, "%.6f", t);
  return kind + "_" + b + (k > 1 ? "_" + std::to_string(k) : std::string()) + ".png";
}

bool is_picture_name(const std::string& name) {
  std::string_view n = name;
  const auto digits = [&n] {  // takes the digits at n's start: how many
    size_t k = 0;
    while (k < n.size() && n[k] >= '0' && n[k] <= '9') ++k;
    n.remove_prefix(k);
    return k;
  };
  if (!(n.substr(0, 5) == "show_" || n.substr(0, 5) == "plot_")) return false;
  n.remove_prefix(5);
  if (digits() == 0 || n.substr(0, 1) != ".") return false;
  n.remove_prefix(1);
  if (digits() != 6) return false;
  if (n.substr(0, 1) == "_") {
    n.remove_prefix(1);
    if (digits() == 0) return false;
  }
  return n == ".png";
}

std::string span_name(const Scene& sc, size_t k) {
  return "span_" + sc.route_names[k] + "_" + sc.route_names[(k + 1) % sc.route_names.size()];
}

std::vector<std::string> timeseries_columns(const Scene& sc, size_t probes) {
  std::vector<std::string> c{"t"};
  for (const Pulley& p : sc.model.pulleys)
    for (const char* q :
         {".omega", ".torque", ".belt_torque", ".hub_load", ".torque_mean", ".belt_torque_mean", ".contact_arc",
          ".slip_arc", ".stick_arc", ".creep", ".slip_speed", ".creep_pitch", ".slip_pitch", ".mu"})
      c.push_back(p.name + q);
  for (const Pulley& p : sc.model.pulleys)
    if (p.arm >= 0) c.push_back(p.name + ".arm_angle"), c.push_back(p.name + ".arm_rate");
  for (const Pulley& p : sc.model.pulleys)
    if (p.coupling >= 0)
      for (const char* q : {".rotor_angle", ".rotor_speed", ".windup", ".coupling_torque"}) c.push_back(p.name + q);
  for (size_t k = 0; k < sc.route.spans.size(); ++k)
    for (const char* q : {".tension", ".tension_mean"}) c.push_back(span_name(sc, k) + q);
  for (size_t k = 0; k < probes; ++k)
    for (const char* q : {".sde_force", ".normal_force", ".friction_force", ".slip_velocity"})
      c.push_back(probe_name(k, probes) + q);
  if (sc.model.track_energy) {
    for (const char* q : {"energy.mechanical", "energy.work_torques", "energy.dissipated_axial",
                          "energy.dissipated_bending", "energy.dissipated_contact", "energy.dissipated_friction"})
      c.push_back(q);
    // the arms' and couplings' losses, where the drive has them (Simulation::sample_row writes them alike)
    if (sc.model.n_arm() > 0) c.push_back("energy.dissipated_arms");
    if (sc.model.n_coupling() > 0) c.push_back("energy.dissipated_couplings");
  }
  return c;
}

Outputs::Outputs(const Scene& sc, const RunSettings& rs) : scene_(sc), rs_(rs) {}

Outputs::~Outputs() = default;

const OutputDir& Outputs::claim(bool make) {
  if (!dir_) {
    auto dir = std::make_unique<OutputDir>(rs_.out_dir, make);
    dir->lock();
    dir_ = std::move(dir);
    if (rs_.on_claimed) rs_.on_claimed();
  }
  return *dir_;
}

void Outputs::open(bool append) {
  const OutputDir& dir = claim();
  // it exists only when frames are asked for (no GL context, no encoder otherwise); the settings
  // keep the paths as given (checkpoints store them so), relative ones taken inside the folder
  if (rs_.frames && rs_.frames->draws()) {
    FrameSettings f = *rs_.frames;
    for (std::string* p : {&f.png_dir, &f.video_path})
      if (!p->empty()) *p = output_path(rs_, *p);
    // an earlier run's frames go, and with them the difference images beltsim compare drew of
    // them (frame_NNNNN_diff.png): of frames no longer there, they stayed after a passing run
    if (!append && !f.png_dir.empty()) {
      const auto frame = numbered("frame_", ".png"), diff = numbered("frame_", "_diff.png");
      remove_numbered(OutputDir(f.png_dir), [&](const std::string& n) { return frame(n) || diff(n); });
    }
    sink_ = rs_.frame_factory(scene_, f);
  }
  if (rs_.keep_states) {
    states_ = std::make_unique<OutputDir>(dir, "states");
    if (!append) remove_numbered(*states_, numbered("state_", ".ckpt"));
  }
  if (!append) start_parameters();
  open_rows(append);
}

void Outputs::start_parameters() {
  const std::string parameters = write_parameters(scene_, rs_, *dir_);
  last_.parameters_bytes = static_cast<long>(parameters.size());
  last_.parameters_hash = fnv1a64(parameters);
}

std::vector<std::string> Outputs::earlier_outputs() const {
  namespace fs = std::filesystem;
  const std::string& folder = dir_->path();
  // this run's own video and PNG folder, when they lie directly in the folder
  std::string video, pngs;
  if (sink_ && rs_.frames) {
    if (!rs_.frames->video_path.empty()) video = name_in(folder, path(rs_.frames->video_path.c_str()));
    if (!rs_.frames->png_dir.empty()) pngs = name_in(folder, path(rs_.frames->png_dir.c_str()));
  }
  std::vector<std::string> left;
  for (const std::string& n : {std::string("snapshots.csv"), units_file_name("snapshots.csv")})
    if (!has_snapshots() && dir_->has(n)) left.push_back(n);
  // every video, whatever its name (a script's frames.video, a resumed run's NAME_resumed_T.mp4)
  for (const std::string& n :
       regular_files(folder, [&](const std::string& f) { return f != video && video_name_problem(f).empty(); }))
    left.push_back(n);
  // the pictures sim:show and sim:plot drew into the folder by their default names (show_<t>.png,
  // plot_<t>_2.png; one a script named, file = "a.png", may be any file of the user's): many are
  // named by the first few and their count (a console session draws dozens)
  const std::vector<std::string> pictures = regular_files(folder, is_picture_name);
  constexpr size_t kNamed = 3;
  for (size_t k = 0; k < pictures.size() && (k < kNamed || pictures.size() == kNamed + 1); ++k)
    left.push_back(pictures[k]);
  if (pictures.size() > kNamed + 1) left.push_back(std::to_string(pictures.size() - kNamed) + " more pictures");
  // every PNG folder: frames/ (the default's name) and any other that holds frame_NNNNN.png files
  // (a script's frames.png, whatever its name); and the checkpoints saved into a subfolder
  // (sim:save("ck/mid.ckpt")), named with those in the folder, but in a subfolder that is a run's
  // output folder itself (a console session's replay/, with its own parameters.csv)
  const auto checkpoint = [](const std::string& f) { return f.size() > 5 && f.compare(f.size() - 5, 5, ".ckpt") == 0; };
  std::error_code ec;
  std::vector<std::string> png_dirs, checkpoints;
  for (const auto& e : fs::directory_iterator(folder, ec)) {
    const std::string n = e.path().filename().string();
    if (n == pngs || n == "states" || e.symlink_status(ec).type() != fs::file_type::directory) continue;
    if (n == "frames" || !regular_files(e.path().string(), numbered("frame_", ".png")).empty())
      png_dirs.push_back(n + "/");
    if (fs::symlink_status(e.path() / "parameters.csv", ec).type() == fs::file_type::not_found)
      for (const std::string& c : regular_files(e.path().string(), checkpoint)) checkpoints.push_back(n + "/" + c);
  }
  std::sort(png_dirs.begin(), png_dirs.end());
  left.insert(left.end(), png_dirs.begin(), png_dirs.end());
  if (!rs_.keep_states && dir_->has("states")) left.push_back("states/");
  // checkpoints saved into the folder (sim:save("mid.ckpt")): resumed after this run has written
  // the folder, each is refused (check_state: its outputs are gone), so they are named as it starts
  for (const std::string& n : regular_files(folder, checkpoint)) left.push_back(n);
  std::sort(checkpoints.begin(), checkpoints.end());
  left.insert(left.end(), checkpoints.begin(), checkpoints.end());
  return left;
}

void Outputs::open_rows(bool append) {
  const OutputDir& dir = *dir_;
  const std::vector<std::string> columns = timeseries_columns(scene_, rs_.probes.size());
  // each column's SI unit (io/units.hpp, the table docs/outputs.md lists) in timeseries_units.csv
  // and snapshots_units.csv, written whole, also on resume (the same columns): a folder of an
  // earlier version gets them
  ColumnUnits units;
  for (const std::string& c : columns) units.emplace_back(c, unit_of(c));
  write_units_file(dir, "timeseries.csv", units);
  csv_ = std::make_unique<CsvWriter>(dir, "timeseries.csv", columns, append);
  events_ = std::make_unique<RowFile>(dir, "events.csv", append);
  if (!append) events_->write("t,what,value\n");
  if (has_snapshots()) {
    units.clear();
    std::string header;
    for (const char* c : kSnapshotColumns) {
      if (!header.empty()) header += ',';
      header += c;
      const bool text = std::string_view(c) == "pulley" || std::string_view(c) == "state";
      units.emplace_back(c, text ? std::nullopt : std::optional<std::string>(unit_of(c)));
    }
    write_units_file(dir, "snapshots.csv", units);
    snapshots_ = std::make_unique<RowFile>(dir, "snapshots.csv", append);
    if (!append) snapshots_->write(header + "\n");
  }
  if (append) {  // the files' hashes go on from those of their bytes before (set_state)
    csv_->file().continue_hash(last_.csv_hash);
    events_->continue_hash(last_.events_hash);
    if (snapshots_) snapshots_->continue_hash(last_.snapshots_hash);
  }
}

void Outputs::close(const Warnings& w, const std::string& rows) {
  std::exception_ptr failed;
  try {
    if (sink_) sink_->finish();  // first: a full disk below must not leave the video unfinished
  } catch (...) {
    failed = std::current_exception();
  }
  // a video that got no frame is removed by its writer (media/video_writer.hpp), which is said: a
  // trial's run stopped before its first frame left, unsaid, an MP4 of 808 bytes no player opens
  if (sink_ && rs_.frames && !rs_.frames->video_path.empty() && sink_->frames_written() == 0 && rs_.on_warning)
    rs_.on_warning("no frame was drawn before the run ended (frames from t = " + rounded_text(rs_.frames->t_start) +
                   " s): no video, " + output_path(rs_, rs_.frames->video_path) + " is not written");
  try {
    if (csv_) {  // the fallbacks, beside the parameters they qualify (whole rows, one write)
      std::ostringstream f;
      for (const WarningKindInfo& i : warning_kinds()) {
        const WarningStat& s = w[i.kind];
        f << "warning." << i.name << ".count," << s.count << ",,derived," << csv_text(i.description) << '\n'
          << "warning." << i.name << ".first_t," << (s.count > 0 ? value_text(s.first_t) : std::string())
          << ",s,derived,"
          << "simulated time it first fired (empty: never)\n";
      }
      f << rows;
      RowFile(*dir_, "parameters.csv", true).write(f.str());
    }
  } catch (...) {
    if (!failed) failed = std::current_exception();
  }
  if (dir_) last_ = get_state();
  states_.reset();
  dir_.reset();  // the folder is free for another simulation: this one writes nothing more
  if (failed) std::rethrow_exception(failed);
}

void Outputs::sample(std::vector<double> row) {
  csv_->row(row);
  last_.csv_last_t = row.front();
  rows_++;
  if (rs_.keep_samples) samples_.push_back(std::move(row));
}

void Outputs::event(double t, const std::string& what, const std::string& text) {
  if (!events_) return;
  events_->write(value_text(t) + ',' + csv_text(what) + ',' + csv_text(text) + '\n');
}

// all rows by one write(2) (io/row_file.hpp): the file holds whole snapshots. Columns in SI
// (docs/outputs.md); state as model/observables.hpp names it
void Outputs::snapshot(double t, const Observation& o) {
  std::string rows;
  for (size_t i = 0; i < o.elements.size(); ++i) {
    const ElementObs& e = o.elements[i];
    append_value(rows, t);
    rows += ',' + std::to_string(i) + ',';
    for (double v : {scene_.sites[i].s, e.x, e.y, e.tension, e.normal, e.friction, e.slip, e.mu}) {
      append_value(rows, v);
      rows += ',';
    }
    if (e.pulley >= 0) rows += csv_text(scene_.model.pulleys[e.pulley].name);
    rows += ',';
    rows += contact_state_name(e.state);
    rows += '\n';
  }
  snapshots_->write(rows);
}

void Outputs::frame(double t, const Eigen::VectorXd& y, const Drive& drive, const Observation& obs) {
  sink_->frame(t, y.data(), drive, &obs);
}

void Outputs::keep_state(const std::string& name, const std::string& checkpoint) {
  write_file_whole(*states_, name, checkpoint);
  kept_bytes_ += static_cast<double>(checkpoint.size());
}

bool Outputs::has_snapshots() const {
  return rs_.snapshot_every > 0 || !rs_.snapshot_times.empty();
}

std::string Outputs::path(const char* name) const {
  return output_path(rs_, name);
}

long Outputs::bytes(const char* name) const {
  return std::max(0L, dir_->size(name));
}

double Outputs::written_bytes() const {
  return static_cast<double>(bytes("timeseries.csv") + bytes("snapshots.csv")) + kept_bytes_;
}

double Outputs::free_bytes() const {
  struct statvfs fs {};
  if (::fstatvfs(dir_->fd(), &fs) != 0) return -1;
  return static_cast<double>(fs.f_bavail) * static_cast<double>(fs.f_frsize);
}

long Outputs::frames_written() const {
  return frames_before_ + (sink_ ? sink_->frames_written() : 0);
}

}  // namespace beltsim
