// Runs Debian's gnuplot (package gnuplot-nox) on a script, without a shell: the script goes to a
// private temporary file whose path is gnuplot's only argument (posix_spawnp with an argv), so no
// path or title can be read as shell syntax. Strings inside the script must still be gnuplot
// literals: gnuplot_string() makes one that holds any text (quotes, spaces, backslashes).
#pragma once

#include <string>
#include <string_view>

namespace beltsim::plot {

// Runs `gnuplot SCRIPTFILE` with stdin from /dev/null and waits for it. Returns what gnuplot
// printed on stdout and stderr (its warnings) when it exits with status 0. Throws
// std::runtime_error: "gnuplot not found ..." when it is not installed, "gnuplot failed (exit
// N): <its output>" when the script fails.
std::string run_gnuplot(const std::string& script);

// A gnuplot string literal holding `text` as it is: single quotes, in which gnuplot processes
// no escapes, with each ' doubled; line breaks become spaces (a literal is one line).
std::string gnuplot_string(std::string_view text);

}  // namespace beltsim::plot
