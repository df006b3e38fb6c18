#include "sweep/slurm.hpp"

#include <algorithm>
#include <stdexcept>

#include "io/number_text.hpp"
#include "io/output_dir.hpp"
#include "sweep/capture.hpp"
#include "sweep/results.hpp"

namespace beltsim::sweep {

namespace {

// the characters neither sh nor sbatch's reader of #SBATCH lines treat specially
const char* const kPlain = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-./=,:+@%";
// the longest --output and --chdir path slurmctld takes (PATH_MAX), and the longest job name
constexpr std::size_t kSlurmPathMax = 4096, kSlurmNameMax = 1024;

std::string command(const std::string& program, const std::vector<std::string>& args) {
  std::string c = shell_quoted(program);
  for (const std::string& a : args) {
    c += ' ';
    c += shell_quoted(a);
  }
  return c;
}

// one argument of an #SBATCH line as sbatch reads it: bare when it has none of the characters
// its reader treats specially (white space, ' and " group, \ escapes, # starts a comment), else
// between double quotes with each \ and " preceded by a backslash (the reader takes the character
// after a backslash as it is, between quotes too)
std::string sbatch_word(const std::string& s) {
  if (!s.empty() && s.find_first_not_of(kPlain) == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) {
    if (c == '\\' || c == '"') q += '\\';
    q += c;
  }
  return q + '"';
}

// FOLDER/FILE as an --output filename pattern, FILE's own %A, %a, %j kept: each % of the folder
// doubled, since Slurm expands %j, %u, %x, ... in the whole path and reads %% as one %
std::string output_pattern(const std::string& folder, const std::string& file) {
  std::string p;
  for (char c : folder) {
    p += c;
    if (c == '%') p += '%';
  }
  return p + "/" + file;
}

const char* const kArrayOutput = "slurm-%A_%a.out";
const char* const kCollectOutput = "slurm-%j-collect.out";

std::string header(const SlurmSettings& s, const std::string& what) {
  std::string h = "#!/bin/sh\n# " + what + " (written by beltsim sweep --slurm)\n";
  h += "#SBATCH --job-name=" + sbatch_word("beltsim-" + s.name) + "\n";
  h += "#SBATCH --chdir=" + sbatch_word(s.workdir) + "\n";
  h += "#SBATCH --ntasks=1\n#SBATCH --cpus-per-task=1\n";
  if (s.partition) h += "#SBATCH --partition=" + sbatch_word(*s.partition) + "\n";
  if (s.time) h += "#SBATCH --time=" + sbatch_word(*s.time) + "\n";
  return h;
}

// s as an error shows it on one line: each control character as \n, \r, \t or \xNN
std::string shown(const std::string& s) {
  static const char* const hex = "0123456789abcdef";
  std::string r;
  for (char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\n')
      r += "\\n";
    else if (c == '\r')
      r += "\\r";
    else if (c == '\t')
      r += "\\t";
    else if (u < 0x20 || u == 0x7f)
      r += std::string("\\x") + hex[u >> 4] + hex[u & 15];
    else
      r += c;
  }
  return r;
}

// throws std::invalid_argument naming `what` and its value when the value has a control
// character: a line break would end the script's line and run the rest as a command, and no
// other has a meaning in a path or a name that a batch script should carry
void check_text(const std::string& what, const std::string& value) {
  for (char c : value) {
    const auto u = static_cast<unsigned char>(c);
    if (u < 0x20 || u == 0x7f)
      throw std::invalid_argument(what + " '" + shown(value) + "' has a control character (" +
                                  shown(std::string(1, c)) + "), which a Slurm batch script cannot hold safely");
  }
}

// throws std::invalid_argument when `value` is longer than slurmctld takes
void check_length(const std::string& what, const std::string& value, std::size_t max) {
  if (value.size() > max)
    throw std::invalid_argument(what + " is " + std::to_string(value.size()) + " bytes long; Slurm takes at most " +
                                std::to_string(max) + " ('" + shown(value.substr(0, 60)) + "...')");
}

// the seconds of a time in one of Slurm's formats (sbatch(1) --time: M, M:S, H:M:S, D-H, D-H:M,
// D-H:M:S, each a number of digits); -1 when it is in none, or longer than Slurm counts (2^31 - 1 s)
long long slurm_seconds(const std::string& t) {
  const std::size_t dash = t.find('-');
  const std::string days = dash == std::string::npos ? "0" : t.substr(0, dash);
  const std::string rest = dash == std::string::npos ? t : t.substr(dash + 1);
  std::vector<std::string> parts;
  for (std::size_t from = 0;;) {
    const std::size_t colon = rest.find(':', from);
    parts.push_back(rest.substr(from, colon == std::string::npos ? std::string::npos : colon - from));
    if (colon == std::string::npos) break;
    from = colon + 1;
  }
  const auto number = [](const std::string& d) -> long long {
    if (d.empty() || d.size() > 9 || d.find_first_not_of("0123456789") != std::string::npos) return -1;
    return std::stoll(d);
  };
  std::vector<long long> n;  // the numbers after the days, in the order written
  for (const std::string& p : parts) n.push_back(number(p));
  const long long d = number(days);
  if (parts.size() > 3 || d < 0 || std::find(n.begin(), n.end(), -1LL) != n.end()) return -1;
  n.resize(3, 0);
  // D-H, D-H:M, D-H:M:S and H:M:S name the hours first; M and M:S the minutes
  long long h = n[0], m = n[1], s = n[2];
  if (dash == std::string::npos && parts.size() < 3) h = 0, m = n[0], s = n[1];
  const long long total = d * 86400 + h * 3600 + m * 60 + s;
  return total > 2147483647LL ? -1 : total;
}

// Slurm partition names separated by commas, each of letters, digits, _, - and ., none empty or
// starting with - (sbatch would read it as an option)
bool partition_list(const std::string& p) {
  for (std::size_t from = 0;;) {
    const std::size_t comma = p.find(',', from);
    const std::string name = p.substr(from, comma == std::string::npos ? std::string::npos : comma - from);
    if (name.empty() || name[0] == '-' ||
        name.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-.") !=
            std::string::npos)
      return false;
    if (comma == std::string::npos) return true;
    from = comma + 1;
  }
}

// text as a message quotes what a program printed: its first 200 bytes on one line, control
// characters shown as \n, \xNN, ...
std::string printed(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  return text.size() > 200 ? shown(text.substr(0, 200)) + "..." : shown(text);
}

// the standard output of args, run within limits; throws with its standard error when it fails,
// and saying which limit it passed
std::string output_of(const std::vector<std::string>& args, const CaptureLimits& limits) {
  const Captured r = run_capture(args, limits);
  std::string c;
  for (const std::string& x : args) {
    if (!c.empty()) c += ' ';
    c += shell_quoted(x);
  }
  if (r.timed_out)
    throw std::runtime_error(c + " gave no answer within " + number_text(limits.seconds) +
                             " s and was stopped (is slurmctld reachable?)" +
                             (r.err.empty() ? std::string() : ": " + printed(r.err)));
  if (r.overflowed)
    throw std::runtime_error(c + " printed more than " + std::to_string(limits.max_bytes) +
                             " bytes and was stopped; one job id expected: " + printed(r.out.empty() ? r.err : r.out));
  if (r.status != 0) throw std::runtime_error(c + " failed" + (r.err.empty() ? std::string() : ": " + printed(r.err)));
  return r.out;
}

// the job id sbatch --parsable printed: "ID" or "ID;CLUSTER" on one line, the id of 1 to 10
// digits (Slurm's are 32-bit); throws naming what it printed otherwise
std::string job_id(const std::string& out) {
  std::string line = out;
  if (!line.empty() && line.back() == '\n') line.pop_back();
  const std::size_t semicolon = line.find(';');
  const std::string id = line.substr(0, semicolon);
  const bool cluster_ok =
      semicolon == std::string::npos ||
      (semicolon + 1 < line.size() && line.find_first_of(";\n\r", semicolon + 1) == std::string::npos);
  if (id.empty() || id.size() > 10 || id.find_first_not_of("0123456789") != std::string::npos || !cluster_ok)
    throw std::runtime_error("sbatch --parsable printed no job id (ID or ID;CLUSTER on one line expected): '" +
                             printed(out) + "'");
  return id;
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

std::string shell_quoted(const std::string& s) {
  if (!s.empty() && s.find_first_not_of(kPlain) == std::string::npos) return s;
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

void check_slurm_settings(const SlurmSettings& s) {
  if (s.partition && !partition_list(*s.partition))
    throw std::invalid_argument(
        "--partition: Slurm partition names (letters, digits, _, - and ., not starting with -) separated by "
        "commas expected, got '" +
        shown(*s.partition) + "'");
  if (s.time) {
    const long long seconds = slurm_seconds(*s.time);
    if (seconds == 0 || *s.time == "-1")
      throw std::invalid_argument("--time: a limit above 0 expected, got '" + *s.time +
                                  "' (Slurm reads 0 and -1 as no limit; leave --time out for the partition's own)");
    if (seconds < 0)
      throw std::invalid_argument(
          "--time: Slurm's time format (minutes, M:S, H:M:S, D-H, D-H:M or D-H:M:S, up to 24855 days) expected, "
          "got '" +
          shown(*s.time) + "'");
  }
  if (s.max_parallel < 0) throw std::invalid_argument("--max-parallel must be >= 1");
  check_text("the sweep's folder", s.dir);
  check_text("the job's name (the sweep file's name)", s.name);
  check_text("the jobs' working folder (the current folder)", s.workdir);
  check_text("beltsim's path", s.program);
  for (const auto* args : {&s.point_args, &s.collect_args})
    for (const std::string& a : *args) check_text("the points' command's argument", a);
  if (s.dir.find('\\') != std::string::npos)
    throw std::invalid_argument("the sweep's folder '" + s.dir +
                                "' has a backslash: Slurm drops each one from an --output path (and expands "
                                "nothing in it then), so no job could write its output there; choose another");
  check_length("the jobs' --output path in the sweep's folder", output_pattern(s.dir, kCollectOutput), kSlurmPathMax);
  check_length("the jobs' working folder (the current folder)", s.workdir, kSlurmPathMax);
  check_length("the job's name", "beltsim-" + s.name, kSlurmNameMax);
}

SlurmJobs write_slurm_jobs(const std::vector<Point>& points, const SlurmSettings& s) {
  check_slurm_settings(s);
  std::vector<int> todo;
  Definition now = s.definition;
  const Results results = current_results(s.dir, points, now);
  for (std::size_t k = 0; k < points.size(); ++k)
    if (s.rerun || !results[k] || !results[k]->ok()) todo.push_back(points[k].index);
  SlurmJobs jobs;
  jobs.array = index_ranges(todo);
  jobs.reasons = rerun_reasons(results);
  // nothing to run: an array without --array would be one task with no point to run
  if (todo.empty()) return jobs;
  const OutputDir top(s.dir);
  std::string a = header(s, "sweep " + s.name + ": " + std::to_string(todo.size()) + " of " +
                                std::to_string(points.size()) + " points, one array task each");
  a += "#SBATCH --array=" + jobs.array;
  if (s.max_parallel > 0) a += '%' + std::to_string(s.max_parallel);
  a += '\n';
  a += "#SBATCH --output=" + sbatch_word(output_pattern(s.dir, kArrayOutput)) + "\n";
  std::vector<std::string> point = s.point_args;
  point.push_back("--point");
  a += "exec " + command(s.program, point) + " \"$SLURM_ARRAY_TASK_ID\"\n";
  write_file_whole(top, "sweep.sbatch", a);
  std::string c = header(s, "sweep " + s.name + ": summary.csv from the points' results, after the array");
  c += "#SBATCH --output=" + sbatch_word(output_pattern(s.dir, kCollectOutput)) + "\n";
  c += "exec " + command(s.program, s.collect_args) + "\n";
  write_file_whole(top, "collect.sbatch", c);
  jobs.array_script = top.file("sweep.sbatch");
  jobs.collect_script = top.file("collect.sbatch");
  return jobs;
}

std::pair<std::string, std::string> submit_slurm_jobs(const SlurmJobs& jobs, const CaptureLimits& limits) {
  const std::string array = job_id(output_of({"sbatch", "--parsable", jobs.array_script}, limits));
  const std::string dependency = "--dependency=afterany:" + array;
  try {
    return {array, job_id(output_of({"sbatch", "--parsable", dependency, jobs.collect_script}, limits))};
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string(e.what()) + "; the job array " + array +
                             " is submitted: submit the summary's job after it with sbatch " + dependency + " " +
                             shell_quoted(jobs.collect_script));
  }
}

}  // namespace beltsim::sweep
