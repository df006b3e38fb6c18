#include "sweep/capture.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace beltsim::sweep {

Captured run_capture(const std::vector<std::string>& args) {
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
  const pid_t pid = fork();
  if (pid < 0) {
    const int e = errno;
    for (int fd : {out[0], out[1], err[0], err[1]}) ::close(fd);
    throw std::runtime_error("cannot run " + args[0] + ": " + std::strerror(e));
  }
  if (pid == 0) {
    const int null = ::open("/dev/null", O_RDONLY);
    if (null >= 0) dup2(null, 0);
    dup2(out[1], 1);
    dup2(err[1], 2);
    execvp(argv[0], argv.data());
    const char m[] = "cannot run the program (is it installed and on PATH?)\n";
    (void)!::write(2, m, sizeof m - 1);
    _exit(127);
  }
  ::close(out[1]);
  ::close(err[1]);
  Captured c;
  // both pipes read as they fill: a program that writes much to one while the other stays open
  // must not wait on a full pipe that nobody reads
  pollfd fds[2] = {{out[0], POLLIN, 0}, {err[0], POLLIN, 0}};
  std::string* text[2] = {&c.out, &c.err};
  char b[4096];
  for (int reading = 2; reading > 0;) {
    if (::poll(fds, 2, -1) < 0) {
      if (errno == EINTR) continue;
      break;  // cannot happen with valid descriptors; the output read so far is kept
    }
    for (int k = 0; k < 2; ++k) {
      if (fds[k].fd < 0 || fds[k].revents == 0) continue;
      const ssize_t n = ::read(fds[k].fd, b, sizeof b);
      if (n > 0) {
        text[k]->append(b, static_cast<std::size_t>(n));
      } else if (!(n < 0 && errno == EINTR)) {  // its end (or an error): no more to read
        ::close(fds[k].fd);
        fds[k].fd = -1;
        --reading;
      }
    }
  }
  for (const pollfd& p : fds)
    if (p.fd >= 0) ::close(p.fd);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  c.status = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  return c;
}

}  // namespace beltsim::sweep
