// A full disk in a test: code run in a child process whose files cannot grow past a size (the
// kernel fails write(2) past RLIMIT_FSIZE the same way it fails it on a full disk: a short write,
// then an error). A child, so that the limit and whatever the code leaves behind (an object that
// cannot be closed, the outputs' recorded failures) stay out of the test program.
#pragma once

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <functional>

namespace beltsim::test {

// exit status of a child killed by a signal, or of no child (fork failed)
constexpr int kNoExitStatus = -1;
// exit status of a child whose code threw (it never returns into the forked copy of the test)
constexpr int kChildThrew = 125;

// runs `child` in a forked process whose files cannot grow past `limit` bytes (SIGXFSZ ignored:
// write(2) fails with EFBIG instead) and returns the child's exit status, which is what `child`
// returns (0 to 124), kChildThrew or kNoExitStatus. The child ends with _exit: no exit handlers
// or destructors of the test program run in it (`child`'s own objects are destroyed as it
// returns; to leave them as they are, it calls _exit itself).
inline int exit_status_under_file_size_limit(long limit, const std::function<int()>& child) {
  const pid_t pid = ::fork();
  if (pid < 0) return kNoExitStatus;
  if (pid == 0) {
    ::signal(SIGXFSZ, SIG_IGN);
    const rlimit r{static_cast<rlim_t>(limit), static_cast<rlim_t>(limit)};
    ::setrlimit(RLIMIT_FSIZE, &r);
    int status = kChildThrew;
    try {
      status = child();
    } catch (...) {
    }
    ::_exit(status);
  }
  int status = 0;
  if (::waitpid(pid, &status, 0) != pid || !WIFEXITED(status)) return kNoExitStatus;
  return WEXITSTATUS(status);
}

}  // namespace beltsim::test
