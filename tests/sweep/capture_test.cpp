// A program's output and error captured (src/sweep/capture.hpp), through sh.
#include "sweep/capture.hpp"

#include <gtest/gtest.h>

#include <chrono>
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

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// past its time the program is killed with the children it started (a pipe they hold open does
// not keep the reader waiting), and what it printed before is kept
TEST(Capture, AProgramPastItsTimeIsStoppedWithItsChildren) {
  const auto t0 = std::chrono::steady_clock::now();
  const Captured c = run_capture({"sh", "-c", "printf started; sleep 30 & wait"}, {0.5, 0});
  EXPECT_LT(seconds_since(t0), 10.0);
  EXPECT_TRUE(c.timed_out);
  EXPECT_FALSE(c.overflowed);
  EXPECT_EQ(c.status, 128 + 9);
  EXPECT_EQ(c.out, "started");
  // a child that outlives its parent with the pipe open: the same
  const Captured d = run_capture({"sh", "-c", "(sleep 30; echo late) & printf gone"}, {0.5, 0});
  EXPECT_LT(seconds_since(t0), 20.0);
  EXPECT_TRUE(d.timed_out);
  EXPECT_EQ(d.out, "gone");
}

// more output than the bound on either stream: the program is stopped, the first bytes kept
TEST(Capture, OutputPastItsBoundStopsTheProgram) {
  const auto t0 = std::chrono::steady_clock::now();
  const Captured c = run_capture({"sh", "-c", "head -c 50000000 /dev/zero | tr '\\0' 7; sleep 30"}, {60, 65536});
  EXPECT_LT(seconds_since(t0), 20.0);
  EXPECT_TRUE(c.overflowed);
  EXPECT_FALSE(c.timed_out);
  EXPECT_EQ(c.out, std::string(65536, '7'));
  const Captured d = run_capture({"sh", "-c", "head -c 200000 /dev/zero >&2; sleep 30"}, {60, 1000});
  EXPECT_TRUE(d.overflowed);
  EXPECT_EQ(d.err.size(), 1000u);
  // within the bounds nothing changes
  const Captured e = run_capture({"sh", "-c", "printf 12"}, {60, 2});
  EXPECT_FALSE(e.overflowed || e.timed_out);
  EXPECT_EQ(e.out, "12");
  EXPECT_EQ(e.status, 0);
}

}  // namespace
}  // namespace beltsim::sweep
