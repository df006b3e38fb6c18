// A parameter's place in the scenario's tables, as an error carries it (scene/validate.hpp,
// ParameterError) to where it is reported: script/key_line.hpp finds the line the script wrote the
// key on from it, the message names it by path_text.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace beltsim {

struct KeyPath {
  std::string pulley;              // "driver" of "pulley 'driver'.radius"; empty when none
  std::vector<std::string> chain;  // {"belt", "sde", "k"}; list positions as digits ("2")
  bool empty() const { return pulley.empty() && chain.empty(); }
};

// the path as the messages spell it: "belt.sde.k", "pulley 'driver'.radius", "friction.segments[2].mu",
// "run.atol"
std::string path_text(const KeyPath& p);

// the path a text starts with, in path_text's spelling (also "pulley 2.radius", the second entry of
// `pulleys`, "spray 2.radius" and "friction.segments.2.mu"); an empty path when it starts with none.
// name_after_space: "pulley 'driver' inertia" is pulley 'driver'.inertia.
KeyPath parse_path(std::string_view text, bool name_after_space = true);

// the characters of a Lua name and a number, as parse_path and the script's key scan
// (script/key_line.cpp) read them: a name's first character, its others, a decimal digit; the end
// of the run of digits of s that starts at i
bool ident_start(char c);
bool ident_char(char c);
bool digit(char c);
size_t digits_end(std::string_view s, size_t i);

}  // namespace beltsim
