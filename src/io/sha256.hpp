// SHA-256 of text and of files (Nettle's, nettle-dev): what a sweep point records of the files that
// define it (sweep/inputs.hpp), so that an edit is seen when the sweep resumes.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <string_view>

namespace beltsim {

// the hash of bytes given a piece at a time
class Sha256 {
 public:
  Sha256();
  ~Sha256();
  Sha256(const Sha256&) = delete;
  Sha256& operator=(const Sha256&) = delete;
  void update(const void* data, std::size_t n);
  void update(std::string_view s) { update(s.data(), s.size()); }
  // the 64 lower-case hex digits of what was given (as sha256sum prints them)
  std::string hex();

 private:
  struct State;
  std::unique_ptr<State> s_;
};

// the hash of the file's bytes; "" when it cannot be read (missing, a folder, unreadable)
std::string file_sha256(const std::string& path);

}  // namespace beltsim
