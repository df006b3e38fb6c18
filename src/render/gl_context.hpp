// An OpenGL 3.3 core context without a window system, behind a small interface so that the
// renderer does not care who made it: OSMesa (libosmesa6; gone from Mesa 25.1) or EGL
// on the surfaceless platform (EGL_PLATFORM_SURFACELESS_MESA). The renderer draws into its own
// framebuffer object either way. One thread per context; the context is current on the thread
// that created it.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>

namespace beltsim::render {

enum class GlBackend { osmesa, egl };

class GlContext {
 public:
  virtual ~GlContext() = default;
  // address of a GL function (core or extension), null when absent
  virtual void* proc(const char* name) const = 0;
  virtual void make_current() = 0;
  virtual GlBackend backend() const = 0;
};

// Creates a core-profile context of at least OpenGL major.minor (the renderer needs 3.3). Throws
// std::runtime_error with a message that names the backend, the step that failed and what to
// install or set.
std::unique_ptr<GlContext> make_gl_context(GlBackend backend, int major = 3, int minor = 3);
// the backend of the renderers this process makes: osmesa unless the program's edge set another
// (src/app: BELTSIM_GL)
GlBackend default_gl_backend();
void set_default_gl_backend(GlBackend b);
// "osmesa" (or "") and "egl"; nullopt for another name
std::optional<GlBackend> gl_backend_named(std::string_view name);
const char* backend_name(GlBackend b);

// how many contexts this process has created (a run without frames creates none: tested)
long gl_contexts_created();

}  // namespace beltsim::render
