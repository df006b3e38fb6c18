// `beltsim sweep FILE`: the points of a sweep run on this machine's processors, one at a time
// (--point), listed, collected, or written as a Slurm job array (commands.hpp, sweep/).
#include <fcntl.h>
#include <sched.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <stdexcept>
#include <utility>

#include "app/commands.hpp"
#include "io/csv_writer.hpp"
#include "io/output_dir.hpp"
#include "script/docall.hpp"
#include "script/interpreter.hpp"
#include "script/script_args.hpp"
#include "script/signals.hpp"
#include "script/sweep_run.hpp"
#include "sweep/driver.hpp"
#include "sweep/inputs.hpp"
#include "sweep/results.hpp"
#include "sweep/slurm.hpp"

namespace beltsim::app {

namespace {

namespace fs = std::filesystem;

using script::stop_flag;
using script::stop_signal;
using script::stopped_status;

// the processors this process may run on (its affinity mask: a cgroup's or taskset's share)
int processors() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof set, &set) == 0 && CPU_COUNT(&set) > 0) return CPU_COUNT(&set);
  const long n = sysconf(_SC_NPROCESSORS_ONLN);
  return n > 0 ? static_cast<int>(n) : 1;
}

// stdout sent to stderr while this lives (flushed at both ends)
class StdoutToStderr {
 public:
  StdoutToStderr() {
    std::fflush(stdout);
    saved_ = fcntl(1, F_DUPFD_CLOEXEC, 0);
    if (saved_ >= 0 && dup2(2, 1) < 0) ::close(std::exchange(saved_, -1));
  }
  ~StdoutToStderr() {
    std::fflush(stdout);
    if (saved_ >= 0) dup2(saved_, 1), ::close(saved_);
  }
  StdoutToStderr(const StdoutToStderr&) = delete;
  StdoutToStderr& operator=(const StdoutToStderr&) = delete;

 private:
  int saved_ = -1;
};

// what defines a point now, bar its files (sweep/inputs.hpp): the program and, of the options,
// --trusted. The --set lists are the grid: each point's own values are its parameters, matched
// already (sweep/results.hpp); the limits only
// decide whether a point fails, and a failed point runs again anyway. The sweep file: a point
// run from another is not this sweep's (its path as the loader records it, script/load_source).
beltsim::sweep::Definition definition(const Raw& raw, const std::string& file) {
  return {beltsim::sweep::program_identity(),
          raw.trusted ? "--trusted" : "",
          {},
          fs::absolute(file).lexically_normal().string()};
}

// the arguments that give a point's process the same sweep: the file, the folder, the --set
// lists and the safety options as typed
std::vector<std::string> sweep_args(const std::string& file, const std::string& dir, const Raw& raw) {
  std::vector<std::string> a{"sweep", file, "--out", dir};
  for (const std::string& s : raw.set) a.insert(a.end(), {"--set", s});
  const std::vector<std::string> safe = safety_words(raw);
  a.insert(a.end(), safe.begin(), safe.end());
  return a;
}

// the Slurm jobs of this sweep (the paths absolute), checked before anything is loaded or
// written: a UsageError for what the batch scripts cannot hold or Slurm would not take
beltsim::sweep::SlurmSettings slurm_settings(const std::string& file, const std::string& dir, const std::string& name,
                                             const Raw& raw) {
  beltsim::sweep::SlurmSettings ss;
  ss.program = beltsim::sweep::this_program();
  ss.dir = fs::absolute(dir).lexically_normal().string();
  ss.point_args = sweep_args(fs::absolute(file).lexically_normal().string(), ss.dir, raw);
  ss.collect_args = ss.point_args;
  ss.collect_args.push_back("--collect");
  ss.name = name;
  ss.workdir = fs::current_path().string();
  ss.partition = raw.partition;
  ss.time = raw.time;
  if (raw.max_parallel) ss.max_parallel = whole_number("--max-parallel", *raw.max_parallel, 1);
  ss.rerun = raw.rerun;
  try {
    beltsim::sweep::check_slurm_settings(ss);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  return ss;
}

// --collect over a folder that holds no point of this sweep (another sweep's, a run's) is refused,
// as is one another sweep file's points fill (std::runtime_error); the sweep's own folder whose
// points all died before writing a result is collected
void check_collect_folder(const std::string& dir, const std::string& file,
                          const std::vector<beltsim::sweep::Point>& points) {
  namespace sw = beltsim::sweep;
  std::error_code ec;
  int found = 0;
  // the sweep's own folder whose points all died before writing a result (a Slurm array
  // cancelled or timed out): its job scripts naming this sweep file, or a point's folder without
  // a point.csv, are there, and the summary says 'not run' for each
  bool ours = false;
  {
    std::ifstream job(fs::path(dir) / "sweep.sbatch");
    const std::string text{std::istreambuf_iterator<char>(job), std::istreambuf_iterator<char>()};
    ours = !text.empty() && text.find(fs::absolute(file).lexically_normal().string()) != std::string::npos;
  }
  for (const sw::Point& p : points) {
    ours =
        ours || (fs::is_directory(fs::path(dir) / p.id, ec) && !fs::exists(fs::path(dir) / p.id / sw::kPointFile, ec));
    if (const std::optional<sw::PointResult> r = sw::read_point_result(dir, p)) {
      ++found;
      const std::optional<sw::Inputs> in = sw::parse_inputs(r->inputs);
      if (in && !in->files.empty() && !sw::same_file(in->files.front().first, file))
        throw std::runtime_error("--collect: " + dir + " holds the points of " + in->files.front().first + ", not of " +
                                 file + ": give " + file + "'s own folder (--out)");
    }
  }
  if (found == 0 && !ours)
    throw std::runtime_error("--collect: no point of " + file + " has run in " + dir +
                             " (a sweep's folder holds a folder for each point): nothing to collect");
}

// the quick form into a folder that holds another study (points of other parameters: the default
// folder out/<script> is every study's of the script) is refused, rather than replace that study's
// summary.csv and run its points' folders again (std::runtime_error)
void check_same_study(const std::string& dir, const std::vector<beltsim::sweep::Point>& points) {
  std::vector<std::string> now;
  for (const auto& [name, v] : points[0].params) now.push_back(name);
  if (const std::string r = beltsim::sweep::other_study_refusal(dir, now); !r.empty()) throw std::runtime_error(r);
}

int sweep(const std::string& file, const Raw& raw, const script::Safety& s) {
  namespace sw = beltsim::sweep;
  const std::string dir = raw.out ? *raw.out : script::default_out_dir(file);
  const std::string name = fs::path(file).stem().string();
  const bool quick = !raw.set.empty();
  const int jobs = raw.jobs ? whole_number("--jobs", *raw.jobs, 1) : processors();
  const int point = raw.point ? whole_number("--point", *raw.point, 0) : -1;
  if (!raw.slurm && (raw.submit || raw.partition || raw.time || raw.max_parallel))
    throw UsageError("--submit, --partition, --time and --max-parallel go with --slurm");
  if (int(point >= 0) + int(raw.list) + int(raw.collect) + int(raw.slurm) > 1)
    throw UsageError("give one of --point, --list, --collect and --slurm");
  // --jobs sets how many points this process runs at once: with --point (one point, in this
  // process), --list and --collect (none) and --slurm (Slurm runs them: --max-parallel) it would
  // be ignored, and a user who asked for 2 would not learn that nothing ran 2 at a time
  if (raw.jobs && (point >= 0 || raw.list || raw.collect || raw.slurm))
    throw UsageError("--jobs goes with running the points on this machine" +
                     std::string(raw.slurm ? " (with --slurm, --max-parallel bounds the tasks running at once)"
                                           : ": --point runs one point, --list and --collect run none"));
  if (raw.rerun && (point >= 0 || raw.list || raw.collect))
    throw UsageError("--rerun goes with running the points or --slurm (--point runs its point in any case)");
  std::optional<sw::SlurmSettings> slurm;
  if (raw.slurm) slurm = slurm_settings(file, dir, name, raw);
  std::vector<sw::Point> points;
  sw::Grid grid;
  try {
    if (quick) grid = script::set_grid(raw.set);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  try {
    script::Interpreter lua(s);
    const script::Interruptible on_signal(lua);
    lua.set_stop_flag(&stop_flag());
    if (quick) {
      if (std::error_code ec; !fs::is_regular_file(file, ec))
        throw script::ScriptError(
            file + (fs::exists(file, ec) ? ": not a regular file (a script is read whole, once)" : ": no such script"));
      points = sw::grid_points(grid);
      // a sweep file given --set lists: refused before a point runs, is listed or anything is
      // written (each point failed, and a finished sweep's summary.csv and point.csv were replaced
      // by errors; --list listed the --set lists' points). What the script prints as it is probed
      // goes to stderr under --list, whose stdout is the points' CSV. --point's run of the script
      // refuses it the same way (script/sweep_run.hpp)
      if (point < 0) {
        std::optional<StdoutToStderr> quiet;
        if (raw.list) quiet.emplace();
        script::check_ordinary_script(lua, file, points[0]);
      }
    } else {
      points = script::load_sweep(lua, file);
    }
    if (raw.list) {
      std::string h = "point";
      for (const auto& [n, v] : points[0].params) h += "," + n;
      std::printf("%s\n", h.c_str());
      for (const sw::Point& p : points) {
        std::string r = p.id;
        for (const auto& [n, v] : p.params) r.append(",").append(csv_text(sw::value_text(v)));
        std::printf("%s\n", r.c_str());
      }
      return 0;
    }
    if (point >= 0) {
      if (point >= static_cast<int>(points.size()))
        throw UsageError("--point " + std::to_string(point) + ": the sweep has points 0.." +
                         std::to_string(points.size() - 1));
      // the quick form's point into a folder of another study replaced that study's point K, as
      // the whole sweep would have replaced them all (a check that the sweep running its points
      // has made already, on the folder it holds)
      if (quick) check_same_study(dir, points);
      const sw::Point& p = points[static_cast<std::size_t>(point)];
      const std::string point_dir = (fs::path(dir) / p.id).string();
      std::fprintf(stderr, "beltsim sweep: point %s of %zu (%s)\n", p.id.c_str(), points.size(),
                   sw::params_text(p).c_str());
      sw::PointResult r = sw::unique_columns(p, quick ? script::run_script_point(lua, file, p, point_dir)
                                                      : script::run_sweep_point(lua, file, p, point_dir));
      if (lua.interrupted() || stop_signal() != 0) return stopped_status();  // not a result: it runs again
      const sw::Definition d = definition(raw, file);
      sw::Inputs in{d.program, d.options, {}};
      for (const script::LoadedFile& f : lua.loaded_files()) in.files.emplace_back(f.path, f.sha256);
      r.inputs = sw::inputs_text(in);
      sw::write_point_result(dir, p, r);
      std::fprintf(stderr, "beltsim sweep: point %s: %s\n", p.id.c_str(), r.status.c_str());
      return r.ok() ? 0 : 1;
    }
  } catch (const script::WrongFileKind& e) {
    throw UsageError(e.what());
  } catch (const script::ScriptError& e) {
    std::fprintf(stderr, "beltsim: %s\n%s", e.what(), script::shown_traceback(e.traceback).c_str());
    return stop_signal() != 0 ? stopped_status() : 1;
  } catch (const std::invalid_argument& e) {  // the grid of the --set lists
    throw UsageError(e.what());
  }

  // a summary merged over a folder that holds no point of this sweep replaced another sweep's
  // summary.csv with rows of 'outdated' or 'not run', or wrote one into a run's folder: refused
  // (the folder's existence before it is claimed, the points once no other sweep holds it)
  std::error_code ec;
  if (raw.collect && !fs::is_directory(dir, ec))
    throw std::runtime_error("--collect: " + dir + " is not a folder: nothing to collect");
  const OutputDir top = sw::claim_sweep_folder(dir);  // held to the end: one sweep at a time on the folder
  if (quick && !raw.collect) check_same_study(dir, points);
  if (raw.collect) check_collect_folder(dir, file, points);
  // the earlier folders of points a sweep killed outright was running again, put back (or removed
  // when the run had ended) before the points' results are read
  for (const std::string& line : sw::settle_earlier_folders(top, name)) std::fprintf(stderr, "%s\n", line.c_str());
  // the closing line counts the results summary.csv holds, whenever they ran (as the last progress
  // line does)
  const auto summary = [&] {
    const sw::SummaryCounts c =
        sw::write_summary(dir, points, definition(raw, file), quick ? sw::Figures::kRunResult : sw::Figures::kOwn);
    std::fprintf(stderr,
                 "beltsim sweep: %s/%s: %d ok%s, %d failed, %d not run (the results it holds of the %zu points, "
                 "whenever they ran)\n",
                 dir.c_str(), sw::kSummaryFile, c.ok, c.over_text().c_str(), c.failed, c.not_run, points.size());
    return c.failed + c.not_run == 0 ? 0 : 1;
  };
  if (raw.collect) return summary();
  if (slurm) {
    slurm->definition = definition(raw, file);
    const sw::SlurmJobs j = sw::write_slurm_jobs(points, *slurm);
    if (j.array.empty()) {
      std::fprintf(stderr,
                   "beltsim sweep: every point is done: nothing to submit (the job scripts left as they were)\n");
      return summary();
    }
    for (const std::string& line : sw::reason_lines(name, j.reasons)) std::fprintf(stderr, "%s\n", line.c_str());
    if (const std::string line = sw::moved_line(name, top, sw::move_stale_folders(top, points)); !line.empty())
      std::fprintf(stderr, "%s\n", line.c_str());
    std::printf("%s\n%s\n", j.array_script.c_str(), j.collect_script.c_str());
    if (!raw.submit) {
      std::fprintf(
          stderr, "beltsim sweep: submit with\n  jid=$(sbatch --parsable %s)\n  sbatch --dependency=afterany:$jid %s\n",
          sw::shell_quoted(j.array_script).c_str(), sw::shell_quoted(j.collect_script).c_str());
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
  ds.definition = definition(raw, file);
  ds.rerun = raw.rerun;
  ds.quick = quick;
  ds.stop = &stop_flag();
  ds.stop_signal = [] { return stop_signal(); };
  sw::DriverReport r;
  try {
    r = sw::run_points(points, ds, top);
  } catch (const std::exception&) {
    // the points finished before the error are in the summary; the error is what is told (a
    // summary that cannot be written either is recorded and named by main as well)
    try {
      summary();
    } catch (const std::exception&) {
    }
    throw;
  }
  const int status = summary();
  return r.stopped ? stopped_status() : status;
}

}  // namespace

int cmd_sweep(const std::string& file, const Raw& raw, const script::Safety& s) {
  try {
    return sweep(file, raw, s);
  } catch (const UsageError&) {
    throw;
  } catch (const std::exception& e) {  // a folder or a file that cannot be written, sbatch failing, ...
    std::fprintf(stderr, "beltsim: %s\n", e.what());
    mark_output_failure_shown(e.what());
    return stop_signal() != 0 ? stopped_status() : 1;
  }
}

}  // namespace beltsim::app
