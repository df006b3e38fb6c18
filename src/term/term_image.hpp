// A PNG shown in the terminal, through chafa (Debian's libchafa-dev): as a real image where the
// terminal can show one (kitty graphics, iTerm2 inline images, sixel), else as coloured Unicode
// block symbols (truecolor, 256 or 16 colours, whatever the terminal takes).
//
// The terminal is recognised from the environment (TERM, COLORTERM, TERM_PROGRAM, KITTY_WINDOW_ID,
// ... by chafa_term_db_detect; nothing is asked of the terminal itself). The picture is as wide as
// the terminal (TIOCGWINSZ on `out`, 80 columns when that fails), as high as its aspect ratio
// needs, at most the terminal's height less one row.
//
// The caller may force the choice (ImageMode; the command line reads it from BELTSIM_TERM_IMAGES):
//   off      never show pictures
//   symbols  Unicode blocks in truecolor
//   sixel    DEC sixel graphics (ESC P ... q ... ESC \)
//   kitty    the kitty graphics protocol
//   iterm    iTerm2's inline images
// A forced mode writes even when `out` is not a terminal (a pipe, a file), so it can be tested or
// passed through; unset or empty, nothing is written unless `out` is a terminal.
#pragma once

#include <cstdio>
#include <optional>
#include <string>
#include <string_view>

namespace beltsim::term {

// in character cells; 0 = from the terminal (columns) and the image's aspect (rows). Both set:
// the picture fills exactly that many cells.
struct CellSize {
  int columns = 0, rows = 0;
};

enum class ImageMode { automatic, off, symbols, sixel, kitty, iterm };
// the mode named by one of the words above ("" is automatic), or nullopt for another word
std::optional<ImageMode> image_mode(std::string_view word);

// Writes the picture to `out` and returns true; returns false with the reason in *why_not (when
// not null) and writes nothing when out is not a terminal (and no mode is forced), the terminal
// is "dumb", the mode is off, the PNG cannot be read, or chafa fails.
bool show_image_in_terminal(const std::string& png, std::FILE* out, ImageMode mode, std::string* why_not,
                            CellSize size = {});

}  // namespace beltsim::term
