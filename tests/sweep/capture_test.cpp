// A program's output and error captured (src/sweep/capture.hpp), through sh.
#include "sweep/capture.hpp"

#include <gtest/gtest.h>

#include <string>

namespace beltsim::sweep {
namespace {

// 200 kB on stderr before a word on stdout: more than a pipe holds (64 kB), so a reader that waits
// for stdout's end first never sees it while the program waits for room on stderr
TEST(Capture, BothStreamsWhateverTheirSize) {
  const Captured c = run_capture(
      {"sh", "-c", "head -c 200000 /dev/zero | tr '\\0' e >&2; printf 'job 42'; head -c 100 /dev/zero >&2"});
  EXPECT_EQ(c.status, 0);
  EXPECT_EQ(c.out, "job 42");
  EXPECT_EQ(c.err, std::string(200000, 'e') + std::string(100, '\0'));
}

TEST(Capture, StatusAndAProgramThatIsMissing) {
  EXPECT_EQ(run_capture({"sh", "-c", "printf out; printf err >&2; exit 3"}).status, 3);
  EXPECT_EQ(run_capture({"sh", "-c", "kill -TERM $$"}).status, 128 + 15);
  const Captured c = run_capture({"beltsim-no-such-program"});
  EXPECT_EQ(c.status, 127);
  EXPECT_NE(c.err.find("PATH"), std::string::npos) << c.err;
  EXPECT_EQ(c.out, "");
}

}  // namespace
}  // namespace beltsim::sweep
