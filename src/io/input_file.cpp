#include "io/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace beltsim {

namespace {

// what a file of another kind than regular is, in words
std::string kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "it is a folder";
  if (S_ISFIFO(mode)) return "it is a FIFO (a named pipe), not a regular file";
  if (S_ISCHR(mode) || S_ISBLK(mode)) return "it is a device, not a regular file";
  if (S_ISSOCK(mode)) return "it is a socket, not a regular file";
  return "not a regular file";
}

}  // namespace

InputFile::InputFile(const std::string& path) : path_(path) {
  fd_ = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd_ < 0) throw InputFileError(path, std::strerror(errno), false);
  struct stat st {};
  std::string why;
  bool other_kind = false;
  if (::fstat(fd_, &st) != 0) {
    why = std::strerror(errno);
  } else if (!S_ISREG(st.st_mode)) {
    why = kind_of(st.st_mode), other_kind = true;
  } else if (::fcntl(fd_, F_SETFL, ::fcntl(fd_, F_GETFL) & ~O_NONBLOCK) != 0) {
    why = std::strerror(errno);
  }
  if (!why.empty()) {
    ::close(fd_);
    throw InputFileError(path, why, other_kind);
  }
  size_ = static_cast<long>(st.st_size);
}

InputFile::~InputFile() {
  if (stream_)
    std::fclose(stream_);  // (closes fd_)
  else
    ::close(fd_);
}

std::FILE* InputFile::stream() {
  if (!stream_ && !(stream_ = ::fdopen(fd_, "rb"))) throw InputFileError(path_, std::strerror(errno), false);
  return stream_;
}

std::string InputFile::read_rest() {
  std::string text(static_cast<size_t>(size_), '\0');
  size_t got = 0;
  while (got < text.size()) {
    const ssize_t n = ::read(fd_, text.data() + got, text.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw InputFileError(path_, std::strerror(errno), false);
    if (n == 0) break;  // it shrank while read
    got += static_cast<size_t>(n);
  }
  text.resize(got);
  return text;
}

}  // namespace beltsim
