#include "term/term_image.hpp"

#include <chafa.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string_view>

#include "media/png_writer.hpp"

extern char** environ;

namespace beltsim::term {

namespace {

using Mode = ImageMode;

bool fail(std::string* why_not, const std::string& why) {
  if (why_not) *why_not = why;
  return false;
}

// chafa's reference-counted objects released on every path out
struct TermInfo {
  ChafaTermInfo* p = nullptr;
  ~TermInfo() {
    if (p) chafa_term_info_unref(p);
  }
};
struct Config {
  ChafaCanvasConfig* p = chafa_canvas_config_new();
  ~Config() { chafa_canvas_config_unref(p); }
};
struct SymbolMap {
  ChafaSymbolMap* p = chafa_symbol_map_new();
  ~SymbolMap() { chafa_symbol_map_unref(p); }
};
struct Canvas {
  ChafaCanvas* p = nullptr;
  ~Canvas() {
    if (p) chafa_canvas_unref(p);
  }
};

}  // namespace

std::optional<ImageMode> image_mode(std::string_view v) {
  if (v.empty()) return ImageMode::automatic;
  if (v == "off") return ImageMode::off;
  if (v == "symbols") return ImageMode::symbols;
  if (v == "sixel") return ImageMode::sixel;
  if (v == "kitty") return ImageMode::kitty;
  if (v == "iterm") return ImageMode::iterm;
  return std::nullopt;
}

bool show_image_in_terminal(const std::string& png, std::FILE* out, ImageMode mode, std::string* why_not,
                            CellSize size) {
  // the mode: forced by the caller (BELTSIM_TERM_IMAGES), or chosen below from what the terminal supports
  if (mode == Mode::off) return fail(why_not, "pictures are off (BELTSIM_TERM_IMAGES=off)");
  if (!out) return fail(why_not, "no output stream");
  const int fd = ::fileno(out);
  const bool tty = fd >= 0 && ::isatty(fd);
  if (mode == Mode::automatic) {
    if (!tty) return fail(why_not, "the output is not a terminal");
    const char* term = std::getenv("TERM");
    if (!term || !*term || std::strcmp(term, "dumb") == 0)
      return fail(why_not, std::string("the terminal (TERM=") + (term ? term : "") + ") shows no colours");
  }

  Image img;
  try {
    img = read_png(png);
  } catch (const std::exception& e) {
    return fail(why_not, e.what());
  }

  TermInfo info{chafa_term_db_detect(chafa_term_db_get_default(), environ)};
  if (!info.p) return fail(why_not, "chafa cannot describe this terminal");
  if (mode == Mode::automatic) {
    if (chafa_term_info_have_seq(info.p, CHAFA_TERM_SEQ_BEGIN_KITTY_IMMEDIATE_IMAGE_V1)) mode = Mode::kitty;
    else if (chafa_term_info_have_seq(info.p, CHAFA_TERM_SEQ_BEGIN_ITERM2_IMAGE)) mode = Mode::iterm;
    else if (chafa_term_info_have_seq(info.p, CHAFA_TERM_SEQ_BEGIN_SIXELS)) mode = Mode::sixel;
    else mode = Mode::symbols;
  } else {
    // a forced mode needs its sequences even where the environment names another terminal
    TermInfo fallback{chafa_term_db_get_fallback_info(chafa_term_db_get_default())};
    chafa_term_info_supplement(info.p, fallback.p);
  }

  // the terminal's size in cells and, when it tells, in pixels (for the cells' aspect ratio)
  winsize ws{};
  const bool known = tty && ::ioctl(fd, TIOCGWINSZ, &ws) == 0 && ws.ws_col > 0 && ws.ws_row > 0;
  int cell_w = 10, cell_h = 20;  // [pixels] typical, when the terminal does not say
  if (known && ws.ws_xpixel > 0 && ws.ws_ypixel > 0) {
    cell_w = std::max(1, ws.ws_xpixel / ws.ws_col);
    cell_h = std::max(1, ws.ws_ypixel / ws.ws_row);
  }
  int cols = size.columns > 0 ? size.columns : known ? ws.ws_col : 80;
  int rows = size.rows > 0 ? size.rows : known && ws.ws_row > 2 ? ws.ws_row - 1 : -1;
  const bool exact = size.columns > 0 && size.rows > 0;
  chafa_calc_canvas_geometry(img.width, img.height, &cols, &rows, static_cast<float>(cell_w) / cell_h, TRUE,
                             exact ? TRUE : FALSE);
  if (cols <= 0 || rows <= 0) return fail(why_not, "chafa found no room for the picture");

  Config config;
  chafa_canvas_config_set_geometry(config.p, cols, rows);
  chafa_canvas_config_set_cell_geometry(config.p, cell_w, cell_h);
  switch (mode) {
    case Mode::sixel: chafa_canvas_config_set_pixel_mode(config.p, CHAFA_PIXEL_MODE_SIXELS); break;
    case Mode::kitty: chafa_canvas_config_set_pixel_mode(config.p, CHAFA_PIXEL_MODE_KITTY); break;
    case Mode::iterm: chafa_canvas_config_set_pixel_mode(config.p, CHAFA_PIXEL_MODE_ITERM2); break;
    default: {
      chafa_canvas_config_set_pixel_mode(config.p, CHAFA_PIXEL_MODE_SYMBOLS);
      ChafaCanvasMode cm = CHAFA_CANVAS_MODE_FGBG;
      if (chafa_term_info_have_seq(info.p, CHAFA_TERM_SEQ_SET_COLOR_FGBG_DIRECT)) cm = CHAFA_CANVAS_MODE_TRUECOLOR;
      else if (chafa_term_info_have_seq(info.p, CHAFA_TERM_SEQ_SET_COLOR_FGBG_256)) cm = CHAFA_CANVAS_MODE_INDEXED_256;
      else if (chafa_term_info_have_seq(info.p, CHAFA_TERM_SEQ_SET_COLOR_FGBG_16)) cm = CHAFA_CANVAS_MODE_INDEXED_16;
      chafa_canvas_config_set_canvas_mode(config.p, cm);
      // block elements (half, quarter and eighth blocks) and the space: drawn alike by every font
      SymbolMap symbols;
      chafa_symbol_map_add_by_tags(symbols.p, static_cast<ChafaSymbolTags>(CHAFA_SYMBOL_TAG_BLOCK | CHAFA_SYMBOL_TAG_SPACE));
      chafa_canvas_config_set_symbol_map(config.p, symbols.p);
      break;
    }
  }
  Canvas canvas{chafa_canvas_new(config.p)};
  if (!canvas.p) return fail(why_not, "chafa cannot make a canvas of " + std::to_string(cols) + "x" + std::to_string(rows));
  chafa_canvas_draw_all_pixels(canvas.p, CHAFA_PIXEL_RGB8, img.rgb.data(), img.width, img.height, 3 * img.width);
  GString* text = chafa_canvas_print(canvas.p, info.p);
  if (!text) return fail(why_not, "chafa printed nothing");
  std::string s(text->str, text->len);
  g_string_free(text, TRUE);
  if (s.empty()) return fail(why_not, "chafa printed nothing");
  if (s.back() != '\n') s += '\n';
  if (std::fwrite(s.data(), 1, s.size(), out) != s.size() || std::fflush(out) != 0)
    return fail(why_not, std::string("cannot write to the terminal: ") + std::strerror(errno));
  return true;
}

}  // namespace beltsim::term
