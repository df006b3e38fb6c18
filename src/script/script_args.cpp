#include "script/script_args.hpp"

#include <charconv>
#include <cctype>
#include <cmath>
#include <stdexcept>

namespace beltsim::script {

std::optional<double> decimal(const std::string& s) {
  const size_t from = !s.empty() && s[0] == '+' ? 1 : 0;
  double x = 0;
  const auto r = std::from_chars(s.data() + from, s.data() + s.size(), x, std::chars_format::general);
  if (s.size() == from || r.ec != std::errc() || r.ptr != s.data() + s.size() || !std::isfinite(x)) return std::nullopt;
  return x;
}

ScriptArg parse_set(const std::string& kv) {
  const size_t eq = kv.find('=');
  auto bad = [&](const std::string& why) { return std::invalid_argument("--set " + kv + ": " + why); };
  if (eq == std::string::npos) throw bad("KEY=VALUE expected (e.g. --set elements=120)");
  ScriptArg a;
  a.key = kv.substr(0, eq);
  a.text = kv.substr(eq + 1);
  bool name = !a.key.empty() && !std::isdigit(static_cast<unsigned char>(a.key[0]));
  for (char c : a.key) name = name && (std::isalnum(static_cast<unsigned char>(c)) || c == '_');
  if (!name) throw bad("the key must be a Lua name (letters, digits and _, not starting with a digit)");
  for (const char* kw : {"and", "break", "do", "else", "elseif", "end", "false", "for", "function", "goto", "if", "in",
                         "local", "nil", "not", "or", "repeat", "return", "then", "true", "until", "while"})
    if (a.key == kw)
      throw bad("the key must be a Lua name, and '" + a.key + "' is one of Lua's reserved words (a script could not "
                "read it as beltsim.args." + a.key + ")");
  const std::string& v = a.text;
  if (v == "true" || v == "false") {
    a.value = v == "true";
  } else if (v.size() >= 2 && v.front() == '"' && v.back() == '"') {
    a.value = v.substr(1, v.size() - 2);
  } else if (!v.empty() && (std::isdigit(static_cast<unsigned char>(v[0])) || v[0] == '+' || v[0] == '-' || v[0] == '.')) {
    const auto x = decimal(v);
    if (!x)
      throw bad("a value that starts like a number must be a finite decimal number (120, -0.3, 1e-3); hexadecimal, "
                "inf, nan and units are not read (quote it, \"...\", for a string)");
    long long i = 0;
    const size_t from = v[0] == '+' ? 1 : 0;
    const auto r = std::from_chars(v.data() + from, v.data() + v.size(), i);
    if (r.ec == std::errc() && r.ptr == v.data() + v.size())
      a.value = i;
    else
      a.value = *x;
  } else {
    a.value = v;
  }
  return a;
}

std::vector<ScriptArg> parse_sets(const std::vector<std::string>& kvs) {
  std::vector<ScriptArg> out;
  for (const std::string& kv : kvs) {
    ScriptArg a = parse_set(kv);
    for (const ScriptArg& b : out)
      if (b.key == a.key)
        throw std::invalid_argument("--set " + kv + ": " + a.key + " is set twice (also --set " + b.key + "=" + b.text + ")");
    out.push_back(std::move(a));
  }
  return out;
}

}  // namespace beltsim::script
