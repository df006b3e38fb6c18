#include "render/gl_context.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/osmesa.h>

#include <atomic>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <vector>

#include "media/shared_library.hpp"

namespace beltsim::render {

namespace {

std::atomic<long> g_contexts{0};

// the functions of OSMesa and EGL used here, from their libraries opened at the first context
// (media/shared_library.hpp: not linked, so that a run without frames does not load Mesa)
// clang-format off
#define BELTSIM_OSMESA_FUNCTIONS(X)                                                                       \
  X(OSMesaCreateContextAttribs) X(OSMesaDestroyContext) X(OSMesaGetProcAddress) X(OSMesaMakeCurrent)
#define BELTSIM_EGL_FUNCTIONS(X)                                                                          \
  X(eglGetProcAddress) X(eglGetError) X(eglInitialize) X(eglBindAPI) X(eglChooseConfig)                   \
  X(eglCreateContext) X(eglMakeCurrent) X(eglDestroyContext) X(eglTerminate)
// clang-format on

struct OsMesaApi {
  BELTSIM_OSMESA_FUNCTIONS(BELTSIM_SHARED_DECLARE)
  OsMesaApi() {
    const char* soname = "libOSMesa.so.8";
    void* library = open_shared_library(soname, "libosmesa6");
    BELTSIM_OSMESA_FUNCTIONS(BELTSIM_SHARED_LOAD)
  }
};

struct EglApi {
  BELTSIM_EGL_FUNCTIONS(BELTSIM_SHARED_DECLARE)
  EglApi() {
    const char* soname = "libEGL.so.1";
    void* library = open_shared_library(soname, "libegl1");
    BELTSIM_EGL_FUNCTIONS(BELTSIM_SHARED_LOAD)
  }
};


// opened once, on the first call (a failure throws, and the next call tries again)
const OsMesaApi& osmesa() {
  static const OsMesaApi api;
  return api;
}
const EglApi& egl() {
  static const EglApi api;
  return api;
}

class OsMesaContext final : public GlContext {
 public:
  OsMesaContext(int major, int minor) {
    const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA, OSMESA_DEPTH_BITS, 0, OSMESA_STENCIL_BITS, 0,
                           OSMESA_ACCUM_BITS, 0, OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                           OSMESA_CONTEXT_MAJOR_VERSION, major, OSMESA_CONTEXT_MINOR_VERSION, minor, 0};
    ctx_ = osmesa().OSMesaCreateContextAttribs(attribs, nullptr);
    if (!ctx_)
      throw std::runtime_error("cannot create an OpenGL " + std::to_string(major) + "." + std::to_string(minor) +
                               " core context with OSMesa (OSMesaCreateContextAttribs failed; Debian package "
                               "libosmesa6, Mesa's llvmpipe; try BELTSIM_GL=egl)");
    // the renderer draws into its own framebuffer object: the window-system buffer stays tiny
    buffer_.resize(16 * 16 * 4);
    make_current();
    g_contexts++;
  }
  ~OsMesaContext() override { osmesa().OSMesaDestroyContext(ctx_); }
  void* proc(const char* name) const override { return reinterpret_cast<void*>(osmesa().OSMesaGetProcAddress(name)); }
  void make_current() override {
    if (!osmesa().OSMesaMakeCurrent(ctx_, buffer_.data(), GL_UNSIGNED_BYTE, 16, 16))
      throw std::runtime_error("OSMesaMakeCurrent failed");
  }
  GlBackend backend() const override { return GlBackend::osmesa; }

 private:
  OSMesaContext ctx_ = nullptr;
  std::vector<unsigned char> buffer_;
};

class EglContext final : public GlContext {
 public:
  EglContext(int major, int minor) {
    auto fail = [&](const std::string& step) {
      throw std::runtime_error("cannot create an OpenGL " + std::to_string(major) + "." + std::to_string(minor) +
                               " core context with EGL (surfaceless Mesa platform): " + step + " failed (EGL error 0x" +
                               hex(egl().eglGetError()) +
                               "; Debian packages libegl1, libegl-mesa0, libgl1-mesa-dri; try BELTSIM_GL=osmesa)");
    };
    auto get_display =
        reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(egl().eglGetProcAddress("eglGetPlatformDisplayEXT"));
    if (!get_display) fail("eglGetPlatformDisplayEXT");
    dpy_ = get_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (dpy_ == EGL_NO_DISPLAY) fail("eglGetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA)");
    EGLint egl_major = 0, egl_minor = 0;
    if (!egl().eglInitialize(dpy_, &egl_major, &egl_minor)) fail("eglInitialize");
    if (!egl().eglBindAPI(EGL_OPENGL_API)) fail("eglBindAPI(EGL_OPENGL_API)");
    const EGLint cfg_attr[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_NONE};
    EGLConfig cfg = nullptr;
    EGLint n = 0;
    if (!egl().eglChooseConfig(dpy_, cfg_attr, &cfg, 1, &n) || n < 1) fail("eglChooseConfig");
    const EGLint ctx_attr[] = {EGL_CONTEXT_MAJOR_VERSION, major, EGL_CONTEXT_MINOR_VERSION, minor,
                               EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT, EGL_NONE};
    ctx_ = egl().eglCreateContext(dpy_, cfg, EGL_NO_CONTEXT, ctx_attr);
    if (ctx_ == EGL_NO_CONTEXT) fail("eglCreateContext");
    make_current();
    g_contexts++;
  }
  ~EglContext() override {
    egl().eglMakeCurrent(dpy_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
    egl().eglDestroyContext(dpy_, ctx_);
    egl().eglTerminate(dpy_);
  }
  void* proc(const char* name) const override { return reinterpret_cast<void*>(egl().eglGetProcAddress(name)); }
  void make_current() override {
    if (!egl().eglMakeCurrent(dpy_, EGL_NO_SURFACE, EGL_NO_SURFACE, ctx_))
      throw std::runtime_error("eglMakeCurrent (surfaceless) failed (EGL error 0x" + hex(egl().eglGetError()) + ")");
  }
  GlBackend backend() const override { return GlBackend::egl; }

 private:
  static std::string hex(EGLint v) {
    char b[16];
    std::snprintf(b, sizeof b, "%04x", static_cast<unsigned>(v));
    return b;
  }
  EGLDisplay dpy_ = EGL_NO_DISPLAY;
  EGLContext ctx_ = EGL_NO_CONTEXT;
};

}  // namespace

std::unique_ptr<GlContext> make_gl_context(GlBackend b, int major, int minor) {
  if (b == GlBackend::egl) return std::make_unique<EglContext>(major, minor);
  return std::make_unique<OsMesaContext>(major, minor);
}

namespace {
std::atomic<GlBackend> g_default_backend{GlBackend::osmesa};
}  // namespace

void set_default_gl_backend(GlBackend b) { g_default_backend.store(b); }
GlBackend default_gl_backend() { return g_default_backend.load(); }

std::optional<GlBackend> gl_backend_named(std::string_view name) {
  if (name.empty() || name == "osmesa") return GlBackend::osmesa;
  if (name == "egl") return GlBackend::egl;
  return std::nullopt;
}

const char* backend_name(GlBackend b) { return b == GlBackend::egl ? "EGL surfaceless" : "OSMesa"; }

long gl_contexts_created() { return g_contexts.load(); }

}  // namespace beltsim::render
