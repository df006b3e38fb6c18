#include "scene/key_path.hpp"

#include <cctype>

namespace beltsim {

bool ident_start(char c) {
  return std::isalpha(static_cast<unsigned char>(c)) || c == '_';
}
bool ident_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
}
bool digit(char c) {
  return std::isdigit(static_cast<unsigned char>(c));
}
size_t digits_end(std::string_view s, size_t i) {
  while (i < s.size() && digit(s[i])) ++i;
  return i;
}

namespace {

bool is_digits(std::string_view s) {
  return !s.empty() && digits_end(s, 0) == s.size();
}

}  // namespace

std::string path_text(const KeyPath& p) {
  std::string t;
  if (!p.pulley.empty()) t.append("pulley '").append(p.pulley).append("'");
  for (const std::string& k : p.chain) {
    if (is_digits(k))
      t.append("[").append(k).append("]");
    else
      t.append(t.empty() ? "" : ".").append(k);
  }
  return t;
}

KeyPath parse_path(std::string_view text, bool name_after_space) {
  KeyPath p;
  std::string_view rest = text;
  if (constexpr std::string_view pn = "pulley ";
      rest.substr(0, pn.size()) == pn && rest.size() > pn.size() && digit(rest[pn.size()])) {
    // "pulley 2": the second entry of `pulleys` (its name not read yet)
    const size_t e = digits_end(rest, pn.size());
    p.chain = {"pulleys", std::string(rest.substr(pn.size(), e - pn.size()))};
    rest = e < rest.size() && rest[e] == '.' ? rest.substr(e + 1) : std::string_view{};
  } else if (constexpr std::string_view pu = "pulley '"; rest.substr(0, pu.size()) == pu) {
    const size_t e = rest.find('\'', pu.size());
    if (e == std::string_view::npos) return p;
    p.pulley = std::string(rest.substr(pu.size(), e - pu.size()));
    rest = rest.substr(e + 1);
    if (!rest.empty() && (rest[0] == '.' || (rest[0] == ' ' && name_after_space)))
      rest = rest.substr(1);
    else
      rest = {};
  }
  // name ( .name | .digits | [digits] )*
  size_t i = 0;
  while (i < rest.size()) {
    size_t b = i;
    if (ident_start(rest[i])) {
      while (i < rest.size() && ident_char(rest[i])) ++i;
    } else if (!p.chain.empty() && digit(rest[i])) {
      i = digits_end(rest, i);
    } else {
      break;
    }
    p.chain.emplace_back(rest.substr(b, i - b));
    // "spray 2.radius", and "spray 2" at the text's end or before ':', ';' or " (" ("unknown key
    // 'x' in spray 2 (did you mean ...)"): the second entry of the list `spray`
    if (p.chain.size() == 1 && i < rest.size() && rest[i] == ' ') {
      const size_t e = digits_end(rest, i + 1);
      const bool ends = e == rest.size() || rest[e] == ':' || rest[e] == ';' || rest.substr(e, 2) == " (";
      if (e > i + 1 && (ends || (e + 1 < rest.size() && rest[e] == '.'))) {
        p.chain.emplace_back(rest.substr(i + 1, e - i - 1));
        i = e;
      }
    }
    if (i + 1 < rest.size() && rest[i] == '.') {
      ++i;
    } else if (i < rest.size() && rest[i] == '[') {
      const size_t e = rest.find(']', i);
      if (e == std::string_view::npos || !is_digits(rest.substr(i + 1, e - i - 1))) break;
      p.chain.emplace_back(rest.substr(i + 1, e - i - 1));
      i = e + 1;
      if (i + 1 < rest.size() && rest[i] == '.')
        ++i;
      else
        break;
    } else {
      break;
    }
  }
  return p;
}

}  // namespace beltsim
