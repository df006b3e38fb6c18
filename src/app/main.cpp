// beltsim command line.
//   beltsim run SCRIPT [--out DIR] [--t-end T] [--integrator NAME] [--rtol R] [--no-frames]
//   beltsim wp  SCRIPT [--out DIR] [--t-end T] [--integrators A,B] [--rtols R1,R2] [--ref-rtol R]
//                      [--wall-limit S]
// The flags override what the script passes to scene:run{}. Exit status: 0 on success, 1 on a
// script, parameter or run error (message on stderr, outputs written so far kept), 2 on bad
// usage, 130 when stopped by Ctrl-C (outputs flushed).
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include <filesystem>
#include <sstream>
#include <vector>

#include "integrate/stepper.hpp"
#include "plot/wp_plot.hpp"
#include "script/interpreter.hpp"
#include "sim/work_precision.hpp"

namespace {

std::atomic<bool> g_stop{false};

void on_sigint(int) { g_stop.store(true); }

const char* kUsage =
    "usage: beltsim run SCRIPT [--out DIR] [--t-end T] [--integrator NAME] [--rtol R] [--no-frames]\n"
    "       beltsim wp  SCRIPT [--out DIR] [--t-end T] [--integrators A,B,..] [--rtols R1,R2,..]\n"
    "                          [--ref-rtol R] [--wall-limit S]\n"
    "\n"
    "run: runs a Lua scenario script. The options override the script's run settings:\n"
    "  --out DIR          output folder (default: out/<script name>)\n"
    "  --t-end T          end time [s]\n"
    "  --integrator NAME  one of: %s\n"
    "  --rtol R           relative tolerance of the step-size control\n"
    "  --no-frames        render no frames and no video, whatever the script asks\n"
    "Writes DIR/timeseries.csv (samples at fixed times) and DIR/parameters.csv, and the\n"
    "frames (PNG) and video (MP4) a script asks for with scene:run{ frames = {...} }.\n"
    "\n"
    "wp: error against run time. Runs the script's scene with every integrator (or those of\n"
    "--integrators) at every tolerance of --rtols (default 1e-2,1e-3,1e-4,1e-5,1e-6), each\n"
    "against a reference run of esdirk32 at --ref-rtol (default 1e-7); a run taking longer\n"
    "than --wall-limit seconds (default 120) is stopped and recorded as unfinished.\n"
    "Writes DIR/wp.csv and DIR/wp.png (default DIR: out/<script name>/wp).\n";

int usage(const char* error) {
  std::string names;
  for (const auto& n : beltsim::integrator_names()) names += (names.empty() ? "" : ", ") + n;
  if (error) std::fprintf(stderr, "beltsim: %s\n", error);
  std::fprintf(error ? stderr : stdout, kUsage, names.c_str());
  return error ? 2 : 0;
}

bool parse_number(const char* s, double& out) {
  char* end = nullptr;
  out = std::strtod(s, &end);
  return end != s && *end == '\0';
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) return usage("no command given");
  const std::string cmd = argv[1];
  if (cmd == "--help" || cmd == "-h" || cmd == "help") return usage(nullptr);
  if (cmd == "--version") {
    std::printf("beltsim 0.1.0\n");
    return 0;
  }
  if (cmd != "run" && cmd != "wp") return usage(("unknown command '" + cmd + "'").c_str());
  std::string script;
  beltsim::script::Overrides o;
  beltsim::WpSettings wps;
  auto number_list = [](const char* v, std::vector<double>& out) {
    out.clear();
    std::stringstream ss(v);
    std::string item;
    while (std::getline(ss, item, ',')) {
      double x = 0;
      if (!parse_number(item.c_str(), x) || !(x > 0 && x < 1)) return false;
      out.push_back(x);
    }
    return !out.empty();
  };
  for (int k = 2; k < argc; ++k) {
    const std::string a = argv[k];
    auto value = [&]() -> const char* { return k + 1 < argc ? argv[++k] : nullptr; };
    if (a == "--out" || a == "--t-end" || a == "--integrator" || a == "--rtol") {
      const char* v = value();
      if (!v) return usage((a + " needs a value").c_str());
      double x = 0;
      if (a == "--out") {
        o.out = v;
      } else if (a == "--integrator") {
        o.integrator = v;
      } else if (!parse_number(v, x)) {
        return usage((a + " needs a number, got '" + v + "'").c_str());
      } else if (a == "--t-end") {
        if (!(x > 0)) return usage(("--t-end must be > 0 s, got " + std::string(v)).c_str());
        o.t_end = x;
      } else {
        if (!(x > 0 && x < 1)) return usage(("--rtol must be in (0, 1), got " + std::string(v)).c_str());
        o.rtol = x;
      }
    } else if (cmd == "wp" && (a == "--integrators" || a == "--rtols" || a == "--ref-rtol" || a == "--wall-limit")) {
      const char* v = value();
      if (!v) return usage((a + " needs a value").c_str());
      double x = 0;
      if (a == "--integrators") {
        std::stringstream ss(v);
        std::string item;
        wps.integrators.clear();
        while (std::getline(ss, item, ',')) wps.integrators.push_back(item);
        for (const auto& n : wps.integrators) {
          try {
            beltsim::check_integrator(n);
          } catch (const std::invalid_argument& e) {
            return usage(e.what());
          }
        }
      } else if (a == "--rtols") {
        if (!number_list(v, wps.rtols)) return usage(("--rtols needs numbers in (0, 1) separated by commas, got '" + std::string(v) + "'").c_str());
      } else if (!parse_number(v, x) || !(x > 0)) {
        return usage((a + " needs a positive number, got '" + v + "'").c_str());
      } else if (a == "--ref-rtol") {
        if (!(x < 1)) return usage(("--ref-rtol must be in (0, 1), got " + std::string(v)).c_str());
        wps.ref_rtol = x;
      } else {
        wps.wall_limit = x;
      }
    } else if (a == "--no-frames") {
      o.no_frames = true;
    } else if (a == "--help" || a == "-h") {
      return usage(nullptr);
    } else if (!a.empty() && a[0] == '-') {
      return usage(("unknown option '" + a + "'").c_str());
    } else if (script.empty()) {
      script = a;
    } else {
      return usage(("unexpected argument '" + a + "'").c_str());
    }
  }
  if (script.empty()) return usage("no script given");
  if (o.integrator) {
    try {
      beltsim::check_integrator(*o.integrator);
    } catch (const std::invalid_argument& e) {
      return usage(e.what());
    }
  }

  std::signal(SIGINT, on_sigint);
  if (cmd == "wp") {
    try {
      beltsim::script::Captured cap;
      beltsim::script::Interpreter lua;
      if (o.t_end) lua.set_overrides({.out = {}, .t_end = o.t_end, .integrator = {}, .rtol = {}});
      lua.set_capture(&cap);
      lua.run_file(script);
      if (!cap.scene) throw std::runtime_error(script + ": the script never calls scene:run{}");
      wps.base = cap.settings;
      wps.base.out_dir = o.out ? *o.out : (std::filesystem::path("out") / std::filesystem::path(script).stem() / "wp").string();
      const beltsim::WpResult r = beltsim::work_precision(*cap.scene, wps, &g_stop);
      const std::string png = (std::filesystem::path(wps.base.out_dir) / "wp.png").string();
      std::string drawn;
      try {
        beltsim::plot::plot_wp_png(r, png);
        drawn = png;
      } catch (const std::exception& e) {  // the CSV is the result; the picture is a convenience
        std::fprintf(stderr, "beltsim wp: no plot: %s\n", e.what());
      }
      std::fprintf(stderr, "beltsim wp: wrote %s%s%s\n", r.csv_path.c_str(), drawn.empty() ? "" : " and ",
                   drawn.c_str());
      return g_stop.load() ? 130 : 0;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "beltsim: %s\n", e.what());
      return 1;
    }
  }
  try {
    beltsim::script::Interpreter lua;
    lua.set_overrides(o);
    lua.set_stop_flag(&g_stop);
    lua.run_file(script);
    if (lua.interrupted()) {
      std::fprintf(stderr, "beltsim: interrupted; the outputs written so far are kept\n");
      return 130;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "beltsim: %s\n", e.what());
    return 1;
  }
  return 0;
}
