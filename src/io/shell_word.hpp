#pragma once

#include <string>

namespace beltsim {

// s as one word of a POSIX shell command line: as it is when it holds only characters no shell
// treats specially, else in single quotes ('\'' for a quote); with a control character (a
// newline would end session.lua's comment line) as bash's $'...' with escapes. For a command a
// message prints for the user to copy: session.lua's replay line, plot's example
std::string shell_word(const std::string& s);

}  // namespace beltsim
