// Pictures of a drive's mode shapes (sim/modes.hpp, docs/modes.md): each mode drawn by the frame
// renderer at its largest deflection, as a PNG, and on request as a short video of its cycles.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "sim/modes.hpp"

namespace beltsim::render {

struct ModePictures {
  std::string dir;          // where the files go (made when missing, never through a link)
  int count = 6;            // the first `count` modes of the analysis
  bool video = false;       // also a video of each: three cycles, 24 frames each, at 24 frames/s
  double amplitude = 0.03;  // the largest point displacement drawn, as a share of the layout's size
  int width = 1280, height = 720;
};

// each pulley's line of a mode's picture: its rim's (and an arm's centre's) share of the mode's
// largest point displacement and phase ("driver: rim 0.420 at +180°")
std::vector<std::string> mode_pulley_lines(const Model& model, const Mode& m);

// the still's note on how far its colours reach ("colours here within ±0.40"),
// empty where they reach 0.95 or more: at_still, each element's tension change at the still's
// phase on the scale of −1 to 1 (the largest over the cycle)
std::string still_reach_text(const std::vector<double>& at_still);

// Draws the modes of `a` (analysed at the state y of the drive d) into DIR/mode_NN_<f>Hz.png (NN
// from 01, the mode's number in modes.csv; f its frequency) and the videos asked for (.mp4 beside
// them), after removing DIR's files of those names (an earlier analysis's: remove_numbered,
// io/output_dir.hpp); returns the paths written. The belt is coloured by the mode's change of
// tension (which spans stretch, which slacken: linearised, over the largest in its cycle, on a
// scale from −1 to 1). Throws std::runtime_error (the renderer's, the writers', naming the file).
std::vector<std::string> draw_modes(const Scene& sc, const Drive& d, const Eigen::VectorXd& y, const ModeAnalysis& a,
                                    const ModePictures& p);

}  // namespace beltsim::render
