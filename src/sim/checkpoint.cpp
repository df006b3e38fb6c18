// Checkpoints of a live simulation: everything a continuation needs, in the one checkpoint text
// (io/checkpoint_text.hpp): the run settings, the scene (scene/scene_io.hpp) and the run's state
// (sim/sim_state.hpp, in text by sim/state_io.hpp: the drive as it is now, the schedule's
// positions, the timed changes still ahead, the outputs' positions, the integrator's held step).
// Continuing from it gives the uninterrupted run's outputs and state bit for bit. Callbacks (Lua
// functions) are not saved: a checkpoint counts them and the script registers them again.
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
#include "sim/run_table.hpp"
#include "sim/settings_check.hpp"
#include "sim/simulation.hpp"
#include "sim/state_io.hpp"

namespace beltsim {

namespace {
// the output folder a checkpoint names (absolute) as the run that wrote it names it when it lies
// in the folder beltsim runs in (out/x, not /home/u/out/x); absolute elsewhere
std::string shown_folder(const std::string& out) {
  std::error_code ec;
  const std::filesystem::path cwd = std::filesystem::current_path(ec);
  if (ec || out.empty()) return out;
  const std::filesystem::path rel = std::filesystem::path(out).lexically_normal().lexically_relative(cwd);
  if (rel.empty() || *rel.begin() == "..") return out;
  return rel.string();
}
}  // namespace

namespace {

// The largest checkpoint read: a checkpoint takes about 710 bytes per element on two pulleys
// (measured at 100 and 1000 elements), 15 MB at the 20 000 elements a scene may have without
// allow_large; past this a file is surely not a checkpoint.
constexpr long kMaxCheckpointBytes = 1L << 30;

void write_frames(CheckpointWriter& w, const RunSettings& rs) {
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

void read_frames(CheckpointReader& r, RunSettings& rs) {
  if (!r.line_bool("frames")) return;
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
}

// The settings a checkpoint keeps (kSaved in sim/run_table.hpp), in the table's order: a number,
// flag or text by its slot, a list or table by its own lines.
void write_settings(CheckpointWriter& w, const RunSettings& rs) {
  for (const RunSetting& s : run_settings()) {
    if (!(s.where & kSaved)) continue;
    const RunSlot v = run_slot(s, rs);
    if (auto* x = std::get_if<double*>(&v))
      w.line(s.key, **x);
    else if (auto* b = std::get_if<bool*>(&v))
      w.line(s.key, **b);
    // the output folder absolute: a run resumed from another folder writes where this one did
    else if (auto* t = std::get_if<std::string*>(&v))
      w.line(s.key, s.key == "out" ? std::filesystem::absolute(**t).string() : **t);
    else if (s.key == "probe")
      w.line("probe", rs.probes);
    else if (s.key == "snapshots")
      w.line("snapshots.every", rs.snapshot_every), w.line("snapshots.times", rs.snapshot_times);
    else if (s.key == "frames")
      write_frames(w, rs);
    else
      throw std::logic_error("checkpoint: no writer for the run setting '" + std::string(s.key) + "'");
  }
}

// (checked by the Simulation's constructor as a script's settings are)
RunSettings read_settings(CheckpointReader& r) {
  RunSettings rs;
  for (const RunSetting& s : run_settings()) {
    if (!(s.where & kSaved)) continue;
    const RunSlot v = run_slot(s, rs);
    if (auto* x = std::get_if<double*>(&v))
      **x = r.line_num(s.key);
    else if (auto* b = std::get_if<bool*>(&v))
      **b = r.line_bool(s.key);
    else if (auto* t = std::get_if<std::string*>(&v))
      **t = r.line_str(s.key);
    else if (s.key == "probe")
      rs.probes = r.line_ints("probe", INT_MIN, INT_MAX);
    else if (s.key == "snapshots")
      rs.snapshot_every = r.line_num("snapshots.every"), rs.snapshot_times = r.line_doubles("snapshots.times");
    else if (s.key == "frames")
      read_frames(r, rs);
    else
      throw std::logic_error("checkpoint: no reader for the run setting '" + std::string(s.key) + "'");
  }
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

// the settings by the one check of a script's (settings_check.hpp), once the scene they name is read;
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

}  // namespace

std::string cannot_save(const std::string& integrator) {
  return integrator +
         " keeps a multistep history that SUNDIALS cannot export; checkpoints need a one-step integrator (esdirk32, "
         "trbdf2, ros34pw2, rkf45)";
}

std::string Simulation::lua_law() const {
  for (const auto& [drive, whose] : {std::pair{&drive_, ""}, std::pair{&scene_.drive, "the scene's "}})
    for (size_t j = 0; j < drive->pulleys.size(); ++j)
      for (const auto& [law, what] :
           {std::pair{&drive->pulleys[j].torque, "torque"}, std::pair{&drive->pulleys[j].speed, "speed"}})
        if (law->fn)
          return std::string(whose) + "pulley '" + model_.pulleys[j].name + "'." + what + " (" + law->fn->describe() +
                 ")";
  return "";
}

void Simulation::save(const std::string& path) const {
  require_open("save");
  // a law or a when-condition runs inside a step, at a state the run does not stand at
  if (view_.y || (running_ && !in_action_))
    throw std::logic_error(
        "save: not inside a law or a when-condition (save in a callback's function, or between "
        "run_to calls)");
  if (!integ_->can_save()) throw std::invalid_argument("save: " + cannot_save(rs_.integrator));
  if (const std::string law = lua_law(); !law.empty())
    throw std::invalid_argument("save: " + law +
                                " is Lua code, which a checkpoint cannot hold: give the law as a table "
                                "(constant, per_speed, ramps, sines, ...) to save this simulation");
  // inside a callback's function the run stands inside its time's processing (the callbacks at
  // that time run before its landings, its other callbacks, the restart a change asks for and its
  // samples and frames, integrate/timeline.hpp), a state no run_to stops at, which a resumed run
  // would not continue bit for bit: the checkpoint is written once that time is done, the state
  // run_to(t) stops at (and the live view's pause saves), so that it holds the outputs at t
  if (running_) {
    saves_due_.push_back(path);
    return;
  }
  // written whole (io/output_dir.hpp): a checkpoint is never half a file, and no part of one is
  // left behind when it cannot be written; its missing folders made, as for every output
  write_file_whole(path, checkpoint_text());
}

void Simulation::write_saves_due() {
  if (saves_due_.empty()) return;
  std::vector<std::string> due;
  due.swap(saves_due_);
  // (a change later at that time may have given a law as Lua code)
  if (const std::string law = lua_law(); !law.empty())
    throw std::invalid_argument("save: " + law +
                                " is Lua code, which a checkpoint cannot hold (it was given after "
                                "the callback asked for the checkpoint)");
  // with the wall time of the run so far, this call's included (between calls it is in wall_)
  const double before = wall_;
  wall_ += call_wall_ ? call_wall_() : 0.0;
  std::string text;
  try {
    text = checkpoint_text();
  } catch (...) {
    wall_ = before;
    throw;
  }
  wall_ = before;
  for (const std::string& path : due) write_file_whole(path, text);
}

std::string Simulation::checkpoint_text() const {
  // (the CSV files need no flush: each row is in the file when written)
  CheckpointWriter w;
  w.word("part", "settings");
  write_settings(w, rs_);
  w.word("part", "scene");
  write_scene(w, scene_);
  write_state(w, model_, get_state());
  return w.finish();
}

double Simulation::kept_state_bytes() const {
  // the checkpoint of now, with each value of the held step (the state and its derivative at the
  // step's two ends) that is 0 now counted at the mean width of its values that are not: at the
  // start the speeds are 0 (written "0"), where a state in motion has about 20 bytes for each.
  // Measured at 600 elements (trbdf2): 368 kB at t = 0, 550 to 570 kB in motion, this 508 kB; the rest
  // is the state inside the step that trbdf2 keeps once it has taken one (another 75 kB)
  const IntegratorState s = integ_->get_state();
  double zeros = 0, others = 0, width = 0;
  for (const Eigen::VectorXd* v : {&s.y, &s.f, &s.y_prev, &s.f_prev})
    for (double x : *v) {
      if (x == 0) {
        zeros++;
      } else {
        others++, width += static_cast<double>(number_text(x).size());
      }
    }
  const double in_motion = others > 0 ? width / others : 17;
  return static_cast<double>(checkpoint_text().size()) + zeros * (in_motion - 1);
}

std::unique_ptr<Simulation> Simulation::resume(const std::string& path, const FrameSinkFactory& factory, int* callbacks,
                                               const std::function<void(const RunSettings&)>& vet, bool rewind,
                                               const std::function<void(const std::string&)>& warn,
                                               const std::string& out) {
  return load(path, factory, callbacks, vet, true, rewind, warn, out);
}

std::unique_ptr<Simulation> Simulation::open_checkpoint(const std::string& path) {
  // a run that drew frames keeps its frame settings (what a reader draws by default); the factory
  // is never called, as no output is opened
  const FrameSinkFactory none = [](const Scene&, const FrameSettings&) { return std::unique_ptr<FrameSink>(); };
  return load(path, none, nullptr, {}, false);
}

std::unique_ptr<Simulation> Simulation::load(const std::string& path, const FrameSinkFactory& factory, int* callbacks,
                                             const std::function<void(const RunSettings&)>& vet, bool outputs,
                                             bool rewind, const std::function<void(const std::string&)>& warn,
                                             const std::string& out) {
  const std::string where = path + ": ";  // the caller says what it was doing (beltsim.resume, render)
  std::unique_ptr<Simulation> s;
  SimState st;
  std::string from;  // a branch's source: the checkpoint's folder, read only (out)
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
    st = read_state(r, sc);
    r.finish();
    if (rs.frames) rs.frame_factory = factory, rs.frames->first_number = st.outputs.frames;
    rs.out_dir = shown_folder(rs.out_dir);
    std::error_code ec;
    // a branch's folder is its own, not the checkpoint's (a user's trial got the plain resume's
    // refusal there, whose rewind = true cut the first run)
    const std::filesystem::path branch = std::filesystem::absolute(out, ec).lexically_normal() / "",
                                source = std::filesystem::absolute(rs.out_dir, ec).lexically_normal() / "";
    if (outputs && !out.empty() && branch == source)
      throw std::runtime_error(where + "out = " + out + " is the checkpoint's own output folder, " + rs.out_dir +
                               ": a branch goes into a folder of its own (resume without out to go on in that "
                               "folder)");
    if (outputs && !out.empty() && branch != source) {
      // the frames' paths relative ones lie in out; an absolute one the branch would draw over the run's own
      if (rs.frames)
        for (const std::string* p : {&rs.frames->png_dir, &rs.frames->video_path})
          if (std::filesystem::path(*p).is_absolute())
            throw std::runtime_error(where + "its frames go to " + *p +
                                     ", outside its output folder, where a branch into " + out +
                                     " would draw over the run's own frames; resume it without out (in its "
                                     "own folder), or run the scene again with frames inside its folder");
      from = rs.out_dir, rs.out_dir = out;
    }
    try {
      s.reset(new Simulation(sc, rs, false));
    } catch (const std::invalid_argument& e) {
      throw CheckpointError(std::string("the run settings: ") + e.what());
    }
    // whether the state fits the run its settings and scene make, named by its line
    try {
      s->check_state(st);
      s->integ_->set_state(st.integrator);
    } catch (const StateError& e) {
      r.fail_at(r.line_of(e.key), e.key, e.what());
    }
  } catch (const CheckpointError& e) {
    throw std::runtime_error(where + e.what());
  } catch (const std::bad_alloc&) {
    throw std::runtime_error(where + "there is not enough memory to read it");
  } catch (const std::length_error&) {
    throw std::runtime_error(where + "a size in it is beyond what this machine can hold");
  }
  if (!outputs) {
    s->apply_state(st);
    s->closed_ = true;  // nothing to close, and run_to refuses it
    return s;
  }
  if (vet) {
    vet(s->rs_);
    if (!from.empty()) {  // the source too: it is read
      RunSettings source = s->rs_;
      source.out_dir = from, source.frames.reset();
      vet(source);
    }
  }
  const std::string& folder = from.empty() ? s->rs_.out_dir : from;
  // the folder the checkpoint continues must be there: made anew, it would be left behind empty
  // by the refusal that follows (its files are missing)
  if (std::error_code ec; !std::filesystem::is_directory(folder, ec)) {
    std::string hint;
    const std::filesystem::path beside = std::filesystem::absolute(path).lexically_normal().parent_path();
    if (beside != std::filesystem::absolute(folder, ec).lexically_normal() &&
        std::filesystem::exists(beside / "timeseries.csv", ec))
      hint = " (" + shown_folder(beside.string()) +
             ", where the checkpoint lies, holds a timeseries.csv: if it is that folder " + "moved, move it back to " +
             folder + ")";
    throw std::runtime_error(where + "the run's output folder " + folder +
                             ", whose files this checkpoint continues, is not there" + hint +
                             ": put the run's folder back where it was to resume it, or run the scene again; "
                             "nothing was written");
  }
  // the outputs continue where the checkpoint left them, once the folder is this simulation's alone
  // (a checkpoint resumed twice: the second is refused before it cuts the first one's files);
  // every one checked before any is cut. A branch's go on from a copy of them in its own folder
  // (made when missing), the source only read: nothing of it is cut, so no rewind is asked for
  if (from.empty()) s->out_->claim(false);
  try {
    if (from.empty())
      s->out_->check_state(st.outputs);
    else
      s->out_->check_files(st.outputs, from);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(where + e.what());
  }
  if (!from.empty()) {
    st.outputs = s->out_->branch(st.outputs, from);
    s->branched_from_ = from;
    s->warn_earlier_outputs();
  }
  if (!st.outputs.fingerprinted && warn)
    warn(path + ": a version " + std::to_string(kCheckpointOldest) +
         " checkpoint holds no fingerprint of its outputs, so whether the files in " + s->rs_.out_dir +
         " up to it are its own run's (not a later run's into the folder) could not be checked; a checkpoint "
         "saved by this beltsim is checked");
  // a run's results after the checkpoint are not dropped unasked (a kept state of a finished run,
  // or a copy of its folder, whose checkpoints name the run's own folder)
  if (const std::string later = from.empty() ? s->out_->later_results(st.outputs) : ""; !later.empty() && !rewind)
    throw std::runtime_error(where + "resuming at t = " + rounded_text(st.now()) +
                             " s would cut the run's results after it (" + later +
                             (s->rs_.frames ? "; its frames after it would be drawn again" : "") +
                             "); resume with rewind = true to drop them and continue from the checkpoint, or run "
                             "the scene again to keep them");
  s->apply_state(st);
  if (s->rs_.frames) {
    FrameSettings& f = *s->rs_.frames;
    if (!f.video_path.empty()) {
      // an MP4 cannot be appended to: the continuation's frames go to a file of their own
      std::filesystem::path v(f.video_path);
      char tag[32];
      std::snprintf(tag, sizeof tag, "_resumed_%.6f", st.now());
      f.video_path = (v.parent_path() / (v.stem().string() + tag + v.extension().string())).string();
    }
  }
  s->out_->open(true);
  s->write_event(st.now(), "resume", path);
  if (callbacks) *callbacks = st.callbacks;
  return s;
}

}  // namespace beltsim
