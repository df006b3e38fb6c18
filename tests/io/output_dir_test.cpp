// Outputs never through a link (io/output_dir.hpp): every way the program opens an output (a
// file emptied or continued, cut back, written whole, a CSV, a subfolder, the folder itself)
// refuses a symbolic link planted under the output's name, leaves the link's target as it was and
// names the file; a second hard link, a FIFO and a second writer of a folder are refused too; a
// whole-file write that fails leaves neither a half file nor a NAME.part, and every failure is
// recorded for the exit status.
#include "io/output_dir.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include "io/csv_writer.hpp"
#include "io/row_file.hpp"
#include "support/file_size_limit.hpp"
#include "support/files.hpp"
#include "support/scratch.hpp"

namespace beltsim {
namespace {

using test::slurp;
using test::spit;
using test::what_of;

namespace fs = std::filesystem;

fs::path fresh_dir(const std::string& name) {
  const fs::path d = beltsim::test::scratch_dir("beltsim_output_dir_test") / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

constexpr const char* kSecret = "the user's own file\n";

// a folder holding NAME -> a file outside it (the target), as a scenario package could ship it
struct Planted {
  fs::path dir, target;
  explicit Planted(const std::string& test, const std::string& name) {
    dir = fresh_dir(test) / "out";
    fs::create_directories(dir);
    target = dir.parent_path() / "bashrc";
    spit(target, kSecret);
    fs::create_symlink(target, dir / name);
  }
  // the error names the file and says why; the target is as it was; the link is still a link
  void expect_refused(const std::string& error, const std::string& name) const {
    EXPECT_EQ(error, "cannot write " + (dir / name).string() +
                         ": it is a symbolic link (beltsim never writes through a link)");
    EXPECT_EQ(slurp(target), kSecret);
    EXPECT_TRUE(fs::is_symlink(dir / name));
  }
};

TEST(OutputDir, EveryWayOfWritingRefusesAPlantedLink) {
  {
    const Planted p("open_empty", "events.csv");
    const OutputDir d(p.dir.string());
    p.expect_refused(what_of([&] { d.open_file("events.csv", false); }), "events.csv");
  }
  {
    const Planted p("open_append", "events.csv");
    const OutputDir d(p.dir.string());
    p.expect_refused(what_of([&] { d.open_file("events.csv", true); }), "events.csv");
  }
  {
    const Planted p("truncate", "timeseries.csv");
    const OutputDir d(p.dir.string());
    // the size is the link's business, never the target's: "missing"
    EXPECT_NE(what_of([&] { d.truncate("timeseries.csv", 0); }), "");
    EXPECT_EQ(slurp(p.target), kSecret);
  }
  {
    const Planted p("row_file", "snapshots.csv");
    p.expect_refused(what_of([&] { RowFile((p.dir / "snapshots.csv").string(), false); }), "snapshots.csv");
  }
  {
    const Planted p("csv", "timeseries.csv");
    const OutputDir d(p.dir.string());
    p.expect_refused(what_of([&] { CsvWriter(d, "timeseries.csv", {"t", "x"}, false); }), "timeseries.csv");
  }
  {
    const Planted p("whole", "parameters.csv");
    p.expect_refused(what_of([&] { write_file_whole((p.dir / "parameters.csv").string(), "a\n"); }), "parameters.csv");
  }
  {
    // a dangling link: O_CREAT would make its target
    const fs::path dir = fresh_dir("dangling");
    const fs::path target = dir / "made_elsewhere";
    fs::create_symlink(target, dir / "events.csv");
    EXPECT_NE(what_of([&] { RowFile((dir / "events.csv").string(), false); }).find("symbolic link"), std::string::npos);
    EXPECT_FALSE(fs::exists(target));
  }
}

TEST(OutputDir, AFolderThatIsALinkIsRefused) {
  const fs::path base = fresh_dir("folder_link");
  fs::create_directories(base / "elsewhere");
  fs::create_symlink(base / "elsewhere", base / "frames");
  const std::string e = what_of([&] { OutputDir((base / "frames").string()); });
  EXPECT_EQ(e, "cannot write " + (base / "frames").string() +
                   ": it is a symbolic link (beltsim never writes through a link)");
  const OutputDir d(base.string());
  EXPECT_NE(what_of([&] { OutputDir(d, "frames"); }).find("symbolic link"), std::string::npos);
  EXPECT_TRUE(fs::is_empty(base / "elsewhere"));
  // missing folders are made, each opened as it is made
  const OutputDir deep((base / "a" / "b" / "c").string());
  RowFile(deep, "x.csv", false).write("1\n");
  EXPECT_EQ(slurp(base / "a" / "b" / "c" / "x.csv"), "1\n");
}

TEST(OutputDir, HardLinksAndFifosAreRefusedUntouched) {
  const fs::path dir = fresh_dir("hard");
  spit(dir / "bashrc", kSecret);
  fs::create_hard_link(dir / "bashrc", dir / "events.csv");
  const OutputDir d(dir.string());
  EXPECT_EQ(
      what_of([&] { d.open_file("events.csv", false); }),
      "cannot write " + (dir / "events.csv").string() + ": it has 2 hard links (beltsim writes only files of its own)");
  EXPECT_EQ(slurp(dir / "bashrc"), kSecret);
  // a FIFO would block the open until a reader came: refused at once
  ASSERT_EQ(::mkfifo((dir / "timeseries.csv").c_str(), 0600), 0);
  EXPECT_EQ(what_of([&] { d.open_file("timeseries.csv", false); }),
            "cannot write " + (dir / "timeseries.csv").string() + ": not a regular file");
}

TEST(OutputDir, OneWriterPerFolder) {
  const fs::path dir = fresh_dir("lock");
  {
    OutputDir a(dir.string());
    a.lock();
    OutputDir b(dir.string());
    const std::string e = what_of([&] { b.lock(); });
    EXPECT_EQ(e, "the output folder " + dir.string() +
                     " is in use by another simulation of this beltsim: two simulations writing one folder would "
                     "mix their rows; give this one a folder of its own (out = ...) or close the other first");
  }
  // released with its holder
  OutputDir c(dir.string());
  EXPECT_EQ(what_of([&] { c.lock(); }), "");
  // another process: named by its id
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    OutputDir d(dir.string());
    const std::string e = what_of([&] { d.lock(); });
    _exit(e.find("another beltsim (process " + std::to_string(::getppid()) + ")") != std::string::npos ? 0 : 1);
  }
  int status = 0;
  ::waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
}

// a whole-file write that cannot finish (a file-size limit, as a full disk) leaves the old file
// and nothing else: no NAME.part, no half file; the error names the file and is recorded
TEST(OutputDir, AFailedWholeWriteLeavesTheOldFileAndNoPart) {
  const fs::path dir = fresh_dir("whole_fails");
  spit(dir / "run.ckpt", "old checkpoint\n");
  const int status = test::exit_status_under_file_size_limit(4096, [&] {
    const std::string e = what_of([&] { write_file_whole((dir / "run.ckpt").string(), std::string(10000, 'x')); });
    const std::string want = "cannot write " + (dir / "run.ckpt").string() + ": " + std::strerror(EFBIG);
    const auto failures = output_failures();
    return e == want && !failures.empty() && failures.back() == want ? 0 : 1;
  });
  EXPECT_EQ(status, 0) << "not the expected error, or not recorded";
  EXPECT_EQ(slurp(dir / "run.ckpt"), "old checkpoint\n");
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  EXPECT_EQ(names, std::vector<std::string>{"run.ckpt"});
}

TEST(OutputDir, AWholeWriteReplacesAndPlantsNothing) {
  const fs::path dir = fresh_dir("whole_ok");
  spit(dir / "session.lua", "old\n");
  spit(dir / "session.lua.part", "stale\n");  // left by a killed older beltsim
  write_file_whole((dir / "session.lua").string(), "new\n");
  EXPECT_EQ(slurp(dir / "session.lua"), "new\n");
  EXPECT_FALSE(fs::exists(dir / "session.lua.part"));
}

}  // namespace
}  // namespace beltsim
