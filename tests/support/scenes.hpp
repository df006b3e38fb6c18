// The test scenes in Lua, one definition for every test that runs one.
//
// two_pulley: the scene of tests/support/two_pulley.lua (the Python tests read the same file,
// support/scenes.py), with what a test varies. Its text has 7 lines (8 with `extra`): a script's
// next line is line 8 (9), which the tests' expected messages name; with `belt_lines`, the belt's
// line 6 is those lines.
//
// automotive_text: tests/support/automotive.lua as a local function automotive(o), which makes the
// automotive drive's table (its keys there), for a script that follows it.
//
// runaway: the test scene with a frictionless belt, which leaves the driver free to spin up under
// 1e6 N·m (4e7 rad/s² on 0.025 kg·m²), past the runaway check (1e5 rad/s) after 2.5 ms; 7 lines.
#pragma once

#include <fstream>
#include <optional>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>

namespace beltsim::test {

// what a test varies; an empty string or 0 keeps the file's
struct TwoPulley {
  std::string assign;     // what the scene's value goes to (the file's: "local s = ")
  std::string driver;     // the driver's keys after its geometry
  std::string driven_at;  // the driven pulley's centre and radius
  std::string driven;     // the driven pulley's keys after its geometry
  int elements = 0;
  std::string belt;   // more keys of the belt table
  std::string extra;  // a line of more keys of the scene table
  // the lines that stand for the file's belt line (its table written out over several lines, a
  // belt made elsewhere, none: ""); the file's line when not set, and then `elements` and `belt`
  std::optional<std::string> belt_lines;
};

// the text of tests/support/NAME
inline std::string support_text(const std::string& name) {
  const std::string path = std::string(BELTSIM_SOURCE_DIR) + "/tests/support/" + name;
  std::ifstream f(path);
  std::stringstream ss;
  ss << f.rdbuf();
  if (!f) throw std::runtime_error(path + ": cannot read it");
  return ss.str();
}

// the file's lines from "local s = " on
inline const std::string& two_pulley_text() {
  static const std::string text = [] {
    const std::string t = support_text("two_pulley.lua");
    const size_t at = t.find("local s = ");
    if (at == std::string::npos) throw std::runtime_error("tests/support/two_pulley.lua: no line 'local s = '");
    return t.substr(at);
  }();
  return text;
}

inline std::string automotive_text() {
  return "local automotive = (function()\n" + support_text("automotive.lua") + "end)()\n";
}

// group `g` of the one match of `re` in s replaced by `with` (nothing when `with` is empty)
inline void replace_group(std::string& s, const char* re, int g, const std::string& with) {
  if (with.empty()) return;
  std::smatch m;
  if (!std::regex_search(s, m, std::regex(re))) throw std::runtime_error(std::string("two_pulley.lua: no ") + re);
  s.replace(static_cast<size_t>(m.position(g)), static_cast<size_t>(m.length(g)), with);
}

inline std::string two_pulley(const TwoPulley& p = {}) {
  std::string s = two_pulley_text();
  replace_group(s, "^(local s = )", 1, p.assign);
  replace_group(s, "name = 'driver', centre = \\{[^}]*\\}, radius = [^,]*, (.*) \\},", 1, p.driver);
  replace_group(s, "name = 'driven', (centre = \\{[^}]*\\}, radius = [^,]*), (.*) \\},", 2, p.driven);
  replace_group(s, "name = 'driven', (centre = \\{[^}]*\\}, radius = [^,]*),", 1, p.driven_at);
  replace_group(s, "elements = ([0-9]+)", 1, p.elements ? std::to_string(p.elements) : "");
  replace_group(s, "belt = \\{.*()\\s\\},", 1, p.belt.empty() ? "" : ", " + p.belt);
  replace_group(s, "\\n()\\}\\n$", 1, p.extra.empty() ? "" : "  " + p.extra + "\n");
  if (p.belt_lines) {
    std::smatch m;
    if (!std::regex_search(s, m, std::regex("\n(  belt = \\{.*\\},\n)")))
      throw std::runtime_error("two_pulley.lua: no belt line");
    s.replace(static_cast<size_t>(m.position(1)), static_cast<size_t>(m.length(1)), *p.belt_lines);
  }
  return s;
}

inline std::string runaway() {
  TwoPulley p;
  p.driver = "torque = 1e6", p.belt_lines = "  belt = { mu = 0 },\n";
  return two_pulley(p);
}

}  // namespace beltsim::test
