// Checkpoints of a live simulation: everything a continuation needs, in a line-oriented text with
// doubles as hex floats (exact): the run settings, the scene, the model as it is now (laws and μ
// changed since the start), the schedule's positions, the timed changes still ahead, the output
// positions (rows and bytes of the CSV files, frames written) and the integrator's own state.
// Continuing from it gives the uninterrupted run's outputs and state bit for bit. Callbacks
// (Lua functions) are not saved: a checkpoint counts them and the script registers them again.
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "integrate/belt_system.hpp"
#include "integrate/timeline.hpp"
#include "io/csv_writer.hpp"
#include "io/output_dir.hpp"
#include "scene/scene_io.hpp"
#include "sim/simulation.hpp"

namespace beltsim {

namespace {

constexpr const char* kMagic = "beltsim-checkpoint";
// 2: failed-step counts in the integrator state; 3: several probes, snapshots, interval means
constexpr int kVersion = 3;

void put(std::ostream& o, const char* key, double v) { o << key << ' ' << std::hexfloat << v << std::defaultfloat << '\n'; }
void put(std::ostream& o, const char* key, long v) { o << key << ' ' << v << '\n'; }
void put(std::ostream& o, const char* key, const std::string& v) { o << key << ' ' << v.size() << ' ' << v << '\n'; }

void expect(std::istream& in, const char* key) {
  std::string k;
  in >> k;
  if (!in || k != key) throw std::runtime_error(std::string("checkpoint: expected '") + key + "', found '" + k + "'");
}
double get_double(std::istream& in, const char* key) {
  expect(in, key);
  std::string s;
  in >> s;
  return std::strtod(s.c_str(), nullptr);
}
long get_long(std::istream& in, const char* key) {
  expect(in, key);
  long v = 0;
  in >> v;
  if (!in) throw std::runtime_error(std::string("checkpoint: a whole number expected after '") + key + "'");
  return v;
}
std::string get_string(std::istream& in, const char* key) {
  expect(in, key);
  size_t n = 0;
  in >> n;
  in.get();  // the space
  std::string s(n, '\0');
  in.read(s.data(), static_cast<std::streamsize>(n));
  if (!in) throw std::runtime_error(std::string("checkpoint: text after '") + key + "' is cut short");
  return s;
}

void put_frames(std::ostream& o, const FrameSettings& f) {
  for (const auto& [k, v] : {std::pair{"fps", f.fps}, std::pair{"slowdown", f.slowdown}, std::pair{"magnify", f.magnify},
                             std::pair{"t_start", f.t_start}, std::pair{"range_lo", f.range_lo.value_or(NAN)},
                             std::pair{"range_hi", f.range_hi.value_or(NAN)},
                             std::pair{"view_x", f.view_centre ? f.view_centre->x() : NAN},
                             std::pair{"view_y", f.view_centre ? f.view_centre->y() : NAN},
                             std::pair{"view_width", f.view_width.value_or(NAN)}})
    put(o, k, v);
  for (const auto& [k, v] : {std::pair{"width", long(f.width)}, std::pair{"height", long(f.height)},
                             std::pair{"quantity", long(f.quantity)}, std::pair{"levels", long(f.levels)},
                             std::pair{"png_every", long(f.png_every)}})
    put(o, k, v);
  put(o, "png_dir", f.png_dir);
  put(o, "video", f.video_path);
}

FrameSettings get_frames(std::istream& in) {
  FrameSettings f;
  f.fps = get_double(in, "fps"), f.slowdown = get_double(in, "slowdown"), f.magnify = get_double(in, "magnify");
  f.t_start = get_double(in, "t_start");
  auto opt = [](double v) { return std::isnan(v) ? std::optional<double>() : std::optional<double>(v); };
  f.range_lo = opt(get_double(in, "range_lo")), f.range_hi = opt(get_double(in, "range_hi"));
  const double vx = get_double(in, "view_x"), vy = get_double(in, "view_y");
  if (!std::isnan(vx)) f.view_centre = Vec2(vx, vy);
  f.view_width = opt(get_double(in, "view_width"));
  f.width = static_cast<int>(get_long(in, "width")), f.height = static_cast<int>(get_long(in, "height"));
  f.quantity = static_cast<FrameQuantity>(get_long(in, "quantity"));
  f.levels = static_cast<int>(get_long(in, "levels")), f.png_every = static_cast<int>(get_long(in, "png_every"));
  f.png_dir = get_string(in, "png_dir");
  f.video_path = get_string(in, "video");
  return f;
}


}  // namespace

void Simulation::save(const std::string& path) const {
  require_open("save");
  if (running_ || view_y_) throw std::logic_error("save: not inside a callback (save between run_to calls)");
  if (!integ_->can_save())
    throw std::invalid_argument("save: " + rs_.integrator +
                                " keeps a multistep history that SUNDIALS cannot export; checkpoints need a one-step "
                                "integrator (esdirk32, trbdf2, ros34pw2, rkf45)");
  // (the CSV files need no flush: each row is in the file when written)
  std::ostringstream o;
  o << kMagic << ' ' << kVersion << '\n';
  put(o, "integrator", rs_.integrator);
  put(o, "rtol", rs_.rtol);
  put(o, "atol", rs_.atol);
  put(o, "sample_dt", rs_.sample_dt);
  put(o, "out_dir", std::filesystem::absolute(rs_.out_dir).string());
  put(o, "probes", long(rs_.probes.size()));
  for (int i : rs_.probes) o << i << '\n';
  put(o, "snapshot_every", rs_.snapshot_every);
  put(o, "snapshot_times", long(rs_.snapshot_times.size()));
  for (double t : rs_.snapshot_times) put(o, "t", t);
  put(o, "keep_samples", long(rs_.keep_samples));
  put(o, "allow_large", long(rs_.allow_large));
  put(o, "frames", long(rs_.frames.has_value()));
  if (rs_.frames) put_frames(o, *rs_.frames);
  o << "scene\n";
  write_scene(o, scene_);
  o << "drive\n";
  write_drive(o, drive_);
  put(o, "now", tl_->now());
  const std::vector<long> k = tl_->positions();
  put(o, "streams", long(k.size()));
  for (long v : k) o << v << '\n';
  put(o, "pending", long(pending_.size()));
  for (const MuEvent& ev : pending_) {
    put(o, "t", ev.t);
    put(o, "what", ev.what);
    put(o, "text", ev.text);
    write_vector(o, ev.mu);
  }
  put(o, "rows", rows_);
  // the outputs' sizes (0 for one that is not there; never through a link)
  auto bytes = [this](const char* name) { return std::max(0L, out_->size(name)); };
  put(o, "csv_bytes", bytes("timeseries.csv"));
  put(o, "events_bytes", bytes("events.csv"));
  put(o, "snapshots_bytes", has_snapshots() ? bytes("snapshots.csv") : 0L);
  put(o, "mean_from", mean_from_);
  put(o, "mean_covered", mean_covered_);
  put(o, "mean_acc", long(mean_acc_.size()));
  for (double v : mean_acc_) put(o, "v", v);
  put(o, "frames_written", frames_written());
  put(o, "callbacks", long(callbacks_));
  put(o, "wall", wall_);
  o << "integrator_state\n";
  integ_->save(o);
  o << "end\n";
  // written whole (io/output_dir.hpp): a checkpoint is never half a file, and no part of one is
  // left behind when it cannot be written
  write_file_whole(path, o.str());
}

std::unique_ptr<Simulation> Simulation::resume(const std::string& path, const FrameSinkFactory& factory, int* callbacks,
                                               const std::function<void(const RunSettings&)>& vet) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("resume: cannot read " + path + ": " + std::strerror(errno));
  std::string magic;
  int version = 0;
  in >> magic >> version;
  if (magic != kMagic) throw std::runtime_error("resume: " + path + " is not a beltsim checkpoint");
  if (version != kVersion)
    throw std::runtime_error("resume: " + path + " is a version " + std::to_string(version) +
                             " checkpoint; this beltsim reads version " + std::to_string(kVersion));
  RunSettings rs;
  rs.integrator = get_string(in, "integrator");
  rs.rtol = get_double(in, "rtol");
  rs.atol = get_double(in, "atol");
  rs.sample_dt = get_double(in, "sample_dt");
  rs.out_dir = get_string(in, "out_dir");
  rs.probes.assign(static_cast<size_t>(get_long(in, "probes")), 0);
  for (int& i : rs.probes) in >> i;
  rs.snapshot_every = get_double(in, "snapshot_every");
  rs.snapshot_times.resize(static_cast<size_t>(get_long(in, "snapshot_times")));
  for (double& t : rs.snapshot_times) t = get_double(in, "t");
  rs.keep_samples = get_long(in, "keep_samples") != 0;
  rs.allow_large = get_long(in, "allow_large") != 0;
  if (get_long(in, "frames")) {
    rs.frames = get_frames(in);
    rs.frame_factory = factory;
  }
  expect(in, "scene");
  const Scene sc = read_scene(in);
  expect(in, "drive");
  Drive drive = read_drive(in);
  const double now = get_double(in, "now");
  std::vector<long> k(static_cast<size_t>(get_long(in, "streams")));
  for (long& v : k) in >> v;
  std::vector<MuEvent> pending(static_cast<size_t>(get_long(in, "pending")));
  for (MuEvent& ev : pending) {
    ev.t = get_double(in, "t");
    ev.what = get_string(in, "what");
    ev.text = get_string(in, "text");
    ev.mu = read_std_vector(in);
  }
  const long rows = get_long(in, "rows"), csv_bytes = get_long(in, "csv_bytes");
  const long events_bytes = get_long(in, "events_bytes");
  const long snapshots_bytes = get_long(in, "snapshots_bytes");
  const double mean_from = get_double(in, "mean_from"), mean_covered = get_double(in, "mean_covered");
  std::vector<double> mean_acc(static_cast<size_t>(get_long(in, "mean_acc")));
  for (double& v : mean_acc) v = get_double(in, "v");
  const long frames = get_long(in, "frames_written");
  const long n_callbacks = get_long(in, "callbacks");
  const double wall = get_double(in, "wall");
  expect(in, "integrator_state");

  std::unique_ptr<Simulation> s(new Simulation(sc, rs, false));
  if (vet) vet(s->rs_);
  if (drive.pulleys.size() != s->drive_.pulleys.size() || drive.mu.size() != s->drive_.mu.size())
    throw std::runtime_error("resume: " + path + ": the drive does not fit the scene");
  s->drive_ = std::move(drive);
  s->pending_ = std::move(pending);
  s->rows_ = rows;
  s->wall_ = wall;
  s->frames_before_ = frames;
  if (mean_acc.size() != s->mean_acc_.size()) throw std::runtime_error("resume: " + path + ": interval means do not fit the scene");
  s->mean_acc_ = std::move(mean_acc);
  s->mean_from_ = mean_from, s->mean_covered_ = mean_covered;
  s->integ_->load(in);
  expect(in, "end");
  // the outputs continue where the checkpoint left them, once the folder is this simulation's alone
  // (a checkpoint resumed twice: the second is refused before it cuts the first one's files)
  s->claim_out_dir();
  s->out_->truncate("timeseries.csv", csv_bytes);
  s->out_->truncate("events.csv", events_bytes);
  if (s->has_snapshots()) s->out_->truncate("snapshots.csv", snapshots_bytes);
  if (s->rs_.frames) {
    FrameSettings& f = *s->rs_.frames;
    f.first_number = frames;
    if (!f.video_path.empty()) {
      // an MP4 cannot be appended to: the continuation's frames go to a file of their own
      std::filesystem::path v(f.video_path);
      char tag[32];
      std::snprintf(tag, sizeof tag, "_resumed_%.6f", now);
      f.video_path = (v.parent_path() / (v.stem().string() + tag + v.extension().string())).string();
    }
  }
  s->open_outputs(true);
  s->add_streams();
  s->tl_->set_positions(k);
  s->tl_->resume_at(now);
  s->set_landings();
  s->write_event(now, "resume", path);
  if (callbacks) *callbacks = static_cast<int>(n_callbacks);
  return s;
}

}  // namespace beltsim
