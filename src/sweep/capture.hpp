// A program run to its end with its standard output and error read (sbatch for the Slurm jobs).
#pragma once

#include <string>
#include <vector>

namespace beltsim::sweep {

struct Captured {
  std::string out, err;  // all it wrote to each, read as it comes so that neither pipe fills
  int status = 0;        // its exit status; 128 + N when signal N killed it; 127 when it cannot be run
};

// args[0] found on PATH (no shell), its standard input /dev/null; throws std::runtime_error when
// no process can be made
Captured run_capture(const std::vector<std::string>& args);

}  // namespace beltsim::sweep
