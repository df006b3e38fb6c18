// The environment variables beltsim reads, in one place at the program's edge; what they say is
// passed down as settings (nothing below src/app reads the environment for itself):
//   BELTSIM_GL           the renderer's GL context: osmesa (default) or egl
//   BELTSIM_FONT         the frames' font, a .ttf file (default: DejaVu Sans, found at build time)
//   BELTSIM_TERM_IMAGES  pictures in the terminal: off, symbols, sixel, kitty or iterm (default:
//                        what the terminal supports, nothing when the output is not a terminal)
//   BELTSIM_HISTORY      the console's history file (default ~/.beltsim_history)
#pragma once

#include <string>

#include "render/gl_context.hpp"
#include "term/term_image.hpp"

namespace beltsim::app {

struct Environment {
  render::GlBackend gl = render::GlBackend::osmesa;
  std::string font;  // "": the built-in one
  term::ImageMode images = term::ImageMode::automatic;
  std::string history;
};

// throws std::invalid_argument naming the variable, its value and the values it takes
Environment read_environment();
// makes the renderers of this process use the GL backend and font asked for
void apply_render_settings(const Environment& env);

}  // namespace beltsim::app
