// What defines a sweep point's result besides its parameters (docs/sweeps.md, "Resuming"): the
// program, the command's options that change results, and every script file the point loaded
// (the sweep file and what it loaded with dofile, loadfile and require), each with the SHA-256 of
// its bytes. A point records them in its point.csv (the column `inputs`, sweep/results.hpp); a
// resumed sweep counts a point done only when each is as it is now, and says what changed
// otherwise.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace beltsim::sweep {

struct Inputs {
  std::string program;                                     // program_identity()
  std::string options;                                     // the options as typed that change results ("" for none)
  std::vector<std::pair<std::string, std::string>> files;  // absolute path, SHA-256 (hex)
};

// as point.csv holds it, a line each: "program: ...", "options: ...", then "file SHA256 PATH"
std::string inputs_text(const Inputs& in);
// nullopt when text is not in that form
std::optional<Inputs> parse_inputs(const std::string& text);

// the path of the executable running now (/proc/self/exe)
std::string this_program();
// "beltsim VERSION, executable SHA256": a rebuilt program is another program
std::string program_identity();

// what defines a point now, bar its files (read as needed, once each)
struct Definition {
  std::string program, options;
  std::map<std::string, std::string> hashes;  // path -> SHA-256 now ("" when unreadable)
  // the sweep file (the quick form's script) as a point records it, its first file: absolute,
  // lexically normal; "" when not checked. A point run from another file (not the same one by
  // another path) is not this sweep's, whatever the files it loaded hash to now
  std::string sweep_file;
};

// "" when recorded is what defines the point now, else why not, one phrase for a message:
// "the file /a/b.lua has changed", "the program has changed (was ...)", "the sweep file has
// changed (was /a/grid.lua, now /b/grid.lua)"
std::string changed_inputs(const std::string& recorded, Definition& now);
// the same file: the same path, or two paths to one file (std::filesystem::equivalent)
bool same_file(const std::string& a, const std::string& b);

}  // namespace beltsim::sweep
