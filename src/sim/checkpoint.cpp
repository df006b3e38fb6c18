// Checkpoints of a live simulation: everything a continuation needs, in the one checkpoint text
// (io/checkpoint_text.hpp): the run settings, the scene, the drive as it is now (laws and μ
// changed since the start), the schedule's positions, the timed changes still ahead, the output
// positions (bytes of the CSV files, frames written) and the integrator's own state. Continuing
// from it gives the uninterrupted run's outputs and state bit for bit. Callbacks (Lua functions)
// are not saved: a checkpoint counts them and the script registers them again.
//
// Reading trusts nothing in the file: it reads only a regular file of bounded size, every count
// is bounded by the text that holds its values and by the scene, the scene and the settings are
// validated as a script's are, the output positions must fall on row ends past the headers, and
// a checksum catches what is otherwise well-formed. No output is touched before all of it passed.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <new>

#include "integrate/belt_system.hpp"
#include "integrate/timeline.hpp"
#include "io/checkpoint_text.hpp"
#include "io/input_file.hpp"
#include "io/number_text.hpp"
#include "io/output_dir.hpp"
#include "scene/scene_io.hpp"
#include "scene/validate.hpp"
#include "sim/interval_means.hpp"
#include "sim/simulation.hpp"

namespace beltsim {

namespace {

// The largest checkpoint read: a checkpoint takes about 710 bytes per element on two pulleys
// (measured at 100 and 1000 elements), 15 MB at the 20 000 elements a scene may have without
// allow_large; past this a file is surely not a checkpoint.
constexpr long kMaxCheckpointBytes = 1L << 30;

void write_settings(CheckpointWriter& w, const RunSettings& rs) {
  w.line("integrator", rs.integrator);
  w.line("rtol", rs.rtol);
  w.line("atol", rs.atol);
  w.line("sample", rs.sample_dt);
  w.line("out", std::filesystem::absolute(rs.out_dir).string());
  w.line("probe", rs.probes);
  w.line("snapshots.every", rs.snapshot_every);
  w.line("snapshots.times", rs.snapshot_times);
  w.line("keep_samples", rs.keep_samples);
  w.line("allow_large", rs.allow_large);
  w.line("keep_states", rs.keep_states);
  w.line("frames", rs.frames.has_value());
  if (!rs.frames) return;
  const FrameSettings& f = *rs.frames;
  w.line("frames.fps", f.fps);
  w.line("frames.slowdown", f.slowdown);
  w.fixed("frames.size", {static_cast<double>(f.width), static_cast<double>(f.height)});
  w.word("frames.quantity", frame_quantity_info(f.quantity).key);
  w.optional("frames.range.lo", f.range_lo);
  w.optional("frames.range.hi", f.range_hi);
  w.line("frames.levels", f.levels);
  w.line("frames.magnify", f.magnify);
  if (f.view_centre) w.fixed("frames.view.centre", {f.view_centre->x(), f.view_centre->y()});
  else w.word("frames.view.centre", "none");
  w.optional("frames.view.width", f.view_width);
  // the paths as the script gave them: relative ones lie inside the output folder (sim/outputs.cpp)
  w.line("frames.png", f.png_dir);
  w.line("frames.png_every", f.png_every);
  w.line("frames.video", f.video_path);
  w.line("frames.t_start", f.t_start);
}

// (checked by the Simulation's constructor as a script's settings are)
RunSettings read_settings(CheckpointReader& r) {
  RunSettings rs;
  rs.integrator = r.line_str("integrator");
  rs.rtol = r.line_num("rtol");
  rs.atol = r.line_num("atol");
  rs.sample_dt = r.line_num("sample");
  rs.out_dir = r.line_str("out");
  rs.probes = r.line_ints("probe", INT_MIN, INT_MAX);
  rs.snapshot_every = r.line_num("snapshots.every");
  rs.snapshot_times = r.line_doubles("snapshots.times");
  rs.keep_samples = r.line_bool("keep_samples");
  rs.allow_large = r.line_bool("allow_large");
  rs.keep_states = r.line_bool("keep_states");
  if (!r.line_bool("frames")) return rs;
  FrameSettings& f = rs.frames.emplace();
  f.fps = r.line_num("frames.fps");
  f.slowdown = r.line_num("frames.slowdown");
  r.open("frames.size");
  f.width = static_cast<int>(r.integer(0, INT_MAX)), f.height = static_cast<int>(r.integer(0, INT_MAX));
  r.close();
  std::vector<std::string> names;
  for (const FrameQuantityInfo& q : frame_quantities()) names.push_back(q.key);
  f.quantity = frame_quantities()[static_cast<size_t>(r.line_choice("frames.quantity", names))].q;
  f.range_lo = r.line_optional("frames.range.lo");
  f.range_hi = r.line_optional("frames.range.hi");
  f.levels = static_cast<int>(r.line_int("frames.levels", INT_MIN, INT_MAX));
  f.magnify = r.line_num("frames.magnify");
  r.open("frames.view.centre");
  if (const std::optional<double> x = r.optional_num()) f.view_centre = Vec2(*x, r.num());
  r.close();
  f.view_width = r.line_optional("frames.view.width");
  f.png_dir = r.line_str("frames.png");
  f.png_every = static_cast<int>(r.line_int("frames.png_every", INT_MIN, INT_MAX));
  f.video_path = r.line_str("frames.video");
  f.t_start = r.line_num("frames.t_start");
  return rs;
}

// the whole of a regular file of at most kMaxCheckpointBytes: a FIFO, a device (/dev/zero) or a
// folder is refused at once, without blocking on it or reading from it (io/input_file.hpp)
std::string read_checkpoint_file(const std::string& path) {
  std::string text;
  try {
    InputFile file(path);
    if (file.size() > kMaxCheckpointBytes)
      throw CheckpointError(std::to_string(file.size()) + " bytes, more than any checkpoint (at most " +
                            std::to_string(kMaxCheckpointBytes) + ")");
    text = file.read_rest();
  } catch (const InputFileError& e) {
    throw CheckpointError(e.not_regular ? "not a regular file, so not a checkpoint" : "cannot read it: " + e.reason);
  }
  if (text.empty()) throw CheckpointError("an empty file, not a checkpoint");
  return text;
}

// An output the checkpoint continues: the position it was at when saved must lie past its header
// line, on the end of a row, within the file as it is now.
struct OutputCut {
  std::string name;  // in the output folder
  std::string path;
  long bytes;
};

void check_cut(const OutputCut& c) {
  const int fd = ::open(c.path.c_str(), O_RDONLY | O_NONBLOCK | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) throw std::runtime_error("the run's output " + c.path + " cannot be read: " + std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode))
    throw std::runtime_error("the run's output " + c.path + " is not a regular file");
  if (st.st_size < c.bytes)
    throw std::runtime_error("the run's output " + c.path + " (" + std::to_string(st.st_size) +
                             " bytes) is shorter than when the checkpoint was taken (" + std::to_string(c.bytes) + ")");
  // the header: the first line, read in pieces up to the saved position
  long header = -1;
  char buf[4096];
  for (long at = 0; at < c.bytes && header < 0;) {
    const ssize_t n = ::pread(fd, buf, sizeof buf, at);
    if (n <= 0) break;
    if (const void* nl = std::memchr(buf, '\n', static_cast<size_t>(n)))
      header = at + (static_cast<const char*>(nl) - buf) + 1;
    at += n;
  }
  if (header < 0 || c.bytes < header)
    throw std::runtime_error("the checkpoint continues " + c.path + " from byte " + std::to_string(c.bytes) +
                             ", inside its header line: cutting it there would lose the header");
  char last = 0;
  if (::pread(fd, &last, 1, c.bytes - 1) != 1 || last != '\n')
    throw std::runtime_error("the checkpoint continues " + c.path + " from byte " + std::to_string(c.bytes) +
                             ", which is not the end of a row");
}

// the next index of each output stream at `now`, in Simulation::add_streams' order (samples,
// frames, snapshots every dt, snapshots at listed times): the first whose time lies after now
std::vector<long> next_outputs(const RunSettings& rs, double now) {
  auto next = [&](double t0, double dt) {
    if (now < t0) return 0L;
    const double k = std::floor((now - t0) / dt);
    if (!(k < 1e15)) throw CheckpointError("its time " + number_text(now) + " s is beyond its outputs' reach");
    long i = static_cast<long>(k);
    while (i > 0 && stream_time(t0, dt, i - 1) > now) --i;
    while (stream_time(t0, dt, i) <= now) ++i;
    return i;
  };
  std::vector<long> k{next(0.0, rs.sample_dt)};
  if (const std::optional<FrameSettings> f = frame_times(rs)) k.push_back(next(f->t_start, f->frame_dt()));
  if (rs.snapshot_every > 0) k.push_back(next(0.0, rs.snapshot_every));
  if (!rs.snapshot_times.empty())
    k.push_back(std::upper_bound(rs.snapshot_times.begin(), rs.snapshot_times.end(), now) - rs.snapshot_times.begin());
  return k;
}

// the settings by the one check of a script's (run_settings.hpp), once the scene they name is read;
// a refusal names the settings' lines, from to to
void check_read_settings(const CheckpointReader& r, const Scene& sc, const RunSettings& rs, int from, int to) {
  std::string refused;
  try {
    check(sc, rs, false);
  } catch (const std::invalid_argument& e) {
    refused = e.what();
  }
  if (!refused.empty()) r.fail_lines(from, to, "the run settings: " + refused);
}

// a count read from the checkpoint, and its line
struct Count {
  long n;
  int line;
};

// the counts of what was written by `now`: at most the samples and frame times up to then
// (expected: next_outputs at now)
void check_counts(const CheckpointReader& r, const RunSettings& rs, double now, const std::vector<long>& expected,
                  Count rows, Count frames) {
  if (rows.n > expected[0])
    r.fail_at(rows.line, "rows",
              std::to_string(rows.n) + " samples written by t = " + number_text(now) + " s, at most " +
                  std::to_string(expected[0]) + " at a sample every " + number_text(rs.sample_dt) + " s");
  const long frame_times_passed = frame_times(rs) ? expected[1] : 0;
  if (frames.n > frame_times_passed)
    r.fail_at(frames.line, "frames_written",
              std::to_string(frames.n) + " frames written by t = " + number_text(now) + " s, at most the " +
                  std::to_string(frame_times_passed) + " frame times by then");
}

}  // namespace

std::string cannot_save(const std::string& integrator) {
  return integrator +
         " keeps a multistep history that SUNDIALS cannot export; checkpoints need a one-step integrator (esdirk32, "
         "trbdf2, ros34pw2, rkf45)";
}

void Simulation::save(const std::string& path) const {
  require_open("save");
  if (running_ || view_.y) throw std::logic_error("save: not inside a callback (save between run_to calls)");
  if (!integ_->can_save()) throw std::invalid_argument("save: " + cannot_save(rs_.integrator));
  // written whole (io/output_dir.hpp): a checkpoint is never half a file, and no part of one is
  // left behind when it cannot be written
  write_file_whole(path, checkpoint_text());
}

std::string Simulation::checkpoint_text() const {
  // (the CSV files need no flush: each row is in the file when written)
  CheckpointWriter w;
  w.word("part", "settings");
  write_settings(w, rs_);
  w.word("part", "scene");
  write_scene(w, scene_);
  w.word("part", "drive");
  write_drive(w, model_, drive_);
  w.word("part", "outputs");
  w.line("now", tl_->now());
  w.line("streams", tl_->positions());
  w.line("pending", static_cast<long>(pending_.size()));
  for (const MuEvent& ev : pending_) {
    w.line("event.t", ev.t);
    w.line("event.what", ev.what);
    w.line("event.text", ev.text);
    w.line("event.mu", ev.mu);
    w.line("event.share", ev.share);
  }
  w.line("rows", out_->rows());
  // the outputs' sizes (0 for one that is not there; never through a link)
  w.line("csv_bytes", out_->bytes("timeseries.csv"));
  w.line("events_bytes", out_->bytes("events.csv"));
  w.line("snapshots_bytes", has_snapshots() ? out_->bytes("snapshots.csv") : 0L);
  w.line("mean_from", means_->from());
  w.line("mean_covered", means_->covered());
  w.line("mean_acc", means_->integral());
  w.line("frames_written", frames_written());
  w.line("callbacks", callbacks_);
  w.line("wall", wall_);
  w.word("part", "integrator");
  integ_->save(w);
  return w.finish();
}

std::unique_ptr<Simulation> Simulation::resume(const std::string& path, const FrameSinkFactory& factory, int* callbacks,
                                               const std::function<void(const RunSettings&)>& vet) {
  return load(path, factory, callbacks, vet, true);
}

std::unique_ptr<Simulation> Simulation::open_checkpoint(const std::string& path) {
  // a run that drew frames keeps its frame settings (what a reader draws by default); the factory
  // is never called, as no output is opened
  const FrameSinkFactory none = [](const Scene&, const FrameSettings&) { return std::unique_ptr<FrameSink>(); };
  return load(path, none, nullptr, {}, false);
}

std::unique_ptr<Simulation> Simulation::load(const std::string& path, const FrameSinkFactory& factory, int* callbacks,
                                             const std::function<void(const RunSettings&)>& vet, bool outputs) {
  const std::string where = path + ": ";  // the caller says what it was doing (beltsim.resume, render)
  std::unique_ptr<Simulation> s;
  std::vector<OutputCut> cuts;
  double now = 0;
  std::vector<long> positions;
  long n_callbacks = 0;
  try {
    CheckpointReader r(read_checkpoint_file(path));
    r.line_choice("part", {"settings"});
    const int settings_from = r.line_number() + 1;
    RunSettings rs = read_settings(r);
    const int settings_to = r.line_number();
    if (rs.frames) rs.frame_factory = factory;
    r.line_choice("part", {"scene"});
    const Scene sc = read_scene(r);
    check_read_settings(r, sc, rs, settings_from, settings_to);
    r.line_choice("part", {"drive"});
    Drive drive = read_drive(r, sc.model);
    r.line_choice("part", {"outputs"});
    now = r.line_num("now");
    if (!(now >= 0)) r.fail("a time >= 0 s expected");
    positions = r.line_longs("streams", 0, LONG_MAX);
    const int streams_line = r.line_number();
    r.open("pending");
    const size_t n_pending = r.group_count(5);
    r.close();
    std::vector<MuEvent> pending(n_pending);
    const size_t n = static_cast<size_t>(sc.model.n_el());
    for (MuEvent& ev : pending) {
      ev.t = r.line_num("event.t");
      if (const std::string bad = event_time_problem(ev.t); !bad.empty()) r.fail("an event's time " + bad);
      if (!(ev.t >= now)) r.fail("an event still ahead must come at or after the checkpoint's time");
      ev.what = r.line_str("event.what");
      ev.text = r.line_str("event.text");
      ev.mu = r.line_doubles_or_nan("event.mu", n);
      if (ev.mu.size() != n) r.fail(std::to_string(ev.mu.size()) + " values for " + std::to_string(n) + " elements");
      for (double mu : ev.mu)
        if (!std::isnan(mu) && !(mu >= 0)) r.fail("μ must be >= 0 (got " + number_text(mu) + ")");
      ev.share = r.line_doubles("event.share", n);
      if (!ev.share.empty() && ev.share.size() != n)
        r.fail(std::to_string(ev.share.size()) + " shares for " + std::to_string(n) + " elements");
      for (double w : ev.share)
        if (!(w >= 0 && w <= 1)) r.fail("a share of the new μ must be in [0, 1] (got " + number_text(w) + ")");
    }
    const long rows = r.line_int("rows", 0, LONG_MAX);
    const int rows_line = r.line_number();
    const long csv_bytes = r.line_int("csv_bytes", 0, LONG_MAX);
    const long events_bytes = r.line_int("events_bytes", 0, LONG_MAX);
    const long snapshots_bytes = r.line_int("snapshots_bytes", 0, LONG_MAX);
    const double mean_from = r.line_num("mean_from"), mean_covered = r.line_num("mean_covered");
    if (!(0 <= mean_from && mean_from <= mean_covered && mean_covered <= now))
      r.fail("the interval means must cover a time in [0 s, now]");
    std::vector<double> mean_acc = r.line_doubles("mean_acc", 2 * sc.model.pulleys.size() + sc.route.spans.size());
    const long frames = r.line_int("frames_written", 0, LONG_MAX);
    const int frames_line = r.line_number();
    n_callbacks = r.line_int("callbacks", 0, INT_MAX);
    const double wall = r.line_num("wall");
    if (!(wall >= 0)) r.fail("a wall time >= 0 s expected");
    r.line_choice("part", {"integrator"});

    try {
      s.reset(new Simulation(sc, rs, false));
    } catch (const std::invalid_argument& e) {
      throw CheckpointError(std::string("the run settings: ") + e.what());
    }
    if (rs.frames) s->rs_.frames->first_number = frames;
    // the outputs' streams, as Simulation::add_streams adds them, at `now`
    const std::vector<long> expected = next_outputs(s->rs_, now);
    if (positions.size() < expected.size() || positions.size() > expected.size() + static_cast<size_t>(n_callbacks))
      r.fail_at(streams_line, "streams", std::to_string(positions.size()) + " positions for the " + std::to_string(expected.size()) +
                            " output streams of its settings and " + std::to_string(n_callbacks) + " callbacks");
    for (size_t i = 0; i < expected.size(); ++i)
      if (positions[i] != expected[i] && positions[i] + 1 != expected[i])
        r.fail_at(streams_line, "streams", "position " + std::to_string(positions[i]) + " of output stream " + std::to_string(i + 1) +
                              " does not fit the time " + number_text(now) + " s");
    positions.resize(expected.size());
    check_counts(r, rs, now, expected, {rows, rows_line}, {frames, frames_line});

    if (mean_acc.size() != s->means_->size()) r.fail("interval means do not fit the scene");
    if (drive.spray.zones.size() != sc.drive.spray.zones.size())
      r.fail("the drive's " + std::to_string(drive.spray.zones.size()) + " spray zones do not fit the scene's " +
             std::to_string(sc.drive.spray.zones.size()));
    s->drive_ = std::move(drive);
    s->pending_ = std::move(pending);
    s->wall_ = wall;
    s->out_->continue_from(rows, frames);
    s->means_->restore(std::move(mean_acc), mean_from, mean_covered);
    s->integ_->load(r);
    if (!(s->integ_->t_prev() <= now && now <= s->integ_->t()))
      r.fail("the checkpoint's time " + number_text(now) + " s lies outside the integrator's last step");
    r.finish();
    cuts.push_back({"timeseries.csv", s->csv_path(), csv_bytes});
    cuts.push_back({"events.csv", s->events_path(), events_bytes});
    if (s->has_snapshots()) cuts.push_back({"snapshots.csv", s->snapshots_path(), snapshots_bytes});
  } catch (const CheckpointError& e) {
    throw std::runtime_error(where + e.what());
  } catch (const std::bad_alloc&) {
    throw std::runtime_error(where + "there is not enough memory to read it");
  } catch (const std::length_error&) {
    throw std::runtime_error(where + "a size in it is beyond what this machine can hold");
  }
  if (!outputs) {
    s->tl_->resume_at(now);
    s->closed_ = true;  // nothing to close, and run_to refuses it
    return s;
  }
  if (vet) vet(s->rs_);
  // the outputs continue where the checkpoint left them, once the folder is this simulation's alone
  // (a checkpoint resumed twice: the second is refused before it cuts the first one's files);
  // every one checked before any is cut
  const OutputDir& dir = s->out_->claim();
  try {
    for (const OutputCut& c : cuts) check_cut(c);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(where + e.what());
  }
  for (const OutputCut& c : cuts) dir.truncate(c.name, c.bytes);
  if (s->rs_.frames) {
    FrameSettings& f = *s->rs_.frames;
    if (!f.video_path.empty()) {
      // an MP4 cannot be appended to: the continuation's frames go to a file of their own
      std::filesystem::path v(f.video_path);
      char tag[32];
      std::snprintf(tag, sizeof tag, "_resumed_%.6f", now);
      f.video_path = (v.parent_path() / (v.stem().string() + tag + v.extension().string())).string();
    }
  }
  s->out_->open(true);
  s->add_streams();
  if (s->tl_->positions().size() != positions.size())
    throw std::logic_error("resume: the streams differ from those checkpoint.cpp expects (next_outputs)");
  s->tl_->set_positions(positions);
  s->tl_->resume_at(now);
  s->set_landings();
  s->write_event(now, "resume", path);
  if (callbacks) *callbacks = static_cast<int>(n_callbacks);
  return s;
}

}  // namespace beltsim
