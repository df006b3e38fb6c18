// A program run to its end with its standard output and error read (sbatch for the Slurm jobs),
// within a time and an output bound.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace beltsim::sweep {

struct CaptureLimits {
  double seconds = 0;         // past it the program and its process group are killed (SIGKILL); 0: none
  std::size_t max_bytes = 0;  // of each stream; past it the same; 0: none
};

struct Captured {
  std::string out, err;     // what it wrote to each (up to max_bytes), read as it comes so that neither pipe fills
  int status = 0;           // its exit status; 128 + N when signal N killed it; 127 when it cannot be run
  bool timed_out = false;   // killed for running past limits.seconds
  bool overflowed = false;  // killed for writing past limits.max_bytes on a stream
};

// args[0] found on PATH (no shell), its standard input /dev/null, in a process group of its own
// (so that a limit ends the children it started too); throws std::runtime_error when no process
// can be made
Captured run_capture(const std::vector<std::string>& args, const CaptureLimits& limits = {});

}  // namespace beltsim::sweep
