#include "io/suggest.hpp"

#include <algorithm>

namespace beltsim {

std::size_t edit_distance(const std::string& a, const std::string& b) {
  // d[i][j]: distance between the first i characters of a and the first j of b
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= n; ++i)
    for (std::size_t j = 1; j <= m; ++j) {
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + (a[i - 1] != b[j - 1])});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);  // two neighbours swapped
    }
  return d[n][m];
}

namespace {
// `word` is one of the '_'-separated words of `name`
bool is_word_of(const std::string& word, const std::string& name) {
  if (word.empty() || word.size() >= name.size()) return false;
  std::size_t start = 0;
  for (;;) {
    const std::size_t end = name.find('_', start);
    if (name.compare(start, end == std::string::npos ? std::string::npos : end - start, word) == 0 &&
        (end == std::string::npos ? name.size() - start : end - start) == word.size())
      return true;
    if (end == std::string::npos) return false;
    start = end + 1;
  }
}
}  // namespace

std::vector<std::string> close_names(const std::string& name, const std::vector<std::string>& valid) {
  const std::size_t limit = std::max<std::size_t>(1, (name.size() + 2) / 5);
  std::size_t best = limit + 1;
  std::vector<std::string> out;
  for (const std::string& v : valid) {
    if (v == name) continue;
    const std::size_t d = edit_distance(name, v);
    if (d > limit || d >= v.size() || d > best) continue;  // a one-letter name is close to nothing
    if (d < best) out.clear(), best = d;
    if (std::find(out.begin(), out.end(), v) == out.end()) out.push_back(v);
  }
  if (!out.empty()) return out;
  for (const std::string& v : valid)
    if (is_word_of(name, v) && std::find(out.begin(), out.end(), v) == out.end()) out.push_back(v);
  return out;
}

std::string did_you_mean(const std::string& name, const std::vector<std::string>& valid) {
  const std::vector<std::string> c = close_names(name, valid);
  if (c.empty()) return "";
  std::string s = " (did you mean ";
  for (std::size_t k = 0; k < c.size(); ++k)
    s += (k == 0 ? "'" : k + 1 == c.size() ? " or '" : ", '") + c[k] + "'";
  return s + "?)";
}

std::string no_such(const std::string& kind, const std::string& name, const std::vector<std::string>& valid) {
  return "no " + kind + " '" + name + "'" + did_you_mean(name, valid) + "; " + kind + "s: " + join(valid);
}

std::string join(const std::vector<std::string>& names, const std::string& sep) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : sep) + n;
  return s;
}

namespace {
// the names joined by ", ", the last by " WORD "
std::string listed(const std::vector<std::string>& names, const std::string& word) {
  std::string list;
  for (size_t k = 0; k < names.size(); ++k)
    list += (k ? k + 1 < names.size() ? ", " : " " + word + " " : "") + names[k];
  return list;
}
}  // namespace

std::string and_list(const std::vector<std::string>& names) {
  return listed(names, "and");
}

std::string or_list(const std::vector<std::string>& names) {
  return listed(names, "or");
}

}  // namespace beltsim
