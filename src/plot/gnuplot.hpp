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

// A picture gnuplot draws into a private folder of its own (mkdtemp: only this user can enter it)
// and that is then written whole to its destination (io/output_dir.hpp), so gnuplot never opens a
// path in an output folder, where a planted link could send its output elsewhere.
class PrivateOutput {
 public:
  PrivateOutput();  // throws std::runtime_error when the folder cannot be made
  ~PrivateOutput();  // the folder and what is in it removed
  PrivateOutput(const PrivateOutput&) = delete;
  PrivateOutput& operator=(const PrivateOutput&) = delete;
  // where gnuplot writes (its `set output`)
  const std::string& path() const { return file_; }
  // what gnuplot wrote, written whole to dest (its missing folders made); throws "WHO: gnuplot reported no error but
  // wrote no DEST" when it wrote nothing, "cannot write DEST: reason" when dest cannot be written
  void deliver(const std::string& dest, const std::string& who) const;

 private:
  std::string dir_, file_;
};

// The lines' colours of every plot, in order (Tableau's ten: dark enough on white, where gnuplot's
// own fifth, #f0e442, is a yellow a reader hardly sees), and the gnuplot lines that give the
// linetypes 1..10 these colours
extern const char* const kLineColours[10];
std::string line_colours_script();

// A gnuplot string literal holding `text` as it is: single quotes, in which gnuplot processes
// no escapes, with each ' doubled; line breaks become spaces (a literal is one line).
std::string gnuplot_string(std::string_view text);

}  // namespace beltsim::plot
