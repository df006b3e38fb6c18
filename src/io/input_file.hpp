// A file a user names, opened for reading (`beltsim compare` and `plot`, read_png, a checkpoint):
// only a regular file is read. The open itself does not block (O_NONBLOCK: a FIFO without a
// writer would hold a plain open for ever), and what was opened is then checked with fstat (no
// race between a check and the open): a FIFO, a device (/dev/zero never ends), a socket or a
// folder is refused before a byte is read. The descriptor is made blocking again for the reads.
#pragma once

#include <cstdio>
#include <stdexcept>
#include <string>

namespace beltsim {

// "cannot read PATH: REASON"; reason alone as given ("No such file or directory", "it is a FIFO
// (a named pipe), not a regular file"), not_regular for a file of another kind than regular
struct InputFileError : std::runtime_error {
  InputFileError(const std::string& path, const std::string& why, bool other_kind)
      : std::runtime_error("cannot read " + path + ": " + why), reason(why), not_regular(other_kind) {}
  std::string reason;
  bool not_regular;
};

class InputFile {
 public:
  explicit InputFile(const std::string& path);  // throws InputFileError
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  const std::string& path() const { return path_; }
  long size() const { return size_; }  // [bytes] when it was opened
  // a stdio stream on it, made once and closed with this object
  std::FILE* stream();
  // the rest of the file (less when it shrank while read); throws InputFileError
  std::string read_rest();

 private:
  std::string path_;
  int fd_ = -1;
  std::FILE* stream_ = nullptr;
  long size_ = 0;
};

}  // namespace beltsim
