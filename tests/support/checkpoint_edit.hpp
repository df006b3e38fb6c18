// Edits of a checkpoint's text (io/checkpoint_text.hpp) for the tests that damage or change one.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "io/checkpoint_text.hpp"

namespace beltsim::test {

// the text with its checksum line made to match again (a file edited on purpose, or by a program)
inline std::string resealed(std::string text) {
  const size_t last = text.rfind('\n', text.size() - 2);
  if (last == std::string::npos) return text;
  text.erase(last + 1);
  char sum[17];
  std::snprintf(sum, sizeof sum, "%016llx", static_cast<unsigned long long>(fnv1a64(text)));
  return text + "checksum fnv1a64 " + sum + "\n";
}

// the text with the first line that opens with `key ` replaced by `line` (a test failure when
// there is none)
inline std::string with_line(const std::string& text, const std::string& key, const std::string& line) {
  const size_t at = text.find("\n" + key + " ");
  EXPECT_NE(at, std::string::npos) << key;
  if (at == std::string::npos) return text;
  const size_t end = text.find('\n', at + 1);
  return text.substr(0, at + 1) + line + text.substr(end);
}

// what follows `key ` on the first line that opens with it ("" when none)
inline std::string value_of(const std::string& text, const std::string& key) {
  const size_t at = text.find("\n" + key + " ");
  if (at == std::string::npos) return "";
  const size_t from = at + key.size() + 2;
  return text.substr(from, text.find('\n', from) - from);
}

// the 1-based number of the first line that opens with key + after (never the first line)
inline int line_of(const std::string& text, const std::string& key, const std::string& after = " ") {
  const size_t at = text.find("\n" + key + after);
  return 2 + static_cast<int>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

}  // namespace beltsim::test
