// The stop signals' handler: a signal that the kernel gives to another thread (an encoder's,
// llvmpipe's) is passed on to the main thread, so the main thread's waits end (the console's
// ppoll) and its Lua state is the one interrupted.
#include "script/signals.hpp"

#include <gtest/gtest.h>
#include <poll.h>
#include <pthread.h>

#include <cerrno>
#include <csignal>
#include <thread>

namespace beltsim::script {
namespace signals_test {

TEST(Signals, AStopSignalOnAnotherThreadReachesTheMainThread) {
  install_stop_signals();
  // SIGINT blocked here until ppoll unblocks it, so that it cannot come before the wait
  sigset_t with_int, without_int;
  sigemptyset(&with_int);
  sigaddset(&with_int, SIGINT);
  ASSERT_EQ(pthread_sigmask(SIG_BLOCK, &with_int, &without_int), 0);
  sigdelset(&without_int, SIGINT);
  std::thread other([&] {  // SIGINT to that thread alone, which takes it (as an encoder's thread would)
    pthread_sigmask(SIG_UNBLOCK, &with_int, nullptr);
    pthread_kill(pthread_self(), SIGINT);
  });
  other.join();
  const timespec wait{5, 0};  // far longer than the passing on takes; without it the wait runs out
  const int r = ppoll(nullptr, 0, &wait, &without_int);
  const int err = errno;
  pthread_sigmask(SIG_SETMASK, &without_int, nullptr);
  EXPECT_EQ(r, -1);
  EXPECT_EQ(err, EINTR);
  EXPECT_TRUE(stop_flag().load());
  command_done();  // the Ctrl-C taken: the next command starts afresh
  EXPECT_FALSE(stop_flag().load());
}

}  // namespace signals_test
}  // namespace beltsim::script
