// The GL backend: draws a DrawList with OpenGL 3.3 core into a framebuffer object and reads it
// back as an Image. Edges are antialiased analytically (draw_list.hpp, shaders/solid.frag);
// MSAA (samples > 1) is available on top but costs 3× per frame on llvmpipe. It does not create
// the context (gl_context.hpp does); it loads the GL functions it uses through the context.
// Only src/render includes GL headers.
#pragma once

#include <memory>
#include <string>

#include "media/image.hpp"
#include "render/draw_list.hpp"
#include "render/gl_context.hpp"

namespace beltsim::render {

class GlRenderer {
 public:
  // Throws std::runtime_error when a function is missing, a shader fails to compile or the
  // framebuffer is incomplete.
  GlRenderer(GlContext& ctx, int width, int height, int samples = 0);
  ~GlRenderer();
  GlRenderer(const GlRenderer&) = delete;
  GlRenderer& operator=(const GlRenderer&) = delete;

  // draws the list (its size must match) and reads the image back, top row first
  void render(const DrawList& list, Image& out);
  // GL_RENDERER and GL_VERSION, e.g. "llvmpipe (LLVM 15.0.6, 256 bits)" and "4.5 (Core Profile) Mesa 22.3.6"
  std::string gl_renderer() const;
  std::string gl_version() const;
  int width() const;
  int height() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// the embedded GLSL source of shaders/NAME (generated at build time from the shaders/ folder)
const char* shader_source(const std::string& name);

}  // namespace beltsim::render
