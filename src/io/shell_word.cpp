#include "io/shell_word.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <cstring>

namespace beltsim {

std::string shell_word(const std::string& s) {
  auto plain = [](unsigned char c) { return std::isalnum(c) || (c != 0 && std::strchr("_./=:,+-@%", c)); };
  if (!s.empty() && std::all_of(s.begin(), s.end(), plain)) return s;
  const bool control = std::any_of(s.begin(), s.end(), [](unsigned char c) { return c < 0x20 || c == 0x7f; });
  if (!control) {
    std::string q = "'";
    for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return q + "'";
  }
  std::string q = "$'";
  for (unsigned char c : s) {
    if (c == '\'' || c == '\\') {
      q += '\\';
      q += static_cast<char>(c);
    } else if (c == '\n') {
      q += "\\n";
    } else if (c == '\t') {
      q += "\\t";
    } else if (c < 0x20 || c == 0x7f) {
      char b[8];
      std::snprintf(b, sizeof b, "\\x%02x", c);
      q += b;
    } else {
      q += static_cast<char>(c);
    }
  }
  return q + "'";
}

}  // namespace beltsim
