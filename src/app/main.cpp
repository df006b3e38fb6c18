// beltsim command line (CLI11).
//   beltsim run     SCRIPT [--out DIR] [--t-end T] [--integrator NAME] [--rtol R] [--max-wall S]
//                          [--no-frames] [--set KEY=VALUE]... [SAFETY]
//   beltsim wp      SCRIPT [--out DIR] [--t-end T] [--integrators A,B] [--rtols R1,R2] [--ref-rtol R]
//                          [--wall-limit S] [--set KEY=VALUE]... [SAFETY]
//   beltsim plot    CSV [COLUMNS...] [--out PNG] [--from T]
//   beltsim sweep   FILE [--out DIR] [--jobs N] [--point K] [--list] [--collect] [--set KEY=V1,V2,..]...
//                        [--slurm [--submit] [--partition P] [--time T] [--max-parallel M]] [SAFETY]
//   beltsim render  CHECKPOINT --out PNG [--quantity Q] [--size WxH] [--view X,Y,W] [--magnify M] [--range LO,HI]
//   beltsim compare A B [--tol L] [--max-bad N] [--diff PNG] [--rtol R] [--atol A] [--col-tol NAME=R[,A]]...
//   beltsim console [SCRIPT] [--out DIR] [--t-end T] [--integrator NAME] [--rtol R] [--max-wall S]
//                            [--no-frames] [--set KEY=VALUE]... [SAFETY] [-- ARGS...]
//   SAFETY: [--trusted] [--max-instructions N] [--max-lua-memory MiB] (docs/limits-and-safety.md)
// The flags override what the script passes to scene:run{}. Every number is a finite decimal
// (no hex, inf or nan); an option a command does not take is an error. Exit status: 0 on
// success, 1 on a script, parameter, run or plot error or an output that could not be written
// (message on stderr, outputs written so far kept; compare: 0 when the files match, 1 when they
// differ), 2 on bad usage (or an environment variable it
// cannot read, app/environment.hpp), 130 when stopped by Ctrl-C (SIGINT), 143 by SIGTERM and 129
// by SIGHUP (outputs closed; script/signals.hpp).
#include <CLI/CLI.hpp>
#include <sched.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "integrate/integrator.hpp"
#include "integrate/stepper.hpp"
#include "io/csv_writer.hpp"
#include "io/output_dir.hpp"
#include "plot/plot.hpp"
#include "plot/wp_plot.hpp"
#include "scene/parameters.hpp"
#include "script/interpreter.hpp"
#include "script/script_args.hpp"
#include "sim/work_precision.hpp"
#include "term/term_image.hpp"

#include "app/compare.hpp"
#include "app/environment.hpp"
#include "app/render_cmd.hpp"
#include "script/console.hpp"
#include "script/docall.hpp"
#include "script/signals.hpp"
#include "script/lua_sweep.hpp"
#include "sweep/driver.hpp"
#include "sweep/results.hpp"
#include "sweep/slurm.hpp"

namespace {

namespace fs = std::filesystem;

using beltsim::script::stop_flag;
using beltsim::script::stop_signal;
using beltsim::script::stopped_status;

// An output that could not be written (io/output_dir.hpp records each) fails the command, also
// when no message of its own said so (a simulation closed at the interpreter's end, a script that
// caught the error): each not shown yet is named, and a status of 0 becomes 1.
int with_outputs(int status) {
  for (const std::string& m : beltsim::unshown_output_failures()) std::fprintf(stderr, "beltsim: %s\n", m.c_str());
  return status == 0 && !beltsim::output_failures().empty() ? 1 : status;
}

// bad usage: the message goes to stderr and the exit status is 2
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

using beltsim::script::decimal;

double number(const std::string& option, const std::string& text) {
  const auto x = decimal(text);
  if (!x) throw UsageError(option + " needs a finite decimal number, got '" + text + "'");
  return *x;
}

// each comma-separated item a number in (0, 1)
std::vector<double> tolerances(const std::string& option, const std::string& text) {
  std::vector<double> out;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const auto x = decimal(item);
    if (!x) throw UsageError(option + " needs numbers in (0, 1) separated by commas, got '" + text + "'");
    if (const std::string bad = beltsim::rtol_problem(*x); !bad.empty())
      throw UsageError(option + ": each " + bad);
    out.push_back(*x);
  }
  if (out.empty() || (!text.empty() && text.back() == ','))
    throw UsageError(option + " needs numbers in (0, 1) separated by commas, got '" + text + "'");
  return out;
}

void check_integrator(const std::string& name) {
  try {
    beltsim::check_integrator(name);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
}

std::string integrator_list() {
  std::string names;
  for (const auto& n : beltsim::integrator_names()) names += (names.empty() ? "" : ", ") + n;
  return names;
}

// the options as typed: text, turned into numbers and checked by overrides() and the commands,
// so every number goes through decimal()
struct Raw {
  std::optional<std::string> out, t_end, integrator, rtol, max_wall;
  bool no_frames = false;
  std::optional<std::string> integrators, rtols, ref_rtol, wall_limit;  // wp
  std::optional<std::string> from;                                      // plot
  bool trusted = false;                                                 // run, wp, console
  std::optional<std::string> max_instructions, max_lua_memory;
  std::vector<std::string> set;  // run, console, wp: --set KEY=VALUE; sweep: --set KEY=V1,V2,..
  std::optional<std::string> jobs, point, partition, time, max_parallel;  // sweep
  bool list = false, collect = false, slurm = false, submit = false;
};

void add_set(CLI::App* c, Raw& raw) {
  c->add_option("--set", raw.set,
                "a script parameter, read by the script as beltsim.args.KEY (numbers, true/false, text; repeatable); "
                "a key the script never reads is an error")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
}

void add_safety(CLI::App* c, Raw& raw) {
  c->add_flag("--trusted", raw.trusted,
              "the script gets every Lua library (os.execute, io anywhere, debug, C modules): only for scripts "
              "you trust");
  c->add_option("--max-instructions", raw.max_instructions,
                "Lua instructions per script run or console command (default 1e10; 0: no limit)")
      ->type_name("N");
  c->add_option("--max-lua-memory", raw.max_lua_memory, "Lua heap limit in MiB (default 4096; 0: no limit)")
      ->type_name("MiB");
}

beltsim::script::Safety safety(const Raw& raw) {
  beltsim::script::Safety s;
  s.trusted = raw.trusted;
  if (raw.max_instructions) {
    const double x = number("--max-instructions", *raw.max_instructions);
    if (!(x >= 0 && x == std::floor(x) && x <= 1e18))
      throw UsageError("--max-instructions must be a whole number in [0, 1e18] (0: no limit), got " +
                       *raw.max_instructions);
    s.max_instructions = static_cast<std::uint64_t>(x);
  }
  if (raw.max_lua_memory) {
    const double x = number("--max-lua-memory", *raw.max_lua_memory);
    if (!(x >= 0 && x <= 1e9))
      throw UsageError("--max-lua-memory must be in [0, 1e9] MiB (0: no limit), got " + *raw.max_lua_memory);
    s.max_lua_memory = static_cast<std::size_t>(x * (1 << 20));
    if (x > 0 && s.max_lua_memory < (std::size_t(1) << 20))
      throw UsageError("--max-lua-memory must be at least 1 MiB (0: no limit), got " + *raw.max_lua_memory);
  }
  return s;
}

void add_out_and_t_end(CLI::App* c, Raw& raw, const char* out_help) {
  c->add_option("--out", raw.out, out_help)->type_name("DIR");
  c->add_option("--t-end", raw.t_end, "end time [s] (> 0)")->type_name("T");
}

void add_run_overrides(CLI::App* c, Raw& raw) {
  add_out_and_t_end(c, raw, "output folder (default: out/<script name>)");
  c->add_option("--integrator", raw.integrator, "one of: " + integrator_list())->type_name("NAME");
  c->add_option("--rtol", raw.rtol, "relative tolerance of the step-size control, in (0, 1)")->type_name("R");
  c->add_option("--max-wall", raw.max_wall,
                "wall-time limit of each run [s]: a run past it stops at its last step, outputs closed, with an "
                "error (exit 1)")
      ->type_name("S");
  c->add_flag("--no-frames", raw.no_frames, "render no frames and no video, whatever the script asks");
  add_set(c, raw);
  add_safety(c, raw);
}

beltsim::script::Overrides overrides(const Raw& raw) {
  beltsim::script::Overrides o;
  o.out = raw.out;
  if (raw.t_end) {
    const double x = number("--t-end", *raw.t_end);
    if (!(x > 0)) throw UsageError("--t-end must be > 0 s, got " + *raw.t_end);
    o.t_end = x;
  }
  if (raw.integrator) {
    check_integrator(*raw.integrator);
    o.integrator = raw.integrator;
  }
  if (raw.rtol) {
    const double x = number("--rtol", *raw.rtol);
    if (const std::string bad = beltsim::rtol_problem(x); !bad.empty()) throw UsageError("--rtol " + bad);
    o.rtol = x;
  }
  if (raw.max_wall) {
    const double x = number("--max-wall", *raw.max_wall);
    if (!(x > 0)) throw UsageError("--max-wall must be > 0 s, got " + *raw.max_wall);
    o.max_wall = x;
  }
  o.no_frames = raw.no_frames;
  try {
    o.set = beltsim::script::parse_sets(raw.set);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  return o;
}

int cmd_run(const std::string& script, const beltsim::script::Overrides& o, const beltsim::script::Safety& s) {
  try {
    beltsim::script::Interpreter lua(s);
    const beltsim::script::Interruptible on_signal(lua);
    lua.set_overrides(o);
    lua.set_stop_flag(&stop_flag());
    lua.run_file(script);
    if (lua.interrupted() || stop_signal() != 0) return stopped_status();
    // a --set the script never read: the run did not use what was asked of it
    const std::vector<std::string> unread = lua.unread_args(script);
    for (const std::string& m : unread) std::fprintf(stderr, "beltsim: %s\n", m.c_str());
    if (!unread.empty()) return 1;
  } catch (const beltsim::script::ScriptError& e) {
    std::fprintf(stderr, "beltsim: %s\n%s", e.what(), beltsim::script::shown_traceback(e.traceback).c_str());
    return stop_signal() != 0 ? stopped_status() : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "beltsim: %s\n", e.what());
    beltsim::mark_output_failure_shown(e.what());
    return stop_signal() != 0 ? stopped_status() : 1;
  }
  return 0;
}

int cmd_wp(const std::string& script, const beltsim::script::Overrides& o, const beltsim::script::Safety& s,
           beltsim::WpSettings wps) {
  try {
    beltsim::script::Captured cap;
    beltsim::script::Interpreter lua(s);
    const beltsim::script::Interruptible on_signal(lua);
    beltsim::script::Overrides captured;  // --t-end and --set reach the script; --out is wp's own folder
    captured.t_end = o.t_end;
    captured.set = o.set;
    lua.set_overrides(captured);
    lua.set_capture(&cap);
    lua.run_file(script);
    if (!cap.scene) throw std::runtime_error(script + ": the script never calls scene:run{}");
    // the script stops at its first scene:run{}: a key read after it cannot be known (a warning)
    for (const std::string& m : lua.unread_args(script))
      std::fprintf(stderr, "beltsim wp: warning: %s (before its first scene:run{})\n", m.c_str());
    wps.base = cap.settings;
    wps.base.out_dir = o.out ? *o.out : (fs::path("out") / fs::path(script).stem() / "wp").string();
    const beltsim::WpResult r = beltsim::work_precision(*cap.scene, wps, &stop_flag());
    const std::string png = (fs::path(wps.base.out_dir) / "wp.png").string();
    std::string drawn;
    try {
      beltsim::plot::plot_wp_png(r, png);
      drawn = png;
    } catch (const std::exception& e) {  // the CSV is the result; the picture is a convenience
      std::fprintf(stderr, "beltsim wp: no plot: %s\n", e.what());
      beltsim::mark_output_failure_shown(e.what());  // (a picture that cannot be written fails the command)
    }
    std::fprintf(stderr, "beltsim wp: wrote %s%s%s\n", r.csv_path.c_str(), drawn.empty() ? "" : " and ", drawn.c_str());
    return stop_signal() != 0 ? stopped_status() : 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "beltsim: %s\n", e.what());
    beltsim::mark_output_failure_shown(e.what());
    return stop_signal() != 0 ? stopped_status() : 1;
  }
}

int cmd_plot(const std::string& csv, const std::vector<std::string>& columns, const Raw& raw,
             beltsim::term::ImageMode images) {
  const double from = raw.from ? number("--from", *raw.from) : -INFINITY;
  const std::string png = raw.out ? *raw.out : (fs::path(csv).parent_path() / "plot.png").string();
  try {
    beltsim::plot::plot_csv(csv, columns, from, png);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "beltsim: %s\n", e.what());
    beltsim::mark_output_failure_shown(e.what());
    return 1;
  }
  // the picture on a terminal (or wherever BELTSIM_TERM_IMAGES forces it), then the path
  std::fflush(stdout);
  std::string why;
  if (!beltsim::term::show_image_in_terminal(png, stdout, images, &why) && ::isatty(STDOUT_FILENO))
    std::fprintf(stderr, "beltsim plot: not shown in the terminal: %s\n", why.c_str());
  std::printf("%s\n", png.c_str());
  return 0;
}

int cmd_console(const std::optional<std::string>& script, const std::vector<std::string>& args,
                const beltsim::script::Overrides& o, const beltsim::script::Safety& s,
                const beltsim::app::Environment& env) {
  try {
    return beltsim::script::run_console(script, args, o, s, {env.history, env.images});
  } catch (const std::exception& e) {
    std::fprintf(stderr, "beltsim: %s\n", e.what());
    beltsim::mark_output_failure_shown(e.what());
    return 1;
  }
}

// the processors this process may run on (its affinity mask: a cgroup's or taskset's share)
int processors() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0) return CPU_COUNT(&set);
  const long n = sysconf(_SC_NPROCESSORS_ONLN);
  return n > 0 ? static_cast<int>(n) : 1;
}

int whole_number(const std::string& option, const std::string& text, int lo) {
  const double x = number(option, text);
  if (!(x == std::floor(x) && x >= lo && x <= 1e9))
    throw UsageError(option + " must be a whole number >= " + std::to_string(lo) + ", got " + text);
  return static_cast<int>(x);
}

// the quick form's grid: each --set KEY=V1,V2,.. a parameter, crossed in the order given (the
// first varies slowest); each value read as --set reads one
beltsim::sweep::Grid set_grid(const std::vector<std::string>& sets) {
  beltsim::sweep::Grid g;
  for (const std::string& kv : sets) {
    const std::size_t eq = kv.find('=');
    if (eq == std::string::npos) throw UsageError("--set " + kv + ": KEY=V1,V2,.. expected");
    const std::string key = kv.substr(0, eq), list = kv.substr(eq + 1);
    if (std::find(g.names.begin(), g.names.end(), key) != g.names.end())
      throw UsageError("--set " + key + " is given twice; give its values in one list: --set " + key + "=V1,V2,..");
    std::vector<beltsim::sweep::Value> values;
    std::size_t from = 0;
    while (true) {
      const std::size_t comma = list.find(',', from);
      const std::string item = list.substr(from, comma == std::string::npos ? std::string::npos : comma - from);
      try {
        const beltsim::script::ScriptArg a = beltsim::script::parse_set(key + "=" + item);
        std::visit([&](const auto& x) { values.emplace_back(x); }, a.value);
      } catch (const std::invalid_argument& e) {
        throw UsageError(std::string(e.what()) + " (in --set " + kv + ")");
      }
      if (comma == std::string::npos) break;
      from = comma + 1;
    }
    g.names.push_back(key);
    g.values.push_back(std::move(values));
  }
  return g;
}

// the arguments that give a point's process the same sweep: the file, the folder, the --set
// lists and the safety options as typed
std::vector<std::string> sweep_args(const std::string& file, const std::string& dir, const Raw& raw) {
  std::vector<std::string> a{"sweep", file, "--out", dir};
  for (const std::string& s : raw.set) a.insert(a.end(), {"--set", s});
  if (raw.trusted) a.push_back("--trusted");
  if (raw.max_instructions) a.insert(a.end(), {"--max-instructions", *raw.max_instructions});
  if (raw.max_lua_memory) a.insert(a.end(), {"--max-lua-memory", *raw.max_lua_memory});
  return a;
}

std::string params_text(const beltsim::sweep::Point& p) {
  std::string s;
  for (const auto& [name, v] : p.params) s += (s.empty() ? "" : ", ") + name + "=" + beltsim::sweep::value_text(v);
  return s;
}

int cmd_sweep(const std::string& file, const Raw& raw, const beltsim::script::Safety& s) {
  namespace sw = beltsim::sweep;
  const std::string dir = raw.out ? *raw.out : (fs::path("out") / fs::path(file).stem()).string();
  const std::string name = fs::path(file).stem().string();
  const bool quick = !raw.set.empty();
  const int jobs = raw.jobs ? whole_number("--jobs", *raw.jobs, 1) : processors();
  const int point = raw.point ? whole_number("--point", *raw.point, 0) : -1;
  if (!raw.slurm && (raw.submit || raw.partition || raw.time || raw.max_parallel))
    throw UsageError("--submit, --partition, --time and --max-parallel go with --slurm");
  if (int(point >= 0) + int(raw.list) + int(raw.collect) + int(raw.slurm) > 1)
    throw UsageError("give one of --point, --list, --collect and --slurm");
  std::vector<sw::Point> points;
  const sw::Grid grid = quick ? set_grid(raw.set) : sw::Grid{};
  try {
    beltsim::script::Interpreter lua(s);
    const beltsim::script::Interruptible on_signal(lua);
    lua.set_stop_flag(&stop_flag());
    if (quick) {
      if (!fs::is_regular_file(file)) throw beltsim::script::ScriptError(file + ": no such script");
      points = sw::grid_points(grid);
    } else {
      points = beltsim::script::load_sweep(lua, file);
    }
    if (raw.list) {
      std::string h = "point";
      for (const auto& [n, v] : points[0].params) h += "," + n;
      std::printf("%s\n", h.c_str());
      for (const sw::Point& p : points) {
        std::string r = p.id;
        for (const auto& [n, v] : p.params) r += "," + beltsim::csv_text(sw::value_text(v));
        std::printf("%s\n", r.c_str());
      }
      return 0;
    }
    if (point >= 0) {
      if (point >= static_cast<int>(points.size()))
        throw UsageError("--point " + std::to_string(point) + ": the sweep has points 0.." +
                         std::to_string(points.size() - 1));
      const sw::Point& p = points[static_cast<std::size_t>(point)];
      const std::string point_dir = (fs::path(dir) / p.id).string();
      std::fprintf(stderr, "beltsim sweep: point %s of %zu (%s)\n", p.id.c_str(), points.size(), params_text(p).c_str());
      const sw::PointResult r = quick ? beltsim::script::run_script_point(lua, file, p, point_dir)
                                      : beltsim::script::run_sweep_point(lua, file, p, point_dir);
      if (lua.interrupted() || stop_signal() != 0) return stopped_status();  // not a result: it runs again
      sw::write_point_result(dir, p, r);
      std::fprintf(stderr, "beltsim sweep: point %s: %s\n", p.id.c_str(), r.status.c_str());
      return r.ok() ? 0 : 1;
    }
  } catch (const beltsim::script::ScriptError& e) {
    std::fprintf(stderr, "beltsim: %s\n%s", e.what(), beltsim::script::shown_traceback(e.traceback).c_str());
    return stop_signal() != 0 ? stopped_status() : 1;
  } catch (const std::invalid_argument& e) {  // the grid of the --set lists
    throw UsageError(e.what());
  }

  const auto summary = [&] {
    const sw::SummaryCounts c = sw::write_summary(dir, points);
    std::fprintf(stderr, "beltsim sweep: %s/%s: %d ok, %d failed, %d not run\n", dir.c_str(), sw::kSummaryFile, c.ok,
                 c.failed, c.not_run);
    return c.failed + c.not_run == 0 ? 0 : 1;
  };
  if (raw.collect) return summary();
  if (raw.slurm) {
    sw::SlurmSettings ss;
    ss.program = sw::this_program();
    ss.dir = fs::absolute(dir).lexically_normal().string();
    ss.point_args = sweep_args(fs::absolute(file).lexically_normal().string(), ss.dir, raw);
    ss.collect_args = ss.point_args;
    ss.collect_args.push_back("--collect");
    ss.name = name;
    ss.workdir = fs::current_path().string();
    ss.partition = raw.partition;
    ss.time = raw.time;
    if (raw.max_parallel) ss.max_parallel = whole_number("--max-parallel", *raw.max_parallel, 1);
    sw::SlurmJobs j;
    try {
      j = sw::write_slurm_jobs(points, ss);
    } catch (const std::invalid_argument& e) {
      throw UsageError(e.what());
    }
    std::printf("%s\n%s\n", j.array_script.c_str(), j.collect_script.c_str());
    if (j.array.empty()) {
      std::fprintf(stderr, "beltsim sweep: every point is done: nothing to submit\n");
      return summary();
    }
    if (!raw.submit) {
      std::fprintf(stderr, "beltsim sweep: submit with\n  jid=$(sbatch --parsable %s)\n  sbatch --dependency=afterany:$jid %s\n",
                   j.array_script.c_str(), j.collect_script.c_str());
      return 0;
    }
    const auto [array, collect] = sw::submit_slurm_jobs(j);
    std::printf("%s %s\n", array.c_str(), collect.c_str());
    std::fprintf(stderr, "beltsim sweep: submitted job array %s (points %s) and job %s (summary.csv after it)\n",
                 array.c_str(), j.array.c_str(), collect.c_str());
    return 0;
  }
  sw::DriverSettings ds;
  ds.program = sw::this_program();
  ds.point_args = sweep_args(file, dir, raw);
  ds.dir = dir;
  ds.name = name;
  ds.jobs = jobs;
  ds.stop = &stop_flag();
  ds.stop_signal = [] { return stop_signal(); };
  const sw::DriverReport r = sw::run_points(points, ds);
  const int status = summary();
  return r.stopped ? stopped_status() : status;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"beltsim: belt transmissions, the discrete model of K. Kubas; scenarios are Lua scripts.", "beltsim"};
  app.set_version_flag("--version", "beltsim 0.1.0");
  app.require_subcommand(1);
  app.footer("Exit status: 0 on success, 1 on a script, parameter, run or plot error or an output that\n"
             "could not be written, 2 on bad usage, 130 after Ctrl-C, 143 after SIGTERM, 129 after SIGHUP\n"
             "(outputs closed). 'beltsim COMMAND --help' describes a command; 'beltsim help parameters' lists\n"
             "the scene's parameters with their units and defaults.");
  Raw raw;
  std::string script, csv;
  std::optional<std::string> console_script;
  std::vector<std::string> columns, console_args;

  CLI::App* run = app.add_subcommand("run", "run a Lua scenario script");
  run->add_option("SCRIPT", script, "the scenario (Lua)")->required();
  add_run_overrides(run, raw);
  run->footer("The options override the script's scene:run{} settings. Writes DIR/timeseries.csv (samples\n"
              "at fixed times) and DIR/parameters.csv, and the frames (PNG) and video (MP4) a script asks\n"
              "for with scene:run{ frames = {...} }.");

  CLI::App* wp = app.add_subcommand("wp", "error against run time of every integrator");
  wp->add_option("SCRIPT", script, "the scenario (Lua): its first scene:run{} gives the scene")->required();
  add_out_and_t_end(wp, raw, "output folder (default: out/<script name>/wp)");
  wp->add_option("--integrators", raw.integrators, "those to study, separated by commas (default: all)")
      ->type_name("A,B,..");
  wp->add_option("--rtols", raw.rtols, "tolerances (default 1e-2,1e-3,1e-4,1e-5,1e-6)")->type_name("R1,R2,..");
  wp->add_option("--ref-rtol", raw.ref_rtol, "tolerance of the esdirk32 reference run (default 1e-7)")->type_name("R");
  wp->add_option("--wall-limit", raw.wall_limit, "a run taking longer is stopped, unfinished (default 120)")
      ->type_name("S");
  add_set(wp, raw);
  add_safety(wp, raw);
  wp->footer("Runs the script's scene with every integrator at every tolerance, each against the\n"
             "reference. Writes DIR/wp.csv, DIR/wp.png (log-log, gnuplot) and DIR/<integrator>-<rtol>/.");

  CLI::App* plot = app.add_subcommand("plot", "draw columns of a timeseries.csv to a PNG");
  plot->add_option("CSV", csv, "a timeseries.csv written by run")->required();
  plot->add_option("COLUMNS", columns, "columns to draw (default: every <pulley>.omega)");
  plot->add_option("--out", raw.out, "the PNG (default: plot.png beside the CSV)")->type_name("PNG");
  plot->add_option("--from", raw.from, "draw samples with t >= T only [s]")->type_name("T");
  plot->footer("Prints the PNG's path; on a terminal also shows the picture (BELTSIM_TERM_IMAGES=off|symbols|\n"
               "sixel|kitty|iterm forces a mode). Columns of two units share the plot on two y axes.");

  beltsim::app::RenderOptions render_options;
  CLI::App* render = beltsim::app::add_render_command(app, render_options);
  beltsim::app::CompareOptions compare_options;
  CLI::App* compare = beltsim::app::add_compare_command(app, compare_options);

  CLI::App* console = app.add_subcommand("console", "an interactive Lua console with a live simulation");
  console->add_option("SCRIPT", console_script, "a scenario to load first");
  add_run_overrides(console, raw);
  console->footer("Arguments after -- are passed to the script.");

  CLI::App* sweep = app.add_subcommand("sweep", "run a sweep: many points, each a run, on every core or on Slurm");
  sweep->add_option("FILE", script, "a sweep file (returns beltsim.sweep{...}), or a script with --set lists")
      ->required();
  sweep->add_option("--out", raw.out, "the sweep's folder (default: out/<file name>)")->type_name("DIR");
  sweep->add_option("--jobs", raw.jobs, "points run at once (default: the processors this process may use)")
      ->type_name("N");
  sweep->add_option("--point", raw.point, "run point K alone, in this process (0-based, as --list numbers them)")
      ->type_name("K");
  sweep->add_flag("--list", raw.list, "print the points (CSV) and run nothing");
  sweep->add_flag("--collect", raw.collect, "merge the points' results into summary.csv and run nothing");
  sweep->add_option("--set", raw.set,
                    "the quick form: FILE is an ordinary script and each KEY=V1,V2,.. one parameter "
                    "(beltsim.args.KEY); the lists are crossed, the first varying slowest (repeatable)")
      ->type_name("KEY=V1,V2,..")
      ->allow_extra_args(false);
  sweep->add_flag("--slurm", raw.slurm, "write DIR/sweep.sbatch (a job array) and DIR/collect.sbatch, run nothing");
  sweep->add_flag("--submit", raw.submit, "with --slurm: submit both with sbatch and print the job ids");
  sweep->add_option("--partition", raw.partition, "with --slurm: the partition")->type_name("P");
  sweep->add_option("--time", raw.time, "with --slurm: each task's time limit (Slurm's format, e.g. 30 or 1:00:00)")
      ->type_name("T");
  sweep->add_option("--max-parallel", raw.max_parallel, "with --slurm: tasks running at once (--array=..%M)")
      ->type_name("M");
  add_safety(sweep, raw);
  sweep->footer("Each point runs in a process of its own with its folder DIR/<point>/ (point.csv: its parameters,\n"
                "status and figures; log.txt: its messages); DIR/summary.csv merges them. Run again: only the\n"
                "points not ok run. Exit status 0 when every point is ok, 1 otherwise. docs/sweeps.md.");

  // `beltsim console ... -- ARGS`: everything after the first -- belongs to the script
  std::vector<std::string> words(argv + 1, argv + argc);
  if (!words.empty() && words[0] == "console") {
    const auto dd = std::find(words.begin(), words.end(), "--");
    if (dd != words.end()) {
      console_args.assign(dd + 1, words.end());
      words.erase(dd, words.end());
    }
  }
  if (words.size() == 2 && words[0] == "help" && words[1] == "parameters") {
    // the scene's parameter tables, as docs/lua-api.md holds them (scene/parameters.hpp)
    std::fputs(beltsim::parameters_markdown().c_str(), stdout);
    return 0;
  }
  if (!words.empty() && words[0] == "help") words[0] = "--help";
  const std::vector<std::string> commands{"run", "wp", "plot", "render", "compare", "console", "sweep"};
  if (!words.empty() && !words[0].empty() && words[0][0] == '-' && words[0] != "-h" && words[0] != "--help" &&
      words[0] != "--version") {
    std::fprintf(stderr, "beltsim: unknown option '%s' before the command\nRun 'beltsim --help' for the usage.\n",
                 words[0].c_str());
    return 2;
  }
  if (!words.empty() && (words[0].empty() || words[0][0] != '-') &&
      std::find(commands.begin(), commands.end(), words[0]) == commands.end()) {
    std::fprintf(stderr, "beltsim: unknown command '%s' (commands: run, wp, plot, render, compare, console, sweep)\n"
                 "Run 'beltsim --help' for the usage.\n", words[0].c_str());
    return 2;
  }
  std::reverse(words.begin(), words.end());  // CLI11 takes the arguments in reverse order
  try {
    app.parse(words);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    const CLI::App* sub = app.get_subcommands().empty() ? nullptr : app.get_subcommands().front();
    const std::string name = sub ? sub->get_name() : "";
    std::string msg = e.what();
    if (dynamic_cast<const CLI::ExtrasError*>(&e)) {
      std::string extra;
      for (const auto& w : app.remaining(true)) extra += (extra.empty() ? "" : " ") + w;
      msg = (sub ? name + " does not take: " : "unexpected: ") + extra +
            (name == "console" ? " (arguments for the script go after --)" : "");
    }
    std::fprintf(stderr, "beltsim: %s\nRun 'beltsim%s --help' for the usage.\n", msg.c_str(),
                 name.empty() ? "" : (" " + name).c_str());
    return 2;
  }

  beltsim::app::Environment env;
  try {
    env = beltsim::app::read_environment();
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "beltsim: %s\n", e.what());
    return 2;
  }
  beltsim::app::apply_render_settings(env);

  try {
    if (*render) return with_outputs(beltsim::app::cmd_render(render_options));
    if (*compare) return with_outputs(beltsim::app::cmd_compare(compare_options));
    if (*plot) return with_outputs(cmd_plot(csv, columns, raw, env.images));  // a signal ends it at once: nothing to close
    beltsim::script::install_stop_signals();
    if (*run) return with_outputs(cmd_run(script, overrides(raw), safety(raw)));
    if (*sweep) return with_outputs(cmd_sweep(script, raw, safety(raw)));
    if (*console) return with_outputs(cmd_console(console_script, console_args, overrides(raw), safety(raw), env));
    // wp
    beltsim::WpSettings wps;
    if (raw.integrators) {
      std::stringstream ss(*raw.integrators);
      std::string item;
      while (std::getline(ss, item, ',')) {
        check_integrator(item);
        wps.integrators.push_back(item);
      }
      if (wps.integrators.empty()) throw UsageError("--integrators needs names separated by commas");
    }
    if (raw.rtols) wps.rtols = tolerances("--rtols", *raw.rtols);
    if (raw.ref_rtol) {
      const double x = number("--ref-rtol", *raw.ref_rtol);
      if (const std::string bad = beltsim::rtol_problem(x); !bad.empty()) throw UsageError("--ref-rtol " + bad);
      wps.ref_rtol = x;
    }
    if (raw.wall_limit) {
      const double x = number("--wall-limit", *raw.wall_limit);
      if (!(x > 0)) throw UsageError("--wall-limit must be > 0 s, got " + *raw.wall_limit);
      wps.wall_limit = x;
    }
    return with_outputs(cmd_wp(script, overrides(raw), safety(raw), wps));
  } catch (const UsageError& e) {
    const CLI::App* sub = app.get_subcommands().front();
    std::fprintf(stderr, "beltsim: %s\nRun 'beltsim %s --help' for the usage.\n", e.what(), sub->get_name().c_str());
    return 2;
  }
}
