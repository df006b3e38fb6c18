#include "io/output_dir.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <mutex>
#include <stdexcept>

#include "io/beneath.hpp"

namespace beltsim {

namespace {

std::mutex g_failures_mutex;
std::vector<std::string> g_failures;
std::vector<bool> g_shown;  // g_failures[k] was shown to the user

constexpr const char* kLink = "it is a symbolic link (beltsim never writes through a link)";
constexpr const char* kLockName = ".beltsim.lock";

// why openat failed, said for an output
std::string why(int err) {
  if (err == ELOOP) return kLink;
  return std::strerror(err);
}

// a BeneathError said for an output
std::string said(const BeneathError& e) {
  if (e.kind == BeneathError::kLink) return kLink;
  if (e.kind == BeneathError::kHardLinks) return e.reason() + " (beltsim writes only files of its own)";
  return e.reason();
}

// `shown`: the file as messages name it (OutputDir::file)
void check_name(const std::string& shown, const std::string& name) {
  if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos)
    output_error(shown, "not a file name");
}

constexpr const char* kThisBeltsim = "another simulation of this beltsim";

// who holds the lock file open as fd, from the process id its holder wrote in it
std::string lock_holder(int fd) {
  char buf[32] = {0};
  const ssize_t n = ::pread(fd, buf, sizeof buf - 1, 0);
  const long pid = n > 0 ? std::strtol(buf, nullptr, 10) : 0;
  return pid == static_cast<long>(::getpid()) ? kThisBeltsim
         : pid > 0                            ? "another beltsim (process " + std::to_string(pid) + ")"
                                              : "another beltsim";
}

void write_all(int fd, std::string_view text, const std::string& path) {
  for (size_t done = 0; done < text.size();) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n > 0)
      done += static_cast<size_t>(n);
    else if (!(n < 0 && errno == EINTR))
      output_error(path, std::strerror(n < 0 ? errno : ENOSPC));
  }
}

}  // namespace

void note_output_failure(const std::string& message) {
  std::lock_guard<std::mutex> g(g_failures_mutex);
  g_failures.push_back(message);
  g_shown.push_back(false);
}

void output_error(const std::string& path, const std::string& reason) {
  const std::string m = "cannot write " + path + ": " + reason;
  note_output_failure(m);
  throw OutputError(m);
}

std::vector<std::string> output_failures() {
  std::lock_guard<std::mutex> g(g_failures_mutex);
  return g_failures;
}

std::vector<std::string> unshown_output_failures() {
  std::lock_guard<std::mutex> g(g_failures_mutex);
  std::vector<std::string> v;
  for (size_t k = 0; k < g_failures.size(); ++k)
    if (!g_shown[k]) v.push_back(g_failures[k]);
  return v;
}

void mark_output_failure_shown(const std::string& message) {
  std::lock_guard<std::mutex> g(g_failures_mutex);
  for (size_t k = 0; k < g_failures.size(); ++k)
    if (message.find(g_failures[k]) != std::string::npos) g_shown[k] = true;
}

// ---- folders -------------------------------------------------------------------------------------

OutputDir::OutputDir(const std::string& path, bool make) : OutputDir(path, make, nullptr) {}

OutputDir::OutputDir(const std::string& path, bool make, const std::string* shown)
    : path_(trimmed_path(path)), bare_(path.empty()) {
  BeneathError e;
  fd_ = folder_path(path_, make, &e);
  if (fd_ >= 0) return;
  // errors name the file the folder was opened for, when there is one
  const std::string& folder = e.at.empty() ? path_ : e.at;
  const std::string reason =
      e.kind == BeneathError::kSystem && e.err == ENOENT && !make ? "missing: " + e.reason() : said(e);
  output_error(shown ? *shown : folder, shown ? folder + " is " + reason : reason);
}

OutputDir::OutputDir(const OutputDir& parent, const std::string& name) {
  path_ = parent.file(name);
  check_name(path_, name);
  BeneathError e;
  fd_ = folder_at(parent.fd_, name, true, &e);
  if (fd_ < 0) output_error(path_, said(e));
}

OutputDir::OutputDir(OutputDir&& o) noexcept
    : path_(std::move(o.path_)), bare_(o.bare_), fd_(o.fd_), lock_fd_(o.lock_fd_) {
  o.fd_ = o.lock_fd_ = -1;
}

OutputDir& OutputDir::operator=(OutputDir&& o) noexcept {
  if (this != &o) {
    unlock();
    if (fd_ >= 0) ::close(fd_);
    path_ = std::move(o.path_), bare_ = o.bare_;
    fd_ = o.fd_, lock_fd_ = o.lock_fd_;
    o.fd_ = o.lock_fd_ = -1;
  }
  return *this;
}

OutputDir::~OutputDir() {
  unlock();
  if (fd_ >= 0) ::close(fd_);
  fd_ = lock_fd_ = -1;
}

std::string OutputDir::file(std::string_view name) const {
  if (bare_) return std::string(name);  // a file given by its bare name, as given ("taken.csv", not "./taken.csv")
  std::string f = path_;
  if (f != "/") f += '/';
  f.append(name);
  return f;
}

// ---- files written in place ------------------------------------------------------------------------

int OutputDir::open_file(const std::string& name, bool append) const {
  return open_own(name, O_WRONLY | (append ? O_APPEND : 0), !append);
}

int OutputDir::open_own(const std::string& name, int flags, bool empty) const {
  check_name(file(name), name);
  FileMode m;
  m.read = (flags & O_ACCMODE) == O_RDWR;
  m.write = m.create = true;
  m.append = (flags & O_APPEND) != 0;
  m.empty = empty;
  BeneathError e;
  const int fd = file_at(fd_, name, m, &e);
  if (fd < 0) output_error(file(name), said(e));
  return fd;
}

void OutputDir::truncate(const std::string& name, long bytes, long room) const {
  const std::string p = file(name);
  const long have = size(name);
  if (have < 0) output_error(p, "the run's output is missing");
  if (have < bytes) output_error(p, "shorter than when the checkpoint was taken");
  const int fd = open_file(name, true);
  const int r = ::ftruncate(fd, bytes);
  const int err = errno;
  if (r == 0 && room > 0 && ::fallocate(fd, FALLOC_FL_KEEP_SIZE, bytes, room) != 0) errno = 0;  // (as reserve)
  ::close(fd);
  if (r != 0) output_error(p, std::strerror(err));
}

long OutputDir::size(const std::string& name) const {
  struct stat st {};
  if (::fstatat(fd_, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) != 0 || !S_ISREG(st.st_mode)) return -1;
  return static_cast<long>(st.st_size);
}

bool OutputDir::has(const std::string& name) const {
  struct stat st {};
  return ::fstatat(fd_, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0;
}

void OutputDir::remove(const std::string& name) const {
  ::unlinkat(fd_, name.c_str(), 0);
}

void OutputDir::lock() {
  const std::string who = try_lock();
  if (!who.empty())
    throw std::runtime_error("the output folder " + path_ + " is in use by " + who +
                             ": two simulations writing one folder would mix their rows; give this one a folder of "
                             "its own (out = ...) or close the other first");
}

namespace {
// the file open as fd is the one named `name` in the folder dir
bool same_file(int dir, const char* name, int fd) {
  struct stat a {
  }, b{};
  return ::fstat(fd, &a) == 0 && ::fstatat(dir, name, &b, AT_SYMLINK_NOFOLLOW) == 0 && a.st_dev == b.st_dev &&
         a.st_ino == b.st_ino;
}
}  // namespace

std::string OutputDir::try_lock() {
  if (lock_fd_ >= 0) return "";
  int fd = -1;
  // the holder before us removes the file while it still holds the lock (unlock): a claim that
  // opened the file before that gets its lock on a removed file, and opens the new one again
  for (int attempt = 0;; ++attempt) {
    fd = open_own(kLockName, O_RDWR, false);
    struct flock whole {};
    whole.l_type = F_WRLCK;
    whole.l_whence = SEEK_SET;  // the whole file (l_len 0)
    if (::fcntl(fd, F_OFD_SETLK, &whole) != 0) {
      const int err = errno;
      const std::string who = lock_holder(fd);
      ::close(fd);
      if (err != EAGAIN && err != EACCES)
        throw std::runtime_error("cannot lock the output folder " + path_ + ": " + std::strerror(err));
      return who;
    }
    if (same_file(fd_, kLockName, fd)) break;
    ::close(fd);
    if (attempt == 1000)
      throw std::runtime_error("cannot lock the output folder " + path_ + ": its " + kLockName +
                               " was removed under every claim (1000 tries)");
  }
  // who holds it, for the messages; the lock is the OFD lock, and holds without this text
  const std::string pid = std::to_string(::getpid()) + "\n";
  if (::ftruncate(fd, 0) == 0 && ::pwrite(fd, pid.data(), pid.size(), 0) < 0) errno = 0;
  lock_fd_ = fd;
  return "";
}

void OutputDir::unlock() {
  if (lock_fd_ < 0) return;
  // removed while held, so no other claim can hold the file at that name meanwhile; then released
  if (same_file(fd_, kLockName, lock_fd_)) ::unlinkat(fd_, kLockName, 0);
  ::close(lock_fd_);
  lock_fd_ = -1;
}

std::string folder_holder(int dir) {
  const int fd = ::openat(dir, kLockName, O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return "";  // never claimed
  std::string who;
  struct stat st {};
  struct flock whole {};
  whole.l_type = F_WRLCK;
  whole.l_whence = SEEK_SET;
  // a query, not a claim: a simulation starting meanwhile is not refused because of it
  if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && ::fcntl(fd, F_OFD_GETLK, &whole) == 0 &&
      whole.l_type != F_UNLCK) {
    who = lock_holder(fd);
    if (who == kThisBeltsim) who = "";
  }
  ::close(fd);
  return who;
}

std::vector<std::string> regular_files(const std::string& path, const std::function<bool(const std::string&)>& keep) {
  std::error_code ec;
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(path, ec)) {
    const std::string n = e.path().filename().string();
    if (e.symlink_status(ec).type() == std::filesystem::file_type::regular && keep(n)) names.push_back(n);
  }
  std::sort(names.begin(), names.end());
  return names;
}

void remove_numbered(const OutputDir& dir, const std::function<bool(const std::string&)>& numbered) {
  for (const std::string& n : regular_files(dir.path(), numbered)) dir.remove(n);
}

OutputPlace output_place(const std::string& path) {
  auto [dir, name] = split_path(trimmed_path(path));
  if (name.empty() || name == "." || name == "..") output_error(path, "not a file name");
  return OutputPlace{OutputDir(dir, true, &path), name};
}

// ---- files written whole ---------------------------------------------------------------------------

WholeFile::WholeFile(const OutputDir& dir, std::string name) : dir_(dir), name_(std::move(name)) {
  check_name(path(), name_);
  struct stat st {};
  if (::fstatat(dir_.fd(), name_.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0) {
    if (S_ISLNK(st.st_mode)) output_error(path(), kLink);
    if (S_ISDIR(st.st_mode)) output_error(path(), "it is a folder");
  }
  fd_ = ::openat(dir_.fd(), ".", O_TMPFILE | O_WRONLY | O_CLOEXEC, 0666);
  if (fd_ >= 0) return;
  // a file system without unnamed files: NAME.part, made afresh (a stale one, or a link planted
  // under that name, removed first: the name is ours)
  unnamed_ = false;
  const std::string part = name_ + ".part";
  dir_.remove(part);
  fd_ = ::openat(dir_.fd(), part.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);
  // named as the file asked for (a user's trial read "cannot write ro/a.png.part" for ro/a.png)
  if (fd_ < 0) output_error(path(), why(errno));
}

WholeFile::~WholeFile() {
  discard();
}

void WholeFile::write(std::string_view text) {
  try {
    write_all(fd_, text, path());
  } catch (...) {
    discard();
    throw;
  }
}

void WholeFile::reserve(long bytes) {
  struct stat st {};
  if (!done_ && ::fstat(fd_, &st) == 0 && ::fallocate(fd_, FALLOC_FL_KEEP_SIZE, st.st_size, bytes) != 0)
    errno = 0;  // (none taken: the rows appended later may still find room)
}

void WholeFile::discard() {
  if (done_) return;
  done_ = true;
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  if (!unnamed_) dir_.remove(name_ + ".part");
}

void WholeFile::commit(const std::string& as) {
  if (done_) output_error(path(), "already written or given up");
  const std::string part = name_ + ".part";
  const std::string name = as.empty() ? name_ : as;
  check_name(dir_.file(name), name);
  int err = 0;
  if (unnamed_) {
    // an unnamed file gets a name by linkat, which never replaces one: NAME.part first (a stale one
    // removed), then renamed over NAME
    dir_.remove(part);
    const std::string proc = "/proc/self/fd/" + std::to_string(fd_);
    if (::linkat(AT_FDCWD, proc.c_str(), dir_.fd(), part.c_str(), AT_SYMLINK_FOLLOW) != 0 &&
        ::linkat(fd_, "", dir_.fd(), part.c_str(), AT_EMPTY_PATH) != 0)
      err = errno;
    unnamed_ = err != 0;  // from here NAME.part exists
  }
  if (::close(fd_) != 0 && err == 0) err = errno;
  fd_ = -1;
  if (err == 0 && ::renameat(dir_.fd(), part.c_str(), dir_.fd(), name.c_str()) != 0) err = errno;
  if (err != 0) {
    discard();
    output_error(dir_.file(name), std::strerror(err));
  }
  name_ = name;
  done_ = true;
}

void write_file_whole(const OutputDir& dir, const std::string& name, std::string_view text) {
  WholeFile f(dir, name);
  f.write(text);
  f.commit();
}

void write_file_whole(const std::string& path, std::string_view text) {
  const OutputPlace p = output_place(path);
  write_file_whole(p.dir, p.name, text);
}

namespace {
// the path's extension in lower case (".PNG" is ".png")
std::string extension(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext;
}
}  // namespace

std::string png_name_problem(const std::string& path) {
  return extension(path) == ".png" ? "" : "beltsim draws PNG pictures: give a name ending in .png";
}

std::string video_name_problem(const std::string& path) {
  return extension(path) == ".mp4" ? "" : "beltsim writes MP4 videos (H.264): give a name ending in .mp4";
}

}  // namespace beltsim
