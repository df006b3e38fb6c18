// beltsim command line.
//   beltsim run SCRIPT [--out DIR] [--t-end T] [--integrator NAME] [--rtol R] [--no-frames]
// The flags override what the script passes to scene:run{}. Exit status: 0 on success, 1 on a
// script, parameter or run error (message on stderr, outputs written so far kept), 2 on bad
// usage, 130 when stopped by Ctrl-C (outputs flushed).
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "integrate/stepper.hpp"
#include "script/interpreter.hpp"

namespace {

std::atomic<bool> g_stop{false};

void on_sigint(int) { g_stop.store(true); }

const char* kUsage =
    "usage: beltsim run SCRIPT [--out DIR] [--t-end T] [--integrator NAME] [--rtol R] [--no-frames]\n"
    "\n"
    "Runs a Lua scenario script. The options override the script's run settings:\n"
    "  --out DIR          output folder (default: out/<script name>)\n"
    "  --t-end T          end time [s]\n"
    "  --integrator NAME  one of: %s\n"
    "  --rtol R           relative tolerance of the step-size control\n"
    "  --no-frames        render no frames and no video, whatever the script asks\n"
    "Writes DIR/timeseries.csv (samples at fixed times) and DIR/parameters.csv, and the\n"
    "frames (PNG) and video (MP4) a script asks for with scene:run{ frames = {...} }.\n";

int usage(const char* error) {
  std::string names;
  for (const auto& n : beltsim::stepper_names()) names += (names.empty() ? "" : ", ") + n;
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
  if (cmd != "run") return usage(("unknown command '" + cmd + "'").c_str());

  std::string script;
  beltsim::script::Overrides o;
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
      beltsim::make_stepper(*o.integrator);
    } catch (const std::invalid_argument& e) {
      return usage(e.what());
    }
  }

  std::signal(SIGINT, on_sigint);
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
