#include "io/beneath.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <vector>

namespace beltsim {

namespace {

// -1, with *e said
int failed(BeneathError* e, BeneathError::Kind kind, int err, const std::string& at) {
  e->kind = kind;
  e->err = err;
  e->at = at;
  return -1;
}

// the components of a relative path, without "" and "."
std::vector<std::string> components(const std::string& rel) {
  std::vector<std::string> v;
  size_t k = 0;
  while (k <= rel.size()) {
    size_t end = rel.find('/', k);
    if (end == std::string::npos) end = rel.size();
    std::string c = rel.substr(k, end - k);
    if (!c.empty() && c != ".") v.push_back(std::move(c));
    k = end + 1;
  }
  return v;
}

// "a/b" from the first n components
std::string joined(const std::vector<std::string>& parts, size_t n) {
  std::string s;
  for (size_t k = 0; k < n; ++k) s += (k ? "/" : "") + parts[k];
  return s;
}

// the folder of the last component: each one before it entered with folder_at; -1 and *e (whose
// `at` is the path up to the component refused)
int walk_to_last(int root, const std::vector<std::string>& parts, bool make, BeneathError* e) {
  FolderFd dir(::fcntl(root, F_DUPFD_CLOEXEC, 0));
  if (dir.get() < 0) return failed(e, BeneathError::kSystem, errno, "");
  for (size_t k = 0; k + 1 < parts.size(); ++k) {
    if (parts[k] == "..") return failed(e, BeneathError::kDotDot, 0, joined(parts, k + 1));
    const int next = folder_at(dir.get(), parts[k], make, e);
    if (next < 0) {
      e->at = joined(parts, k + 1);
      return -1;
    }
    dir = FolderFd(next);
  }
  const int fd = ::fcntl(dir.get(), F_DUPFD_CLOEXEC, 0);
  return fd >= 0 ? fd : failed(e, BeneathError::kSystem, errno, "");
}

}  // namespace

std::optional<FileMode> file_mode(std::string_view mode) {
  FileMode m;
  if (mode.empty()) return std::nullopt;
  const char first = mode.front();
  mode.remove_prefix(1);
  const bool plus = !mode.empty() && mode.front() == '+';
  if (plus) mode.remove_prefix(1);
  if (mode.find_first_not_of('b') != std::string_view::npos) return std::nullopt;
  if (first == 'r') {
    m.write = plus;
  } else if (first == 'w' || first == 'a') {
    m.read = plus;
    m.write = m.create = true;
    m.empty = first == 'w';
    m.append = first == 'a';
  } else {
    return std::nullopt;
  }
  return m;
}

std::string BeneathError::reason() const {
  switch (kind) {
    case kLink: return "it is a symbolic link";
    case kNotFolder: return "not a folder";
    case kNotRegular: return "not a regular file";
    case kHardLinks: return "it has " + std::to_string(links) + " hard links";
    case kDotDot: return "`..` would leave the folder";
    case kSystem: break;
  }
  return std::strerror(err);
}

int folder_at(int at, const std::string& name, bool make, BeneathError* e) {
  if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos)
    return failed(e, BeneathError::kSystem, EINVAL, name);
  const int how = O_PATH | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC;
  int fd = ::openat(at, name.c_str(), how);
  if (fd < 0 && errno == ENOENT && make) {
    if (::mkdirat(at, name.c_str(), 0777) != 0 && errno != EEXIST) return failed(e, BeneathError::kSystem, errno, name);
    fd = ::openat(at, name.c_str(), how);
  }
  if (fd >= 0) return fd;
  // O_DIRECTORY | O_NOFOLLOW says ENOTDIR for a link as for a file: which one it is
  const int err = errno;
  struct stat st {};
  if ((err == ENOTDIR || err == ELOOP) && ::fstatat(at, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0)
    return failed(e, S_ISLNK(st.st_mode) ? BeneathError::kLink : BeneathError::kNotFolder, err, name);
  return failed(e, BeneathError::kSystem, err, name);
}

int file_at(int at, const std::string& name, const FileMode& m, BeneathError* e) {
  if (name.empty() || name == "." || name.find('/') != std::string::npos)
    return failed(e, BeneathError::kSystem, name.empty() || name == "." ? EISDIR : EINVAL, name);
  if (name == "..") return failed(e, BeneathError::kDotDot, 0, name);
  int flags = m.read && m.write ? O_RDWR : m.write ? O_WRONLY : O_RDONLY;
  if (m.create) flags |= O_CREAT;
  if (m.append) flags |= O_APPEND;
  // O_NONBLOCK: a FIFO must not block the open (it is refused below); ENXIO: a FIFO with no reader
  const int fd = ::openat(at, name.c_str(), flags | O_NOFOLLOW | O_CLOEXEC | O_NONBLOCK | O_NOCTTY, 0666);
  if (fd < 0) {
    const int err = errno;
    const BeneathError::Kind kind = err == ELOOP   ? BeneathError::kLink
                                    : err == ENXIO ? BeneathError::kNotRegular
                                                   : BeneathError::kSystem;
    return failed(e, kind, err, name);
  }
  struct stat st {};
  int r = -1;
  if (::fstat(fd, &st) != 0)
    failed(e, BeneathError::kSystem, errno, name);
  else if (S_ISDIR(st.st_mode))
    failed(e, BeneathError::kSystem, EISDIR, name);
  else if (!S_ISREG(st.st_mode))
    failed(e, BeneathError::kNotRegular, 0, name);
  else if (m.write && st.st_nlink > 1)
    failed(e, BeneathError::kHardLinks, 0, name), e->links = static_cast<long>(st.st_nlink);
  else if (::fcntl(fd, F_SETFL, flags & O_APPEND) != 0)  // blocking again
    failed(e, BeneathError::kSystem, errno, name);
  else if (m.empty && ::ftruncate(fd, 0) != 0)
    failed(e, BeneathError::kSystem, errno, name);
  else
    r = fd;
  if (r < 0) ::close(fd);
  return r;
}

int folder_beneath(int root, const std::string& rel, bool make, BeneathError* e) {
  std::vector<std::string> parts = components(rel);
  parts.emplace_back(".");  // every component is a folder on the way
  return walk_to_last(root, parts, make, e);
}

int file_beneath(int root, const std::string& rel, const FileMode& m, BeneathError* e) {
  const std::vector<std::string> parts = components(rel);
  if (parts.empty()) return failed(e, BeneathError::kSystem, EISDIR, rel);
  const FolderFd dir(walk_to_last(root, parts, m.make_folders, e));
  if (dir.get() < 0) return -1;
  const int fd = file_at(dir.get(), parts.back(), m, e);
  if (fd < 0) e->at = joined(parts, parts.size());
  return fd;
}

int folder_path(const std::string& path, bool make, BeneathError* e) {
  const std::string p = trimmed_path(path);
  const int fd = ::open(p.c_str(), O_PATH | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd >= 0) return fd;
  const int err = errno;
  auto [parent, name] = split_path(p);
  if (err == ENOENT && make && !name.empty() && name != "." && name != "..") {
    // missing: made in its parent, itself opened (or made) the same way
    const FolderFd up(folder_path(parent.empty() ? "." : parent, true, e));
    if (up.get() < 0) return -1;
    const int made = folder_at(up.get(), name, true, e);
    if (made < 0) e->at = p;
    return made;
  }
  struct stat st {};
  if ((err == ENOTDIR || err == ELOOP) && ::fstatat(AT_FDCWD, p.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0 &&
      !S_ISDIR(st.st_mode))
    return failed(e, S_ISLNK(st.st_mode) ? BeneathError::kLink : BeneathError::kNotFolder, err, p);
  return failed(e, BeneathError::kSystem, err, p);
}

std::string trimmed_path(std::string path) {
  while (path.size() > 1 && path.back() == '/') path.pop_back();
  return path.empty() ? "." : path;
}

std::pair<std::string, std::string> split_path(const std::string& path) {
  const size_t k = path.rfind('/');
  if (k == std::string::npos) return {"", path};
  return {k == 0 ? "/" : path.substr(0, k), path.substr(k + 1)};
}

FolderFd& FolderFd::operator=(FolderFd&& o) noexcept {
  if (this != &o) {
    if (fd_ >= 0) ::close(fd_);
    fd_ = o.fd_;
    o.fd_ = -1;
  }
  return *this;
}

FolderFd::~FolderFd() {
  if (fd_ >= 0) ::close(fd_);
}

}  // namespace beltsim
