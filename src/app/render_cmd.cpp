#include "app/render_cmd.hpp"

#include <cmath>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "app/options.hpp"
#include "io/output_dir.hpp"
#include "io/suggest.hpp"
#include "render/recorder.hpp"
#include "script/script_args.hpp"
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

// the run's frame settings (or the defaults) with the options applied
FrameSettings settings(const RenderOptions& o, const RunSettings& rs) {
  FrameSettings f = rs.frames ? *rs.frames : FrameSettings{};
  if (o.quantity) {
    std::vector<std::string> names;
    bool found = false;
    for (const auto& i : frame_quantities()) {
      names.push_back(i.key);
      if (*o.quantity == i.key) {
        // a range belongs to its quantity: another quantity gets its own default
        if (f.quantity != i.q) f.range_lo.reset(), f.range_hi.reset();
        f.quantity = i.q, found = true;
      }
    }
    if (!found)
      throw UsageError("--quantity: unknown quantity '" + *o.quantity + "'" + did_you_mean(*o.quantity, names) +
                  "; one of: " + join(names));
  }
  if (o.size) {
    const auto s = numbers("--size", *o.size, 'x', 2, "WxH in pixels, e.g. 640x360");
    if (s[0] != std::floor(s[0]) || s[1] != std::floor(s[1]) || !(s[0] >= 16 && s[0] <= 8192) ||
        !(s[1] >= 16 && s[1] <= 8192))
      throw UsageError("--size needs whole numbers of pixels in 16..8192, got " + *o.size);
    f.width = static_cast<int>(s[0]), f.height = static_cast<int>(s[1]);
  }
  if (o.view) {
    const auto v = numbers("--view", *o.view, ',', 3, "X,Y,WIDTH in metres (the centre and the visible width)");
    f.view_centre = Vec2(v[0], v[1]);
    f.view_width = v[2];
  }
  if (o.magnify) f.magnify = numbers("--magnify", *o.magnify, ',', 1, "a number > 0")[0];
  if (o.range) {
    const auto r = numbers("--range", *o.range, ',', 2, "LO,HI in the quantity's unit");
    f.range_lo = r[0], f.range_hi = r[1];
  }
  f.png_dir.assign(1, '.');  // one picture, written by render_snapshot
  f.video_path.clear();
  try {
    validate(f);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  return f;
}

}  // namespace

int cmd_render(const RenderOptions& o) {
  try {
    const std::unique_ptr<Simulation> s = Simulation::open_checkpoint(o.checkpoint);
    const FrameSettings f = settings(o, s->settings());
    render::render_snapshot(s->scene(), f, s->now(), s->state().data(), s->drive(), o.out, &s->observation());
    std::printf("%s\n", o.out.c_str());
    return 0;
  } catch (const UsageError& e) {
    std::fprintf(stderr, "beltsim: %s\nRun 'beltsim render --help' for the usage.\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "beltsim render: %s\n", e.what());
    mark_output_failure_shown(e.what());
    return 1;
  }
}

}  // namespace beltsim::app
