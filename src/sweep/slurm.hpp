// A sweep as a Slurm job array (docs/sweeps.md, "On a cluster").
//
// DIR/sweep.sbatch is the array: one task per point not done yet (--array=0-3,7%M), each running
// `beltsim sweep FILE --out DIR --point $SLURM_ARRAY_TASK_ID`. DIR/collect.sbatch merges
// summary.csv (`beltsim sweep FILE --out DIR --collect`) and is submitted with
// --dependency=afterany on the array, so that it runs however the tasks end. Paths are absolute
// and the jobs start in the folder the command was given in, as a Slurm user expects of a job
// script written by a tool. Each task's output is DIR/slurm-<array job>_<task>.out.
//
// Every value is written so that each reader takes it back exactly: the command line quoted for
// sh, the #SBATCH values for sbatch's own reader of those lines (double quotes, \ and " escaped),
// and the folder in --output with each % doubled, as Slurm expands %j, %u, %x, ... there.
// What no quoting makes safe is refused before anything is written (check_slurm_settings).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "sweep/capture.hpp"
#include "sweep/inputs.hpp"
#include "sweep/points.hpp"
#include "sweep/results.hpp"

namespace beltsim::sweep {

struct SlurmSettings {
  std::string program;                    // the beltsim executable (absolute)
  std::vector<std::string> point_args;    // its arguments but `--point K` (paths absolute)
  std::vector<std::string> collect_args;  // its arguments that merge the summary
  std::string dir;                        // the sweep's output folder (absolute)
  std::string name;                       // the job's name: beltsim-<name>
  std::string workdir;                    // the jobs' working folder (absolute)
  std::optional<std::string> partition;   // --partition
  std::optional<std::string> time;        // --time, Slurm's format (minutes, MM:SS, HH:MM:SS, D-HH)
  int max_parallel = 0;                   // the array's %M; 0: as many as Slurm gives
  Definition definition;                  // what defines a point now (a point done otherwise runs again)
  bool rerun = false;                     // every point in the array (--rerun)
};

struct SlurmJobs {
  std::string array_script, collect_script;  // the files written ("" when none was)
  std::string array;                         // the --array value ("" when every point is done)
  Reasons reasons;                           // why points done before are in it again (rerun_reasons)
};

// "0-3,7,9-12" for the sorted indices
std::string index_ranges(const std::vector<int>& indices);
// one word for sh: bare when it has only characters sh reads as they are, else single-quoted
std::string shell_quoted(const std::string& s);
// throws std::invalid_argument, with the reason and the value, for what the scripts cannot hold
// or Slurm would not take: a control character in any value (a line break would end a line of
// the script and run the rest as a command), a backslash in the folder (Slurm drops it from an
// --output path), a path or name longer than slurmctld takes, a partition list or a time not in
// Slurm's forms, a time Slurm reads as no limit (0, -1)
void check_slurm_settings(const SlurmSettings& s);
// writes both scripts for the points not done (sweep/results.hpp); when every point is done,
// neither (the scripts of an earlier --slurm are left as they were) and the array is ""
SlurmJobs write_slurm_jobs(const std::vector<Point>& points, const SlurmSettings& s);
// each sbatch's time and output bound: it answers in a second or two, one short line
inline constexpr CaptureLimits kSbatchLimits{120, 65536};
// submits them with sbatch (the collector after the array, afterany), each run within limits;
// the two job ids. Throws std::runtime_error with sbatch's message when it fails or is missing,
// passes a limit or prints anything but a job id (and, when only the collector failed, the
// array's id and the command that submits the collector).
std::pair<std::string, std::string> submit_slurm_jobs(const SlurmJobs& jobs,
                                                      const CaptureLimits& limits = kSbatchLimits);

}  // namespace beltsim::sweep
