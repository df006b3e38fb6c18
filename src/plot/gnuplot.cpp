#include "plot/gnuplot.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "io/output_dir.hpp"

extern char** environ;

namespace beltsim::plot {

namespace {

namespace fs = std::filesystem;

// a file descriptor closed on every path out
struct Fd {
  int fd = -1;
  ~Fd() { reset(); }
  void reset() {
    if (fd >= 0) ::close(fd);
    fd = -1;
  }
};

// the script in a fresh file only we can read (mkstemps), removed when this goes out of scope
struct ScriptFile {
  std::string path;
  explicit ScriptFile(const std::string& text) {
    std::string templ = (fs::temp_directory_path() / "beltsim-gnuplot-XXXXXX.gp").string();
    if (!templ.empty() && templ[0] != '/') templ = fs::absolute(templ).string();  // never read as an option
    Fd f{::mkstemps(templ.data(), 3)};
    if (f.fd < 0) throw std::runtime_error("gnuplot: cannot create a script file in " + templ + ": " + std::strerror(errno));
    path = templ;
    for (size_t done = 0; done < text.size();) {
      const ssize_t n = ::write(f.fd, text.data() + done, text.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        const std::string why = std::strerror(errno);
        ::unlink(path.c_str());
        throw std::runtime_error("gnuplot: cannot write " + path + ": " + why);
      }
      done += static_cast<size_t>(n);
    }
  }
  ~ScriptFile() { ::unlink(path.c_str()); }
};

}  // namespace

PrivateOutput::PrivateOutput() {
  std::string templ = (fs::temp_directory_path() / "beltsim-gnuplot-XXXXXX").string();
  if (!templ.empty() && templ[0] != '/') templ = fs::absolute(templ).string();
  if (!::mkdtemp(templ.data()))
    throw std::runtime_error("gnuplot: cannot make a private folder " + templ + ": " + std::strerror(errno));
  dir_ = templ;
  file_ = dir_ + "/out.png";
}

PrivateOutput::~PrivateOutput() {
  std::error_code ec;
  fs::remove_all(dir_, ec);
}

void PrivateOutput::deliver(const std::string& dest, const std::string& who) const {
  std::ifstream in(file_, std::ios::binary);
  std::ostringstream bytes;
  if (in) bytes << in.rdbuf();
  if (!in || bytes.str().empty()) throw std::runtime_error(who + ": gnuplot reported no error but wrote no " + dest);
  write_file_whole(dest, bytes.str());
}

std::string gnuplot_string(std::string_view text) {
  std::string s = "'";
  for (char c : text) {
    if (c == '\'')
      s += "''";
    else if (c == '\n' || c == '\r')
      s += ' ';
    else
      s += c;
  }
  return s + "'";
}

std::string run_gnuplot(const std::string& script) {
  const ScriptFile file(script);
  // gnuplot's stdout and stderr into one pipe, read to its end before waiting
  int fds[2];
  if (::pipe2(fds, O_CLOEXEC) != 0) throw std::runtime_error(std::string("gnuplot: pipe: ") + std::strerror(errno));
  Fd rd{fds[0]}, wr{fds[1]};
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, wr.fd, 1);
  posix_spawn_file_actions_adddup2(&actions, wr.fd, 2);
  std::string arg0 = "gnuplot", arg1 = file.path;
  char* argv[] = {arg0.data(), arg1.data(), nullptr};
  pid_t pid = 0;
  const int rc = ::posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  wr.reset();
  if (rc == ENOENT) throw std::runtime_error("gnuplot not found on PATH (install the Debian package gnuplot-nox)");
  if (rc != 0) throw std::runtime_error(std::string("gnuplot: cannot start it: ") + std::strerror(rc));
  std::string out;
  char buf[4096];
  for (;;) {
    const ssize_t n = ::read(rd.fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    out.append(buf, static_cast<size_t>(n));
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw std::runtime_error(std::string("gnuplot: waitpid: ") + std::strerror(errno));
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return out;
  const std::string how = WIFEXITED(status) ? "exit " + std::to_string(WEXITSTATUS(status))
                                            : "signal " + std::to_string(WTERMSIG(status));
  throw std::runtime_error("gnuplot failed (" + how + "): " + (out.empty() ? "no message" : out));
}

const char* const kLineColours[10] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                      "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};

std::string line_colours_script() {
  std::string s;
  for (int k = 0; k < 10; ++k) s += "set linetype " + std::to_string(k + 1) + " lc rgb '" + kLineColours[k] + "'\n";
  return s + "set linetype cycle 10\n";
}

}  // namespace beltsim::plot
