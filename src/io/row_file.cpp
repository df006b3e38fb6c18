#include "io/row_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace beltsim {

namespace {

[[noreturn]] void fail(const std::string& path, int err) {
  throw std::runtime_error("cannot write " + path + ": " + std::strerror(err));
}

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

int open_for_writing(const std::string& path, bool append) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC | (append ? O_APPEND : O_TRUNC), 0666);
  if (fd < 0) fail(path, errno);
  return fd;
}

}  // namespace

RowFile::RowFile(const std::string& path, bool append) : path_(path), fd_(open_for_writing(path, append)) {}

RowFile::~RowFile() {
  if (fd_ >= 0) ::close(fd_);
}

void RowFile::write(std::string_view rows) {
  size_t done = 0;
  const int err = write_all(fd_, rows, done);
  if (err == 0) return;
  // no half row left behind: cut the file back to where this write began
  if (done > 0) {
    const off_t end = ::lseek(fd_, 0, SEEK_CUR);
    if (end >= static_cast<off_t>(done) && ::ftruncate(fd_, end - static_cast<off_t>(done)) == 0)
      ::lseek(fd_, end - static_cast<off_t>(done), SEEK_SET);
  }
  fail(path_, err);
}

void write_file_whole(const std::string& path, std::string_view text) {
  const std::string part = path + ".part";
  const int fd = open_for_writing(part, false);
  size_t done = 0;
  int err = write_all(fd, text, done);
  if (::close(fd) != 0 && err == 0) err = errno;
  if (err == 0 && std::rename(part.c_str(), path.c_str()) != 0) err = errno;
  if (err != 0) {
    std::remove(part.c_str());
    fail(path, err);
  }
}

}  // namespace beltsim
