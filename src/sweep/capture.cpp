#include "sweep/capture.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>
#include <stdexcept>

namespace beltsim::sweep {

namespace {

using Clock = std::chrono::steady_clock;

// the child: its own process group, /dev/null as input, the pipes as output and error, then args
[[noreturn]] void start_child(std::vector<char*>& argv, int out, int err) {
  ::setpgid(0, 0);
  const int null = ::open("/dev/null", O_RDONLY);
  if (null >= 0) dup2(null, 0);
  dup2(out, 1);
  dup2(err, 2);
  execvp(argv[0], argv.data());
  const char m[] = "cannot run the program (is it installed and on PATH?)\n";
  (void)!::write(2, m, sizeof m - 1);
  _exit(127);
}

// the milliseconds poll may wait before the deadline (-1: no deadline; 0: it has passed)
int wait_ms(bool limited, Clock::time_point deadline) {
  if (!limited) return -1;
  const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
  return left <= 0 ? 0 : static_cast<int>(std::min<long long>(left + 1, 60'000));
}

}  // namespace

Captured run_capture(const std::vector<std::string>& args, const CaptureLimits& limits) {
  int out[2], err[2];
  if (pipe2(out, O_CLOEXEC) != 0) throw std::runtime_error("cannot run " + args[0] + ": " + std::strerror(errno));
  if (pipe2(err, O_CLOEXEC) != 0) {
    const int e = errno;
    ::close(out[0]), ::close(out[1]);
    throw std::runtime_error("cannot run " + args[0] + ": " + std::strerror(e));
  }
  std::vector<std::string> a = args;
  std::vector<char*> argv;
  for (std::string& x : a) argv.push_back(x.data());
  argv.push_back(nullptr);
  const bool limited = limits.seconds > 0;
  const Clock::time_point deadline =
      Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(limits.seconds));
  const pid_t pid = fork();
  if (pid < 0) {
    const int e = errno;
    for (int fd : {out[0], out[1], err[0], err[1]}) ::close(fd);
    throw std::runtime_error("cannot run " + args[0] + ": " + std::strerror(e));
  }
  if (pid == 0) start_child(argv, out[1], err[1]);
  ::setpgid(pid, pid);  // also here, so that the group exists before any kill below
  ::close(out[1]);
  ::close(err[1]);
  Captured c;
  // both pipes read as they fill: a program that writes much to one while the other stays open
  // must not wait on a full pipe that nobody reads
  pollfd fds[2] = {{out[0], POLLIN, 0}, {err[0], POLLIN, 0}};
  std::string* text[2] = {&c.out, &c.err};
  char b[4096];
  for (int reading = 2; reading > 0 && !c.timed_out && !c.overflowed;) {
    const int ready = ::poll(fds, 2, wait_ms(limited, deadline));
    if (ready < 0) {
      if (errno == EINTR) continue;
      break;  // cannot happen with valid descriptors; the output read so far is kept
    }
    if (ready == 0) {  // only with a deadline, which has passed
      c.timed_out = true;
      break;
    }
    for (int k = 0; k < 2; ++k) {
      if (fds[k].fd < 0 || fds[k].revents == 0) continue;
      const ssize_t n = ::read(fds[k].fd, b, sizeof b);
      if (n > 0) {
        text[k]->append(b, static_cast<std::size_t>(n));
        if (limits.max_bytes > 0 && text[k]->size() > limits.max_bytes) {
          text[k]->resize(limits.max_bytes);
          c.overflowed = true;
        }
      } else if (!(n < 0 && errno == EINTR)) {  // its end (or an error): no more to read
        ::close(fds[k].fd);
        fds[k].fd = -1;
        --reading;
      }
    }
  }
  for (const pollfd& p : fds)
    if (p.fd >= 0) ::close(p.fd);
  if (c.timed_out || c.overflowed) ::kill(-pid, SIGKILL);
  int status = 0;
  // a program that closed its output but keeps running is waited for until the deadline only
  while (true) {
    const pid_t w = waitpid(pid, &status, limited && !c.timed_out && !c.overflowed ? WNOHANG : 0);
    if (w == pid) break;
    if (w < 0 && errno == EINTR) continue;
    if (w < 0) break;
    if (Clock::now() >= deadline) {
      c.timed_out = true;
      ::kill(-pid, SIGKILL);
      continue;
    }
    ::usleep(10'000);
  }
  c.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return c;
}

}  // namespace beltsim::sweep
