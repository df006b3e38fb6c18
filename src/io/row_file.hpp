// Text files that are only ever seen holding whole rows, whatever stops the process (an error,
// Ctrl-C, SIGTERM, SIGKILL). A row is assembled in memory and handed to the kernel by one write(2)
// on an unbuffered descriptor: when write returns, the row is in the file (the page cache, which
// outlives the process), and no user-space buffer ever holds the first half of a row while the
// second half waits. A write that fails part-way (a full disk, a file-size limit) cuts the file
// back to where the row began and throws std::runtime_error naming the file and the reason
// (io/output_dir.hpp: recorded, never through a link).
//
// What one write(2) does not cover: the kernel copies a write page by page and a SIGKILL that
// arrives between two pages of one write ends it there (Linux's generic_perform_write checks for
// a fatal signal before each page). A row crosses a page boundary once every 4096/length rows, and
// the window is the copy of one page (well under a microsecond): 1 in 400 SIGKILLs in our kill tests
// (tests/io/row_file_test.cpp, tests/io/kill_test.py). Power loss is another matter (no fsync).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "io/fnv1a64.hpp"
#include "io/output_dir.hpp"

namespace beltsim {

class RowFile {
 public:
  // DIR/NAME opened by OutputDir::open_file: append continues the file (a resumed run); otherwise
  // it is created or emptied. Throws std::runtime_error "cannot write PATH: reason".
  RowFile(const OutputDir& dir, const std::string& name, bool append);
  // the same for a path (its folder made when missing)
  RowFile(const std::string& path, bool append);
  ~RowFile();
  RowFile(const RowFile&) = delete;
  RowFile& operator=(const RowFile&) = delete;

  // one or more whole rows, each ending in '\n', in one write(2)
  void write(std::string_view rows);
  const std::string& path() const { return path_; }
  // FNV-1a 64 (io/fnv1a64.hpp) of the file's bytes: those written here, after the hash of what
  // the file held before (an appended file's, set by continue_hash; an emptied file's: none)
  std::uint64_t hash() const { return hash_; }
  void continue_hash(std::uint64_t before) { hash_ = before; }

 private:
  std::string path_;
  int fd_ = -1;
  std::uint64_t hash_ = kFnv1a64Empty;
};

}  // namespace beltsim
