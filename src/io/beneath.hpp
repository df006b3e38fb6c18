// Opening a path beneath a folder that is open already, never through a symbolic link and never
// above the folder: the one routine by which beltsim opens a file inside a folder, its own outputs
// (io/output_dir.hpp) and a scenario script's files (script/sandbox_files.cpp) alike.
//
// The path is walked one component at a time: each folder is opened by openat() on the folder
// before it with O_PATH | O_DIRECTORY | O_NOFOLLOW (made first when missing and asked for), the
// file at the end with O_NOFOLLOW, so that a symbolic link anywhere on the way, planted before or
// swapped in during the walk, is refused rather than followed (a dangling one too: O_CREAT never
// makes its target). `.` and empty components are skipped; `..` is refused (a caller takes it out
// of the path as text first). The file at the end is opened without blocking and must be a regular
// file (a FIFO or a device is refused before it could hang the caller); one opened for writing
// must have no other hard link (else the write would change a file elsewhere); it is emptied only
// after these checks.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>

namespace beltsim {

// how a file is opened: C's modes "r", "w", "a", "r+", "w+", "a+" (file_mode)
struct FileMode {
  bool read = true;
  bool write = false;
  bool create = false;        // made when missing
  bool empty = false;         // emptied (after the checks)
  bool append = false;        // every write at the end
  bool make_folders = false;  // the missing folders on the way are made
};

// the FileMode of a C mode string ([rwa]+?b*, as Lua's io.open takes it); nullopt for another
std::optional<FileMode> file_mode(std::string_view mode);

// why a path beneath a folder could not be opened
struct BeneathError {
  enum Kind {
    kSystem,      // the system's error err (ENOENT, EACCES, EISDIR, ENOTDIR, ENOSPC, ...)
    kLink,        // a component is a symbolic link
    kNotFolder,   // a component before the last is not a folder
    kNotRegular,  // the file is a FIFO, a device or a socket
    kHardLinks,   // the file, opened for writing, has `links` names
    kDotDot,      // a `..` component
  };
  Kind kind = kSystem;
  int err = 0;
  long links = 0;
  std::string at;  // the path up to the component concerned, as given ("" for none)
  // the reason in words: "it is a symbolic link", "not a regular file", strerror(err), ...
  std::string reason() const;
};

// the folder NAME (one component) in the folder `at`, made when missing and `make`: a descriptor
// (O_PATH | O_DIRECTORY | O_CLOEXEC, the caller closes it), or -1 and *e
int folder_at(int at, const std::string& name, bool make, BeneathError* e);
// the file NAME (one component) in the folder `at`, opened as m says: a descriptor (O_CLOEXEC,
// blocking), or -1 and *e
int file_at(int at, const std::string& name, const FileMode& m, BeneathError* e);

// the same for a relative path of any number of components beneath the folder `root`
int folder_beneath(int root, const std::string& rel, bool make, BeneathError* e);
int file_beneath(int root, const std::string& rel, const FileMode& m, BeneathError* e);

// The folder at a path someone named (a command line's --out, a script's output folder): the
// path up to its last component is the system's to resolve (links on it followed: the user named
// it), the last component is never a link; the missing folders are made, each with folder_at, when
// `make`. A descriptor as folder_at's, or -1 and *e (`at`: the folder concerned, "" is ".").
int folder_path(const std::string& path, bool make, BeneathError* e);

// "a/b/" -> "a/b", "" -> "."
std::string trimmed_path(std::string path);
// the folder and the last component of a path: "a/b/c" -> {"a/b", "c"}, "c" -> {"", "c"}, "/c" -> {"/", "c"}
std::pair<std::string, std::string> split_path(const std::string& path);

// the folder descriptor closed when it goes
class FolderFd {
 public:
  explicit FolderFd(int fd = -1) : fd_(fd) {}
  FolderFd(FolderFd&& o) noexcept : fd_(o.fd_) { o.fd_ = -1; }
  FolderFd& operator=(FolderFd&& o) noexcept;
  FolderFd(const FolderFd&) = delete;
  FolderFd& operator=(const FolderFd&) = delete;
  ~FolderFd();
  int get() const { return fd_; }

 private:
  int fd_;
};

}  // namespace beltsim
