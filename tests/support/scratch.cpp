// The scratch folder of scratch.hpp: a gtest listener, appended before main, removes it at the
// end of the test program unless a test failed.
#include "support/scratch.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <mutex>
#include <system_error>

namespace beltsim::test {

namespace fs = std::filesystem;

namespace {

std::mutex m;
fs::path folder;  // empty until the first scratch_dir()

class Remover : public ::testing::EmptyTestEventListener {
  void OnTestProgramEnd(const ::testing::UnitTest& u) override {
    std::lock_guard<std::mutex> lock(m);
    if (folder.empty()) return;
    if (!u.Passed()) {
      std::fprintf(stderr, "the test's files are kept in %s\n", folder.c_str());
      return;
    }
    std::error_code ec;
    fs::remove_all(folder, ec);
  }
};

const bool installed = [] {
  ::testing::UnitTest::GetInstance()->listeners().Append(new Remover);
  return true;
}();

}  // namespace

fs::path scratch_dir(const std::string& prefix) {
  std::lock_guard<std::mutex> lock(m);
  if (folder.empty()) folder = fs::temp_directory_path() / (prefix + "_" + std::to_string(::getpid()));
  fs::create_directories(folder);
  return folder;
}

}  // namespace beltsim::test
