#include "app/render_cmd.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "app/options.hpp"
#include "io/checkpoint_text.hpp"
#include "io/output_dir.hpp"
#include "io/suggest.hpp"
#include "media/video_writer.hpp"
#include "render/draw_list.hpp"
#include "render/recorder.hpp"
#include "scene/scene_io.hpp"
#include "script/script_args.hpp"
#include "script/signals.hpp"
#include "sim/simulation.hpp"

namespace beltsim::app {

namespace {

// n numbers separated by `sep`, each a finite decimal
std::vector<double> numbers(const std::string& option, const std::string& text, char sep, size_t n,
                            const std::string& form) {
  std::vector<double> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, sep)) {
    const auto x = script::decimal(item);
    if (!x) throw UsageError(option + " needs " + form + ", got '" + text + "'");
    out.push_back(*x);
  }
  if (out.size() != n || text.back() == sep) throw UsageError(option + " needs " + form + ", got '" + text + "'");
  return out;
}

// the options' values, read and checked before any state is read, each error naming the option
// as typed
struct Chosen {
  std::optional<FrameQuantity> quantity;
  std::optional<std::pair<int, int>> size;
  std::optional<Vec2> view_centre;
  std::optional<double> view_width, magnify;
  std::optional<std::pair<double, double>> range;
};

Chosen chosen(const RenderOptions& o) {
  Chosen c;
  if (o.quantity) {
    std::vector<std::string> names;
    for (const auto& i : frame_quantities()) {
      names.push_back(i.key);
      if (*o.quantity == i.key) c.quantity = i.q;
    }
    if (!c.quantity)
      throw UsageError("--quantity: unknown quantity '" + *o.quantity + "'" + did_you_mean(*o.quantity, names) +
                       "; one of: " + join(names));
  }
  if (o.size) {
    const auto s = numbers("--size", *o.size, 'x', 2, "WxH in pixels, e.g. 640x360");
    if (s[0] != std::floor(s[0]) || s[1] != std::floor(s[1]) || !(s[0] >= 16 && s[0] <= 8192) ||
        !(s[1] >= 16 && s[1] <= 8192))
      throw UsageError("--size needs whole numbers of pixels in 16..8192, got " + *o.size);
    c.size = {static_cast<int>(s[0]), static_cast<int>(s[1])};
  }
  if (o.view) {
    const auto v = numbers("--view", *o.view, ',', 3, "X,Y,WIDTH in metres (the centre and the visible width)");
    if (const std::string why = view_width_problem(v[2]); !why.empty())
      throw UsageError("--view: the width " + why + ", got '" + *o.view + "'");
    c.view_centre = Vec2(v[0], v[1]), c.view_width = v[2];
  }
  if (o.magnify) {
    c.magnify = numbers("--magnify", *o.magnify, ',', 1, "a number > 0")[0];
    if (const std::string why = magnify_problem(*c.magnify); !why.empty())
      throw UsageError("--magnify " + why + ", got '" + *o.magnify + "'");
  }
  if (o.range) {
    const auto r = numbers("--range", *o.range, ',', 2, "LO,HI in the quantity's unit");
    if (const std::string why = range_problem(r[0], r[1]); !why.empty())
      throw UsageError("--range " + why + ", got '" + *o.range + "'");
    c.range = {r[0], r[1]};
  }
  return c;
}

// the run's frame settings (or the defaults) with the options applied
FrameSettings settings(const Chosen& c, const RunSettings& rs) {
  FrameSettings f = rs.frames ? *rs.frames : FrameSettings{};
  if (c.quantity) {
    // a range belongs to its quantity: another quantity gets its own default
    if (f.quantity != *c.quantity) f.range_lo.reset(), f.range_hi.reset();
    f.quantity = *c.quantity;
  }
  if (c.size) f.width = c.size->first, f.height = c.size->second;
  if (c.view_centre) f.view_centre = c.view_centre, f.view_width = c.view_width;
  if (c.magnify) f.magnify = *c.magnify;
  if (c.range) f.range_lo = c.range->first, f.range_hi = c.range->second;
  f.png_dir.assign(1, '.');  // one picture, written by render_snapshot
  f.video_path.clear();
  try {
    validate(f);  // the options are checked already: the run's settings, as the checkpoint holds them
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  return f;
}

// the checkpoint files named: a file as given, a folder's *.ckpt files in the order of their
// numbers (state_99999.ckpt before state_100000.ckpt: shorter names first, then by name)
std::vector<std::string> state_files(const std::vector<std::string>& given) {
  namespace fs = std::filesystem;
  std::vector<std::string> files;
  for (const std::string& g : given) {
    std::error_code ec;
    if (!fs::is_directory(g, ec)) {
      files.push_back(g);
      continue;
    }
    std::vector<std::string> in;
    for (const fs::directory_entry& e : fs::directory_iterator(g, ec))
      if (e.path().extension() == ".ckpt" && e.is_regular_file(ec)) in.push_back(e.path().filename().string());
    if (ec) throw std::runtime_error(g + ": cannot read the folder: " + ec.message());
    if (in.empty()) throw std::runtime_error(g + ": no states in it (no *.ckpt files)");
    std::sort(in.begin(), in.end(), [](const std::string& a, const std::string& b) {
      return a.size() != b.size() ? a.size() < b.size() : a < b;
    });
    for (const std::string& name : in) files.push_back((fs::path(g) / name).string());
  }
  return files;
}

// what a state's picture is drawn from (render::render_snapshot, FrameSink::frame), taken from its
// checkpoint, which is read once; the scene is the first state's, every other one's checked to be
// the same
struct StateToDraw {
  double t = 0;
  Eigen::VectorXd y;
  Drive drive;
  Observation obs;
};
StateToDraw to_draw(const Simulation& s) {
  return {s.now(), s.state(), s.drive(), s.observation()};
}

// the PNG of the state `file` among several: DIR/<state name>.png
std::string png_path(const std::string& dir, const std::string& file) {
  return (std::filesystem::path(dir) / std::filesystem::path(file).stem()).string() + ".png";
}

// A video that did not get a frame of every state (a stop signal, an error): finished with the
// frames drawn, under the partial name (VideoWriter: written whole, so `path` itself, an earlier
// render's finished video perhaps, is left as it was), and said on stderr; the partial video's
// path on stdout, as a finished one's is
void finish_partial(std::unique_ptr<FrameSink> video, const std::string& path, size_t states) {
  const long drawn = video->frames_written();
  std::error_code ec;
  const bool earlier = std::filesystem::exists(std::filesystem::symlink_status(path, ec));
  const std::string left = earlier ? path + " is left as it was" : "no " + path + " is written";
  if (drawn == 0) {
    video.reset();  // never named: nothing is left
    std::fprintf(stderr, "beltsim render: no state was drawn: no video (%s)\n", left.c_str());
    return;
  }
  video->finish();
  const std::string partial = partial_video_path(path);
  if (!std::filesystem::exists(std::filesystem::symlink_status(partial, ec))) {  // the video's own write failed
    std::fprintf(stderr, "beltsim render: no video is left (%s)\n", left.c_str());
    return;
  }
  std::printf("%s\n", partial.c_str());
  std::fprintf(stderr,
               "beltsim render: the video of the %ld of %zu states drawn is %s (it plays to its last frame; %s)\n",
               drawn, states, partial.c_str(), left.c_str());
}

}  // namespace

int cmd_render(const RenderOptions& o) {
  std::unique_ptr<FrameSink> video;
  size_t total = 0;  // the states to draw
  try {
    if (!o.out && !o.video)
      throw UsageError("--out is required (the PNG, or a folder for several states), or --video MP4");
    if (o.video) {
      if (const std::string bad = video_name_problem(*o.video); !bad.empty())
        throw UsageError("--video " + *o.video + ": " + bad);
    }
    const Chosen c = chosen(o);
    const std::vector<std::string> files = state_files(o.states);
    total = files.size();
    std::error_code ec;
    // --out names a folder for several states (a folder of them too), or when it ends in / (a
    // name ending in / is a folder: it was written as a PNG file of that name, the / dropped)
    const bool several = files.size() > 1 || std::filesystem::is_directory(o.states.front(), ec) ||
                         (o.out && !o.out->empty() && o.out->back() == '/');
    if (o.out && !several) require_png("--out", *o.out);
    // a picture's name for the folder of several states' PNGs: it made a folder named x.png
    if (o.out && several && o.out->back() != '/' && png_name_problem(*o.out).empty())
      throw UsageError("--out " + *o.out + ": " +
                       (files.size() > 1 ? std::to_string(files.size()) + " states"
                                         : "the states of the folder " + o.states.front()) +
                       " need a folder for their PNGs (DIR/<state name>.png each), and a name ending in .png is "
                       "a picture's: give --out a folder, or one state file");
    // the first state gives the scene and the frame settings of every picture
    const std::unique_ptr<Simulation> first = Simulation::open_checkpoint(files.front());
    const FrameSettings f = settings(c, first->settings());
    FrameSettings v = f;
    if (o.video) {
      v.png_dir.clear(), v.video_path = *o.video;
      v.video_whole_frames = static_cast<long>(files.size());
      // a video's size is even (H.264 in yuv420p); PNGs take any
      if (v.width % 2 || v.height % 2) {
        const std::string size = std::to_string(v.width) + "x" + std::to_string(v.height);
        throw UsageError((o.size ? "--size " + size : "the run's frames.size " + size + " (--size sets it)") +
                         ": width and height must be even for --video (H.264 in yuv420p)");
      }
    }
    // every state read (once) and checked before anything is written: a state of another scene
    // among them left the PNGs before it, or a video of one frame, behind a failed render
    std::vector<StateToDraw> states{to_draw(*first)};
    for (size_t k = 1; k < files.size(); ++k) {
      const std::unique_ptr<Simulation> s = Simulation::open_checkpoint(files[k]);
      if (const std::string d = scene_difference(s->scene(), first->scene()); !d.empty())
        throw std::runtime_error(files[k] + ": a state of another scene than " + files.front() + "'s (its " + d +
                                 " differs; one render draws the states of one scene)");
      states.push_back(to_draw(*s));
    }
    // (states of one scene:) two of the same name, the same state of two runs, would give one PNG,
    // the second drawn over the first
    if (o.out && several) {
      std::map<std::string, std::string> drawn;  // a PNG's path: the state drawn to it
      for (const std::string& file : files) {
        const std::string png = png_path(*o.out, file);
        if (const auto [i, added] = drawn.emplace(png, file); !added)
          throw UsageError("--out " + *o.out + ": " + i->second + " and " + file + " would both be drawn to " + png +
                           " (DIR/<state name>.png each, the second over the first): render them into separate "
                           "--out folders");
      }
    }
    if (const std::string small = render::frame_size_problem(first->scene(), f, states[0].t, states[0].y.data());
        !small.empty())
      std::fprintf(stderr, "beltsim render: warning: %s %s\n",
                   o.size ? "--size" : "the run's frames.size (--size sets it)", small.c_str());
    if (o.video) video = render::make_frame_recorder(first->scene(), v);
    for (size_t k = 0; k < files.size(); ++k) {
      // Ctrl-C, SIGTERM, SIGHUP (script/signals.hpp): stopped between two states, the pictures
      // drawn so far kept (each PNG written whole, the video under its partial name)
      if (script::stop_signal() != 0) {
        if (video) finish_partial(std::move(video), *o.video, files.size());
        return script::stopped_status();
      }
      const StateToDraw& s = states[k];
      if (o.out) {
        const std::string png = several ? png_path(*o.out, files[k]) : *o.out;
        render::render_snapshot(first->scene(), f, s.t, s.y.data(), s.drive, png, &s.obs);
        std::printf("%s\n", png.c_str());
      }
      if (video) video->frame(s.t, s.y.data(), s.drive, &s.obs);
    }
    if (video) {
      std::unique_ptr<FrameSink> done = std::move(video);
      done->finish();
      std::printf("%s\n", o.video->c_str());
    }
    return 0;
  } catch (const UsageError& e) {
    std::fprintf(stderr, "beltsim: %s\nRun 'beltsim render --help' for the usage.\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "beltsim render: %s\n", e.what());
    mark_output_failure_shown(e.what());
    // the frames drawn so far make a video that plays, under its partial name
    try {
      if (video) finish_partial(std::move(video), *o.video, total);
    } catch (const std::exception& f) {
      std::fprintf(stderr, "beltsim render: %s\n", f.what());
      mark_output_failure_shown(f.what());
    }
    return script::stop_signal() != 0 ? script::stopped_status() : 1;
  }
}

}  // namespace beltsim::app
