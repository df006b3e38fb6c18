#include "io/number_text.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <system_error>

namespace beltsim {

void append_number(std::string& out, double v) {
  if (std::isnan(v)) {
    out += "nan";
    return;
  }
  char buf[32];  // the longest shortest form, "-2.2250738585072014e-308", has 24
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  out.append(buf, r.ptr);
}

void append_value(std::string& out, double v) {
  append_number(out, v == 0 ? 0.0 : v);
}

std::string value_text(double v) {
  std::string s;
  append_value(s, v);
  return s;
}

std::string number_text(double v) {
  std::string s;
  append_number(s, v);
  return s;
}

std::string rounded_text(double v, int digits) {
  if (std::isnan(v)) return "nan";  // to_chars writes a NaN with its sign bit set "-nan" (Lua's 0/0 on x86)
  char buf[64];  // %.17g's longest, "-2.2250738585072014e-308", has 24
  const auto r = std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, std::clamp(digits, 1, 17));
  return std::string(buf, r.ptr);
}

std::optional<double> parse_number(std::string_view s) {
  if (s.empty() || s.front() == '+') return std::nullopt;
  double v = 0;
  const auto r = std::from_chars(s.data(), s.data() + s.size(), v, std::chars_format::general);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size()) return std::nullopt;
  return v;
}

}  // namespace beltsim
