// `beltsim compare A B`: two PNGs by the golden images' metric (media/image_compare.hpp), or two CSV
// files column by column (plot/csv_compare.hpp). One line on stdout says why they match or
// differ; exit status 0 when they match, 1 when they differ, 2 for bad usage or a file that
// cannot be read (the message names it).
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace beltsim::app {

struct CompareOptions {
  std::string a, b;
  std::optional<std::string> tol, max_bad, diff;  // PNGs
  std::vector<std::string> mask;                  // PNGs: X,Y,W,H [px] left out
  bool ignore_text = false;                       // PNGs: the frames' text boxes left out
  std::optional<std::string> rtol;                // CSVs
  std::vector<std::string> atol;                  // CSVs: A (every column) or UNIT=A
  std::vector<std::string> col_tol;               // CSVs: NAME=RTOL[,ATOL]
  bool failing = false;                           // CSVs: a line for each failing column
  std::vector<std::string> skip;                  // CSVs: columns left out
  bool partial = false;                           // CSVs: A may span a part of B's times
};

int cmd_compare(const CompareOptions& o);

}  // namespace beltsim::app
