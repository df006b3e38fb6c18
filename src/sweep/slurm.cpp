#include "sweep/slurm.hpp"

#include <stdexcept>

#include "io/output_dir.hpp"
#include "sweep/capture.hpp"
#include "sweep/results.hpp"

namespace beltsim::sweep {

namespace {

// one word for sh: single-quoted unless it is plain
std::string shell_word(const std::string& s) {
  if (!s.empty() && s.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-./=,:+@%") ==
                        std::string::npos)
    return s;
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string command(const std::string& program, const std::vector<std::string>& args) {
  std::string c = shell_word(program);
  for (const std::string& a : args) {
    c += ' ';
    c += shell_word(a);
  }
  return c;
}

std::string header(const SlurmSettings& s, const std::string& what) {
  std::string h = "#!/bin/sh\n# " + what + " (written by beltsim sweep --slurm)\n";
  h += "#SBATCH --job-name=" + shell_word("beltsim-" + s.name) + "\n";
  h += "#SBATCH --chdir=" + shell_word(s.workdir) + "\n";
  h += "#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n";
  if (s.partition) h += "#SBATCH --partition=" + *s.partition + "\n";
  if (s.time) h += "#SBATCH --time=" + *s.time + "\n";
  return h;
}

// the standard output of args; throws with its standard error when it fails
std::string output_of(const std::vector<std::string>& args) {
  Captured r = run_capture(args);
  if (r.status != 0) {
    while (!r.err.empty() && (r.err.back() == '\n' || r.err.back() == '\r')) r.err.pop_back();
    std::string c;
    for (const std::string& x : args) c += (c.empty() ? "" : " ") + x;
    throw std::runtime_error(c + " failed" + (r.err.empty() ? std::string() : ": " + r.err));
  }
  return r.out;
}

}  // namespace

std::string index_ranges(const std::vector<int>& indices) {
  std::string s;
  for (std::size_t i = 0; i < indices.size();) {
    std::size_t j = i;
    while (j + 1 < indices.size() && indices[j + 1] == indices[j] + 1) ++j;
    if (!s.empty()) s += ',';
    s += std::to_string(indices[i]);
    if (j > i) {
      s += '-';
      s += std::to_string(indices[j]);
    }
    i = j + 1;
  }
  return s;
}

void check_slurm_settings(const SlurmSettings& s) {
  const auto plain = [](const std::string& v, const char* allowed) {
    return !v.empty() && v.find_first_not_of(allowed) == std::string::npos;
  };
  if (s.partition && !plain(*s.partition, "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-.,"))
    throw std::invalid_argument(
        "--partition: a Slurm partition name (letters, digits, _-., and commas) expected, got '" + *s.partition + "'");
  if (s.time && !plain(*s.time, "0123456789:-"))
    throw std::invalid_argument("--time: Slurm's time format (minutes, MM:SS, HH:MM:SS or D-HH:MM:SS) expected, got '" +
                                *s.time + "'");
  if (s.max_parallel < 0) throw std::invalid_argument("--max-parallel must be >= 1");
}

SlurmJobs write_slurm_jobs(const std::vector<Point>& points, const SlurmSettings& s) {
  check_slurm_settings(s);
  std::vector<int> todo;
  for (const Point& p : points) {
    const auto r = read_point_result(s.dir, p);
    if (!r || !r->ok()) todo.push_back(p.index);
  }
  SlurmJobs jobs;
  jobs.array = index_ranges(todo);
  const OutputDir top(s.dir);
  std::string a = header(s, "sweep " + s.name + ": " + std::to_string(todo.size()) + " of " +
                                std::to_string(points.size()) + " points, one array task each");
  if (!todo.empty()) {
    a += "#SBATCH --array=" + jobs.array;
    if (s.max_parallel > 0) a += '%' + std::to_string(s.max_parallel);
    a += '\n';
  }
  a += "#SBATCH --output=" + shell_word(s.dir + "/slurm-%A_%a.out") + "\n";
  std::vector<std::string> point = s.point_args;
  point.push_back("--point");
  a += "exec " + command(s.program, point) + " \"$SLURM_ARRAY_TASK_ID\"\n";
  write_file_whole(top, "sweep.sbatch", a);
  std::string c = header(s, "sweep " + s.name + ": summary.csv from the points' results, after the array");
  c += "#SBATCH --output=" + shell_word(s.dir + "/slurm-%j-collect.out") + "\n";
  c += "exec " + command(s.program, s.collect_args) + "\n";
  write_file_whole(top, "collect.sbatch", c);
  jobs.array_script = top.file("sweep.sbatch");
  jobs.collect_script = top.file("collect.sbatch");
  return jobs;
}

std::pair<std::string, std::string> submit_slurm_jobs(const SlurmJobs& jobs) {
  const auto id = [](std::string out) {
    // --parsable: "jobid" or "jobid;cluster"
    out = out.substr(0, out.find_first_of(";\n"));
    if (out.empty() || out.find_first_not_of("0123456789") != std::string::npos)
      throw std::runtime_error("sbatch printed no job id: '" + out + "'");
    return out;
  };
  const std::string array = id(output_of({"sbatch", "--parsable", jobs.array_script}));
  const std::string collect =
      id(output_of({"sbatch", "--parsable", "--dependency=afterany:" + array, jobs.collect_script}));
  return {array, collect};
}

}  // namespace beltsim::sweep
