// Runs the points of a sweep on several processes of this machine (docs/sweeps.md).
//
// Each point that is not done (sweep/results.hpp) runs in a process of its own, the beltsim
// program run again with `--point K`, so that a crash or a limit of one point leaves the others
// running. Its standard output and error go to DIR/<id>/log.txt; it writes DIR/<id>/point.csv
// itself, and a process that ends without one (a crash, a kill) gets a point.csv with an error
// status from here. The children run in process groups of their own: a stop (Ctrl-C, SIGTERM)
// reaches them from here, once, and the sweep waits for them to close their outputs; when the
// sweep dies without a word (kill -9) they get SIGTERM (PR_SET_PDEATHSIG).
// A point that has a result from an earlier run (failed, outdated, or any with --rerun) keeps it
// while it runs again: its earlier folder is moved aside whole (keep_earlier_folder,
// sweep/results.hpp) and the point runs in a new one; the result its process writes at its end (or
// the error of a process that died) replaces it, the earlier folder removed, and a point stopped
// before its end gets its earlier folder back, result and files.
// A progress line on stderr says the points done, failed and running and an estimate of the time
// left (rewritten in place on a terminal, a line per finished point otherwise). Done and failed
// count the results summary.csv holds, a point waiting or running counted when its run ends;
// the last line, when nothing runs, counts them all, as the summary's closing line does.
#pragma once

#include <atomic>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "io/output_dir.hpp"
#include "sweep/inputs.hpp"
#include "sweep/points.hpp"

namespace beltsim::sweep {

struct DriverSettings {
  std::string program;                  // the beltsim executable
  std::vector<std::string> point_args;  // its arguments but `--point K`: {"sweep", FILE, "--out", DIR, ...}
  std::string dir;                      // the sweep's output folder
  std::string name;                     // for the progress line
  int jobs = 1;
  Definition definition;                    // what defines a point now: a point done with other inputs runs again
  bool rerun = false;                       // every point runs, done or not (--rerun)
  bool quick = false;                       // the quick form (--set lists over an ordinary script)
  const std::atomic<bool>* stop = nullptr;  // raised by a stop signal
  std::function<int()> stop_signal;         // the signal received (forwarded to the children)
};

struct DriverReport {
  int already_done = 0;  // ok before this run, with the inputs of now
  int outdated = 0;      // run before with other inputs (running again)
  bool stopped = false;
};

// the time left [s] that the progress line gives: each point is taken to last the mean of `ran`,
// the times of the points that ran to their end (ok) in this run; each running one that mean less
// `running`, its elapsed time (nothing when past it); the `waiting` points start as the `jobs`
// processes come free. nullopt when there is no basis (`ran` empty) or the figure is 0 (only points
// running past the mean are left).
std::optional<double> time_left(const std::vector<double>& ran, const std::vector<double>& running, int waiting,
                                int jobs);

// runs every point not done yet (every point with rerun), saying on stderr which run again for a
// change in their inputs and what changed; throws std::runtime_error when a process cannot be started or
// waited for, after stopping the points running (SIGTERM) and
// waiting for them; top is s.dir, claimed by the caller (claim_sweep_folder, sweep/results.hpp)
DriverReport run_points(const std::vector<Point>& points, const DriverSettings& s, const OutputDir& top);

}  // namespace beltsim::sweep
