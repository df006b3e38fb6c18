#include "script/script_args.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
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

namespace {

// the items of the list V1,V2,.. of --set kv, split at its commas; an item that starts with "
// runs to the next " followed by a comma or the list's end, commas and all (--set reads "..." as a
// string)
std::vector<std::string> list_items(const std::string& kv, const std::string& list) {
  std::vector<std::string> items;
  for (std::size_t from = 0;;) {
    std::size_t end = list.find(',', from);
    if (from < list.size() && list[from] == '"') {
      end = from;
      do {
        end = list.find('"', end + 1);
        if (end == std::string::npos)
          throw std::invalid_argument("--set " + kv +
                                      ": a value that opens a quote (\") must close it before a comma or the end");
      } while (end + 1 < list.size() && list[end + 1] != ',');
      ++end;
    }
    if (end == std::string::npos) end = list.size();
    items.push_back(list.substr(from, end - from));
    if (end == list.size()) return items;
    from = end + 1;
  }
}

}  // namespace

sweep::Grid set_grid(const std::vector<std::string>& sets) {
  sweep::Grid g;
  for (const std::string& kv : sets) {
    const std::size_t eq = kv.find('=');
    if (eq == std::string::npos) throw std::invalid_argument("--set " + kv + ": KEY=V1,V2,.. expected");
    const std::string key = kv.substr(0, eq), list = kv.substr(eq + 1);
    if (std::find(g.names.begin(), g.names.end(), key) != g.names.end())
      throw std::invalid_argument("--set " + key + " is given twice; give its values in one list: --set " + key +
                                  "=V1,V2,..");
    if (sweep::reserved_name(key))
      throw std::invalid_argument("--set " + kv + ": a parameter may not be named '" + key +
                                  "': point.csv has a column of that name; give it another");
    std::vector<sweep::Value> values;
    for (const std::string& item : list_items(kv, list)) {
      // (a typo, 300,,500: a point with an empty string failed when its run read the value)
      if (item.empty())
        throw std::invalid_argument("--set " + kv + ": an empty value in the list (write \"\" for an empty string)");
      try {
        const ScriptArg a = parse_set(key + "=" + item);
        std::visit([&](const auto& x) { values.emplace_back(x); }, a.value);
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(std::string(e.what()) + " (in --set " + kv + ")");
      }
    }
    g.names.push_back(key);
    g.values.push_back(std::move(values));
  }
  return g;
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
