// The scratch folder of scratch.hpp: a gtest listener, appended before main, removes it at the
// end of the test program (unless BELTSIM_KEEP is set), in the process that made it only: a
// forked child that ends the program's tests leaves its parent's folder alone.
#include "support/scratch.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <system_error>

namespace beltsim::test {

namespace fs = std::filesystem;

namespace {

std::mutex m;
fs::path folder;  // empty until the first scratch_dir()
pid_t maker = 0;  // the process that made it

class Remover : public ::testing::EmptyTestEventListener {
  void OnTestProgramEnd(const ::testing::UnitTest& u) override {
    std::lock_guard<std::mutex> lock(m);
    if (folder.empty() || maker != ::getpid()) return;
    if (const char* keep = std::getenv("BELTSIM_KEEP"); keep && *keep) {
      std::fprintf(stderr, "the test's files are kept in %s (BELTSIM_KEEP)\n", folder.c_str());
      return;
    }
    std::error_code ec;
    fs::remove_all(folder, ec);
    if (!u.Passed())
      std::fprintf(stderr, "the test's files in %s are removed: BELTSIM_KEEP=1 keeps them\n", folder.c_str());
  }
};

const bool installed = [] {
  ::testing::UnitTest::GetInstance()->listeners().Append(new Remover);
  return true;
}();

}  // namespace

fs::path scratch_dir(const std::string& prefix) {
  std::lock_guard<std::mutex> lock(m);
  if (folder.empty()) {
    folder = fs::temp_directory_path() / (prefix + "_" + std::to_string(::getpid()));
    maker = ::getpid();
  }
  fs::create_directories(folder);
  return folder;
}

}  // namespace beltsim::test
