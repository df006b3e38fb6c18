// Script parameters from the command line (docs/cli.md, "Script parameters"): `--set KEY=VALUE`, read by the
// script as beltsim.args.KEY. Lua-free: the command line parses them, the bindings hand them out.
//
// KEY is a Lua name ([A-Za-z_][A-Za-z0-9_]*). VALUE is read as
//   true, false            a boolean
//   "text"                 a string (the quotes removed; a way to pass text that looks numeric)
//   a finite decimal       an integer when it is one (120, -3), else a float (0.3, 1e-3, 2.)
//   anything else          a string (esdirk32, wet)
// and a value that starts like a number (a digit, a sign or a dot) must be a whole finite decimal:
// "0x10", "1e", "2s", "-inf" and "+nan" are errors, not strings (a typo of a number is caught here,
// not three calls later as a type error); "inf" and "nan" start like words and are strings.
#pragma once

#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "sweep/points.hpp"

namespace beltsim::script {

struct ScriptArg {
  std::string key;
  std::string text;  // the value as typed
  std::variant<long long, double, bool, std::string> value;
};

// a finite decimal number, nothing before or after it: "0x10", "inf", "nan", "1e" and "2s" fail
std::optional<double> decimal(const std::string& s);
// one "KEY=VALUE"; throws std::invalid_argument("--set KEY=VALUE: why")
ScriptArg parse_set(const std::string& key_value);
// all of them; a key given twice is an error too
std::vector<ScriptArg> parse_sets(const std::vector<std::string>& key_values);
// the quick form of `beltsim sweep` (docs/sweeps.md): each --set KEY=V1,V2,.. a parameter of the
// grid, crossed in the order given (the first varies slowest), each value read as parse_set reads
// one; an item that starts with " runs to the next " followed by a comma or the list's end, commas
// and all. Throws std::invalid_argument naming the --set.
sweep::Grid set_grid(const std::vector<std::string>& sets);

}  // namespace beltsim::script
