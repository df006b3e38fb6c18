// Suggestions for misspelt names (keys of scene and run tables, --set keys, method names, pulley
// and column names): the one place that decides which valid names are "close".
//
// Close means an optimal-string-alignment Damerau–Levenshtein distance (insertions, deletions,
// substitutions and transpositions of neighbours, each 1) of at most max(1, (n + 2) / 5) for a
// name of n characters (1 up to 7 characters, 2 up to 12, 3 up to 17): a slip of the finger per
// five characters, so "elemnts" finds "elements" while "mu" does not find "c1". When no name is
// that close, a name that is one whole word of a valid snake_case name is close to it too
// ("damping" finds axial_damping and bending_damping).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace beltsim {

std::size_t edit_distance(const std::string& a, const std::string& b);
// the valid names close to `name`, the closest first (ties in the order given)
std::vector<std::string> close_names(const std::string& name, const std::vector<std::string>& valid);
// " (did you mean 'x'?)", " (did you mean 'x' or 'y'?)", or "" when none is close
std::string did_you_mean(const std::string& name, const std::vector<std::string>& valid);
// "no pulley 'drivn' (did you mean 'driven'?); pulleys: driver, driven": `name` is none of `valid`,
// the `kind` of thing they are, said the same wherever such a name is looked up (the console's
// sim:set_torque and the live view's torque)
std::string no_such(const std::string& kind, const std::string& name, const std::vector<std::string>& valid);
// "a, b, c"
std::string join(const std::vector<std::string>& names, const std::string& sep = ", ");
// "a", "a and b", "a, b and c"
std::string and_list(const std::vector<std::string>& names);
// "a", "a or b", "a, b or c"
std::string or_list(const std::vector<std::string>& names);

}  // namespace beltsim
