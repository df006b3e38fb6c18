// The Slurm batch scripts of a sweep (src/sweep/slurm.hpp) for folders and files whose names hold
// what the shell or sbatch treat specially: the exact text of both scripts, `sh -n` on each, the
// commands as sh runs them and the #SBATCH lines as sbatch reads them (each value back exactly),
// and what cannot be written safely (control characters, a backslash in the output folder, a
// time or a partition Slurm would not take) refused before anything is written.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cctype>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "support/files.hpp"
#include "support/scratch.hpp"
#include "sweep/capture.hpp"
#include "sweep/slurm.hpp"

namespace beltsim::sweep {
namespace {

namespace fs = std::filesystem;

// a fresh folder for one test
std::string fresh(const std::string& name) {
  const fs::path d = test::scratch_dir("beltsim_slurm_script_test") / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d.string();
}

// every "ROOT" in text replaced by root
std::string rooted(std::string text, const std::string& root) {
  for (std::size_t at = text.find("ROOT"); at != std::string::npos; at = text.find("ROOT", at + root.size()))
    text.replace(at, 4, root);
  return text;
}

// a program that prints each of its arguments followed by a NUL, in a folder whose name needs quoting
std::string arguments_printer(const std::string& root) {
  fs::create_directories(root + "/bin dir");
  const std::string p = root + "/bin dir/print'args";
  std::ofstream(p) << "#!/bin/sh\nfor a do printf '%s\\0' \"$a\"; done\n";
  ::chmod(p.c_str(), 0755);
  return p;
}

// the settings of a sweep file ROOT/it's #1.lua into the folder ROOT/<folder>, from ROOT/work d
SlurmSettings settings(const std::string& root, const std::string& folder) {
  SlurmSettings s;
  s.program = root + "/bin dir/print'args";
  s.dir = root + "/" + folder;
  s.point_args = {"sweep", root + "/it's #1.lua", "--out", s.dir, "--set", "mu=0.3,$x"};
  s.collect_args = s.point_args;
  s.collect_args.push_back("--collect");
  s.name = "it's #1";
  s.workdir = root + "/work d";
  s.partition = "gpu";
  s.time = "1:00:00";
  s.max_parallel = 2;
  return s;
}

std::vector<Point> three_points() {
  return grid_points(Grid{{"mu"}, {{Value(0.1), Value(0.2), Value(0.3)}}});
}

// the arguments sbatch takes from a script's #SBATCH lines, by the rules of sbatch(1) and its
// reader: the lines that start with "#SBATCH", up to the first line that is not a comment; in each,
// words split at white space, '...' and "..." group, a backslash takes the next character as it
// is (between quotes too), an unquoted # ends the line
std::vector<std::string> sbatch_arguments(const std::string& script) {
  std::vector<std::string> args;
  std::istringstream in(script);
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("#SBATCH", 0) != 0) {
      const std::size_t first = line.find_first_not_of(" \t\r\f\v");
      if (first != std::string::npos && line[first] != '#') break;
      continue;
    }
    std::string word;
    bool in_word = false;
    char quote = 0;
    for (std::size_t i = 7; i < line.size(); ++i) {
      const char c = line[i];
      if (c == '\\' && i + 1 < line.size()) {
        word += line[++i];
        in_word = true;
      } else if (quote != 0) {
        if (c == quote)
          quote = 0;
        else
          word += c;
      } else if (c == '\'' || c == '"') {
        quote = c;
        in_word = true;
      } else if (c == '#') {
        break;
      } else if (std::isspace(static_cast<unsigned char>(c))) {
        if (in_word) args.push_back(word);
        word.clear();
        in_word = false;
      } else {
        word += c;
        in_word = true;
      }
    }
    EXPECT_EQ(quote, 0) << "an unmatched quote (sbatch stops): " << line;
    if (in_word) args.push_back(word);
  }
  return args;
}

// an --output pattern as Slurm opens it for task 7 of array job 100 (sbatch(1), "filename pattern"):
// %% a %, %A the array's job id, %a the task's index, %j the job's id (101)
std::string expanded(const std::string& pattern) {
  EXPECT_EQ(pattern.find('\\'), std::string::npos) << "a backslash turns Slurm's expansion off: " << pattern;
  std::string s;
  for (std::size_t i = 0; i < pattern.size(); ++i) {
    if (pattern[i] != '%' || i + 1 == pattern.size()) {
      s += pattern[i];
      continue;
    }
    const char c = pattern[++i];
    if (c == '%')
      s += '%';
    else if (c == 'A')
      s += "100";
    else if (c == 'a')
      s += "7";
    else if (c == 'j')
      s += "101";
    else
      ADD_FAILURE() << "Slurm would expand %" << c << " in " << pattern;
  }
  return s;
}

// the arguments the script's command gets when sh runs it as task 7 (its program prints them)
std::vector<std::string> run_arguments(const std::string& script) {
  const Captured c = run_capture({"env", "SLURM_ARRAY_TASK_ID=7", "sh", script});
  EXPECT_EQ(c.status, 0) << c.err;
  std::vector<std::string> args;
  for (std::size_t from = 0; from < c.out.size();) {
    const std::size_t end = c.out.find('\0', from);
    args.push_back(c.out.substr(from, end - from));
    from = end + 1;
  }
  return args;
}

// a folder with a space, ', #, % and $ in its name: both scripts as they are written
TEST(SweepSlurm, BothScriptsForAFolderWithCharactersTheShellAndSlurmTreatSpecially) {
  const std::string root = fresh("exact");
  const SlurmSettings s = settings(root, "mu %x 'q' #1 $HOME");
  const SlurmJobs j = write_slurm_jobs(three_points(), s);
  EXPECT_EQ(j.array, "0-2");
  EXPECT_EQ(j.array_script, s.dir + "/sweep.sbatch");
  EXPECT_EQ(j.collect_script, s.dir + "/collect.sbatch");
  EXPECT_EQ(test::slurp(j.array_script), rooted(R"(#!/bin/sh
# sweep it's #1: 3 of 3 points, one array task each (written by beltsim sweep --slurm)
#SBATCH --job-name="beltsim-it's #1"
#SBATCH --chdir="ROOT/work d"
#SBATCH --ntasks=1
#SBATCH --cpus-per-task=1
#SBATCH --partition=gpu
#SBATCH --time=1:00:00
#SBATCH --array=0-2%2
#SBATCH --output="ROOT/mu %%x 'q' #1 $HOME/slurm-%A_%a.out"
exec 'ROOT/bin dir/print'\''args' sweep 'ROOT/it'\''s #1.lua' --out 'ROOT/mu %x '\''q'\'' #1 $HOME' --set 'mu=0.3,$x' --point "$SLURM_ARRAY_TASK_ID"
)",
                                                root));
  EXPECT_EQ(test::slurp(j.collect_script), rooted(R"(#!/bin/sh
# sweep it's #1: summary.csv from the points' results, after the array (written by beltsim sweep --slurm)
#SBATCH --job-name="beltsim-it's #1"
#SBATCH --chdir="ROOT/work d"
#SBATCH --ntasks=1
#SBATCH --cpus-per-task=1
#SBATCH --partition=gpu
#SBATCH --time=1:00:00
#SBATCH --output="ROOT/mu %%x 'q' #1 $HOME/slurm-%j-collect.out"
exec 'ROOT/bin dir/print'\''args' sweep 'ROOT/it'\''s #1.lua' --out 'ROOT/mu %x '\''q'\'' #1 $HOME' --set 'mu=0.3,$x' --collect
)",
                                                  root));
  for (const std::string& script : {j.array_script, j.collect_script}) {
    const Captured c = run_capture({"sh", "-n", script});
    EXPECT_EQ(c.status, 0) << script << ": " << c.err;
  }
}

// names with " and \ too: sh gives the command each argument exactly, sbatch reads each value
// exactly, and the task's output lands in the folder
TEST(SweepSlurm, ShAndSbatchReadBackEveryValue) {
  const std::string root = fresh("read back");
  for (const std::string folder : {"mu %x 'q' #1 $HOME", "a \"b\" `c` %%j %5a ;&|<>(){}*?[]~!", "%", "-x"}) {
    SlurmSettings s = settings(root, folder);
    s.program = arguments_printer(root);
    s.name = "\"it\" \\ #1 %x";
    s.workdir = root + "/a \\ \"b\" 'c' #d";
    s.point_args.push_back("two\\ words \"q\" 'q' $(x) `y`");
    s.collect_args = s.point_args;
    s.collect_args.push_back("--collect");
    s.partition.reset();
    s.time.reset();
    s.max_parallel = 0;
    const SlurmJobs j = write_slurm_jobs(three_points(), s);
    std::vector<std::string> point = s.point_args;
    point.insert(point.end(), {"--point", "7"});
    EXPECT_EQ(run_arguments(j.array_script), point) << folder;
    EXPECT_EQ(run_arguments(j.collect_script), s.collect_args) << folder;
    std::vector<std::string> a = sbatch_arguments(test::slurp(j.array_script));
    ASSERT_EQ(a.size(), 6u) << test::slurp(j.array_script);
    EXPECT_EQ(a[0], "--job-name=beltsim-" + s.name);
    EXPECT_EQ(a[1], "--chdir=" + s.workdir);
    EXPECT_EQ(a[4], "--array=0-2");
    ASSERT_EQ(a[5].rfind("--output=", 0), 0u) << a[5];
    EXPECT_EQ(expanded(a[5].substr(9)), s.dir + "/slurm-100_7.out");
    const std::vector<std::string> c = sbatch_arguments(test::slurp(j.collect_script));
    ASSERT_EQ(c.size(), 5u) << test::slurp(j.collect_script);
    ASSERT_EQ(c[4].rfind("--output=", 0), 0u) << c[4];
    EXPECT_EQ(expanded(c[4].substr(9)), s.dir + "/slurm-101-collect.out");
  }
}

// the error check_slurm_settings throws for s ("" when none)
std::string refusal(const SlurmSettings& s) {
  try {
    check_slurm_settings(s);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

// a line break (or any control character) in any value would end the script's line and run the
// rest as a command: refused with the reason and the value shown, before anything is written
TEST(SweepSlurm, ControlCharactersAreRefusedBeforeAnythingIsWritten) {
  const std::string root = fresh("refused");
  const auto refused = [&](SlurmSettings s, const std::string& shown) {
    const std::string e = refusal(s);
    EXPECT_NE(e.find("control character"), std::string::npos) << e;
    EXPECT_NE(e.find(shown), std::string::npos) << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << "the error is one line: " << e;
    EXPECT_THROW(write_slurm_jobs(three_points(), s), std::invalid_argument);
    EXPECT_FALSE(fs::exists(s.dir + "/sweep.sbatch")) << s.dir;
    EXPECT_FALSE(fs::exists(s.dir + "/collect.sbatch")) << s.dir;
  };
  fs::create_directories(root + "/a\nb");
  refused(settings(root, "a\nb"), "a\\nb");
  fs::create_directories(root + "/a\r\nb");
  refused(settings(root, "a\r\nb"), "a\\r\\nb");
  SlurmSettings s = settings(root, "plain");
  fs::create_directories(s.dir);
  s.point_args[1] = root + "/x\n#SBATCH --x\ntouch pwned/it.lua";
  refused(s, "x\\n#SBATCH --x\\ntouch pwned/it.lua");
  s = settings(root, "plain");
  s.name = "it\rx";
  refused(s, "it\\rx");
  s = settings(root, "plain");
  s.workdir = root + "/w\td";
  refused(s, "w\\td");
  s = settings(root, "plain");
  s.program = root + "/bin\x7f";
  refused(s, "bin\\x7f");
  s = settings(root, "plain");
  s.collect_args.push_back("\x1b[2J");
  refused(s, "\\x1b[2J");
}

// Slurm drops every backslash of an --output path and then expands nothing, so no pattern names a
// folder with one; sbatch refuses a path longer than PATH_MAX (4096)
TEST(SweepSlurm, AnOutputFolderSlurmCannotNameIsRefused) {
  const std::string root = fresh("backslash");
  std::string e = refusal(settings(root, "a\\b"));
  EXPECT_NE(e.find("backslash"), std::string::npos) << e;
  EXPECT_NE(e.find(root + "/a\\b"), std::string::npos) << e;
  e = refusal(settings(root, std::string(4100, 'd')));
  EXPECT_NE(e.find("4096"), std::string::npos) << e;
  EXPECT_EQ(refusal(settings(root, std::string(4000, 'd'))), "");
}

TEST(SweepSlurm, TimesAndPartitionsSlurmWouldNotTakeAreRefused) {
  SlurmSettings s = settings("/r", "d");
  for (const char* t : {"30", "30:00", "1:00:00", "1-0", "1-12:00", "1-00:00:00", "0:30", "90"}) {
    s.time = t;
    EXPECT_EQ(refusal(s), "") << t;
  }
  for (const char* t : {"-1",    "0",   "0:00",        "0-0:0:0",   "",   "-",  "1-",  "-5",
                        "1-2-3", "::",  "1:2:3:4",     "1-1:2:3:4", "1:", ":1", "abc", "1h",
                        " 30",   "30 ", "99999999999", "30000-0"}) {
    s.time = t;
    const std::string e = refusal(s);
    EXPECT_NE(e.find("--time"), std::string::npos) << t << ": " << e;
    EXPECT_NE(e.find("'" + std::string(t) + "'"), std::string::npos) << t << ": " << e;
  }
  s.time.reset();
  for (const char* p : {"gpu", "cpu-long,gpu", "a.b_c"}) {
    s.partition = p;
    EXPECT_EQ(refusal(s), "") << p;
  }
  for (const char* p : {"-x", "gpu,-x", "", ",", "a,,b", "a,", "a b", "a;b", "a\nb", "--array=0"}) {
    s.partition = p;
    const std::string e = refusal(s);
    EXPECT_NE(e.find("--partition"), std::string::npos) << p << ": " << e;
  }
}

// sbatch's folder put first on PATH for one test (the PATH before restored at its end)
class FakeSbatch {
 public:
  // an sbatch that runs `body` (sh), its arguments logged one a line in ROOT/args
  FakeSbatch(const std::string& root, const std::string& body) : old_(std::getenv("PATH")) {
    fs::create_directories(root + "/bin");
    const std::string p = root + "/bin/sbatch";
    std::ofstream(p) << "#!/bin/sh\nprintf '%s\\n' \"$@\" >> '" << root << "/args'\n" << body << "\n";
    ::chmod(p.c_str(), 0755);
    ::setenv("PATH", (root + "/bin:" + old_).c_str(), 1);
  }
  ~FakeSbatch() { ::setenv("PATH", old_.c_str(), 1); }
  FakeSbatch(const FakeSbatch&) = delete;
  FakeSbatch& operator=(const FakeSbatch&) = delete;

 private:
  std::string old_;
};

// the error submit_slurm_jobs throws with this sbatch ("" when none), and the job ids otherwise
std::string submit_error(const std::string& root, const std::string& body, std::pair<std::string, std::string>* ids) {
  const FakeSbatch sbatch(root, body);
  SlurmJobs j;
  j.array_script = root + "/sweep.sbatch";
  j.collect_script = root + "/collect.sbatch";
  j.array = "0-2";
  try {
    const auto r = submit_slurm_jobs(j, CaptureLimits{1.0, 4096});
    if (ids) *ids = r;
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

// sbatch --parsable prints "ID" or "ID;CLUSTER" on one line: that is read, and anything else, an
// sbatch that does not answer in time or prints past the bound, is an error that says so
TEST(SweepSlurm, SubmitReadsOneJobIdAndBoundsSbatch) {
  const std::string root = fresh("submit");
  std::pair<std::string, std::string> ids;
  EXPECT_EQ(
      submit_error(root,
                   "if [ -e " + root + "/first ]; then echo 13; else touch " + root + "/first; echo '12;cluster'; fi",
                   &ids),
      "");
  EXPECT_EQ(ids, std::make_pair(std::string("12"), std::string("13")));
  EXPECT_EQ(
      test::slurp(root + "/args"),
      "--parsable\n" + root + "/sweep.sbatch\n--parsable\n--dependency=afterany:12\n" + root + "/collect.sbatch\n");
  const auto t0 = std::chrono::steady_clock::now();
  std::string e = submit_error(root, "sleep 60", nullptr);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), 30.0);
  EXPECT_NE(e.find("no answer within 1 s"), std::string::npos) << e;
  e = submit_error(root, "head -c 50000000 /dev/zero | tr '\\0' 7", nullptr);
  EXPECT_NE(e.find("more than 4096 bytes"), std::string::npos) << e;
  EXPECT_LT(e.size(), 1000u) << e;
  for (const char* out : {"Submitted batch job 12", "12\n13", "", "12;", " 12", "12x", "123456789012345678901"}) {
    e = submit_error(root, std::string("printf '") + out + "'", nullptr);
    EXPECT_NE(e.find("no job id"), std::string::npos) << out << ": " << e;
    EXPECT_EQ(e.find('\n'), std::string::npos) << "one line: " << e;
  }
  e = submit_error(root, "echo 'sbatch: error: invalid partition' >&2; exit 1", nullptr);
  EXPECT_NE(e.find("failed: sbatch: error: invalid partition"), std::string::npos) << e;
  // the array submitted, the collector refused: the array's id is told, and how to submit the rest
  e = submit_error(root, "if [ -e " + root + "/once ]; then exit 1; else touch " + root + "/once; echo 77; fi",
                   nullptr);
  EXPECT_NE(e.find("job array 77 is submitted"), std::string::npos) << e;
  EXPECT_NE(e.find("sbatch --dependency=afterany:77 " + root + "/collect.sbatch"), std::string::npos) << e;
}

}  // namespace
}  // namespace beltsim::sweep
