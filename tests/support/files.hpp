// Small helpers many test files share: a file's bytes, the message a call throws.
#pragma once

#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

namespace beltsim::test {

// every byte of the file ("" when it cannot be read)
inline std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// the file made to hold exactly `text`
inline void spit(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// what() of the std::exception the call throws, "" when it throws none
inline std::string what_of(const std::function<void()>& call) {
  try {
    call();
  } catch (const std::exception& e) {
    return e.what();
  }
  return "";
}

}  // namespace beltsim::test
