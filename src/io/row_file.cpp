#include "io/row_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace beltsim {

namespace {

// all of text, in one write(2) unless the kernel takes less (a disk filling part-way: then the
// rest, which gets the error); 0 or the errno, `done` the bytes written
int write_all(int fd, std::string_view text, size_t& done) {
  done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n > 0) done += static_cast<size_t>(n);
    else if (!(n < 0 && errno == EINTR)) return n < 0 ? errno : ENOSPC;
  }
  return 0;
}

}  // namespace

RowFile::RowFile(const OutputDir& dir, const std::string& name, bool append)
    : path_(dir.file(name)), fd_(dir.open_file(name, append)) {}

RowFile::RowFile(const std::string& path, bool append) : path_(path) {
  const OutputPlace p = output_place(path);
  fd_ = p.dir.open_file(p.name, append);
}

RowFile::~RowFile() {
  if (fd_ >= 0) ::close(fd_);
}

void RowFile::write(std::string_view rows) {
  size_t done = 0;
  const int err = write_all(fd_, rows, done);
  if (err == 0) {
    hash_ = fnv1a64(rows, hash_);
    return;
  }
  // no half row left behind: cut the file back to where this write began
  if (done > 0) {
    const off_t end = ::lseek(fd_, 0, SEEK_CUR);
    if (end >= static_cast<off_t>(done) && ::ftruncate(fd_, end - static_cast<off_t>(done)) == 0)
      ::lseek(fd_, end - static_cast<off_t>(done), SEEK_SET);
  }
  output_error(path_, std::strerror(err));
}

}  // namespace beltsim
