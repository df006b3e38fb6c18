#include "app/environment.hpp"

#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/suggest.hpp"
#include "render/text.hpp"

namespace beltsim::app {

namespace {

std::string variable(const char* name) {
  const char* v = std::getenv(name);
  return v ? v : "";
}

}  // namespace

Environment read_environment() {
  Environment env;
  const std::string gl = variable("BELTSIM_GL");
  const auto backend = render::gl_backend_named(gl);
  if (const std::vector<std::string> names{"osmesa", "egl"}; !backend)
    throw std::invalid_argument("BELTSIM_GL=" + gl + " is not one of " + join(names) + did_you_mean(gl, names));
  env.gl = *backend;
  env.font = variable("BELTSIM_FONT");
  const std::string images = variable("BELTSIM_TERM_IMAGES");
  const auto mode = term::image_mode(images);
  if (const std::vector<std::string> names{"off", "symbols", "sixel", "kitty", "iterm"}; !mode)
    throw std::invalid_argument("BELTSIM_TERM_IMAGES=" + images + " is not one of " + join(names) +
                                did_you_mean(images, names));
  env.images = *mode;
  env.history = variable("BELTSIM_HISTORY");
  if (env.history.empty()) {
    const std::string home = variable("HOME");
    env.history = home.empty() ? ".beltsim_history" : home + "/.beltsim_history";
  }
  return env;
}

void apply_render_settings(const Environment& env) {
  render::set_default_gl_backend(env.gl);
  render::Font::set_default_path(env.font);
}

}  // namespace beltsim::app
