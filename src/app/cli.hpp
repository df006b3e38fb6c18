// The command line (CLI11, in cli.cpp alone: its header-only library is the costliest header the
// project compiles). parse_command_line reads argv into the options as typed; main runs the command.
//   beltsim run     SCRIPT [--out DIR] [--t-end T] [--integrator NAME] [--rtol R] [--max-wall S]
//                          [--no-frames] [--set KEY=VALUE]... [SAFETY]
//   beltsim wp      SCRIPT [--out DIR] [--t-end T] [--integrators A,B] [--rtols R1,R2] [--ref-rtol R]
//                          [--wall-limit S] [--set KEY=VALUE]... [SAFETY]
//   beltsim plot    CSV|DIR [COLUMNS...] [--out PNG] [--from T]
//   beltsim sweep   FILE [--out DIR] [--jobs N] [--point K] [--list] [--collect] [--set KEY=V1,V2,..]...
//                        [--slurm [--submit] [--partition P] [--time T] [--max-parallel M]] [SAFETY]
//   beltsim render  STATE... [--out PNG|DIR] [--video MP4] [--quantity Q] [--size WxH] [--view X,Y,W] [--magnify M]
//                           [--range LO,HI]
//   beltsim compare A B [--tol L] [--max-bad N] [--diff PNG] [--rtol R] [--atol A] [--col-tol NAME=R[,A]]...
//   beltsim console [SCRIPT] [--out DIR] [--t-end T] [--integrator NAME] [--rtol R] [--max-wall S]
//                            [--no-frames] [--set KEY=VALUE]... [SAFETY] [-- ARGS...]
//   beltsim help parameters
//   SAFETY: [--trusted] [--max-instructions N] [--max-lua-memory MiB] [--max-lua-wall S] [--max-lua-cpu S]
//           (docs/limits-and-safety.md)
// An option a command does not take is an error.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "app/compare.hpp"
#include "app/options.hpp"
#include "app/render_cmd.hpp"

namespace beltsim::app {

struct CommandLine {
  std::string command;  // run, wp, plot, summary, render, compare, console, sweep or help-parameters
  Raw raw;
  std::string script, csv;                  // run, wp, sweep: the file; plot: the CSV; summary: the folder
  std::optional<std::string> console_script;
  std::vector<std::string> columns;         // plot
  std::vector<std::string> console_args;    // console: the words after --
  RenderOptions render;
  CompareOptions compare;
};

// The command line read; std::nullopt when the program is to exit at once with *status (the help
// or the version printed: 0; bad usage, its message printed on stderr: 2).
std::optional<CommandLine> parse_command_line(int argc, char** argv, int* status);

}  // namespace beltsim::app
