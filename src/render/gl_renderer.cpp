#include "render/gl_renderer.hpp"

#include <GL/glcorearb.h>

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "render/text.hpp"

namespace beltsim::render {

// the GL functions used, loaded through the context (works the same for OSMesa and EGL)
#define BELTSIM_GL_FUNCTIONS(X)                                                                               \
  X(GETSTRING, GetString) X(GETERROR, GetError) X(VIEWPORT, Viewport) X(CLEARCOLOR, ClearColor) X(CLEAR, Clear) \
  X(ENABLE, Enable) X(DISABLE, Disable) X(BLENDFUNC, BlendFunc) X(GENFRAMEBUFFERS, GenFramebuffers)             \
  X(BINDFRAMEBUFFER, BindFramebuffer) X(FRAMEBUFFERRENDERBUFFER, FramebufferRenderbuffer)                       \
  X(CHECKFRAMEBUFFERSTATUS, CheckFramebufferStatus) X(GENRENDERBUFFERS, GenRenderbuffers)                       \
  X(BINDRENDERBUFFER, BindRenderbuffer) X(RENDERBUFFERSTORAGEMULTISAMPLE, RenderbufferStorageMultisample)       \
  X(RENDERBUFFERSTORAGE, RenderbufferStorage) X(BLITFRAMEBUFFER, BlitFramebuffer) X(READPIXELS, ReadPixels)     \
  X(PIXELSTOREI, PixelStorei) X(FINISH, Finish) X(CREATESHADER, CreateShader) X(SHADERSOURCE, ShaderSource)     \
  X(COMPILESHADER, CompileShader) X(GETSHADERIV, GetShaderiv) X(GETSHADERINFOLOG, GetShaderInfoLog)             \
  X(CREATEPROGRAM, CreateProgram) X(ATTACHSHADER, AttachShader) X(LINKPROGRAM, LinkProgram)                     \
  X(GETPROGRAMIV, GetProgramiv) X(GETPROGRAMINFOLOG, GetProgramInfoLog) X(USEPROGRAM, UseProgram)               \
  X(GETUNIFORMLOCATION, GetUniformLocation) X(UNIFORM2F, Uniform2f) X(UNIFORM1I, Uniform1i)                     \
  X(GENVERTEXARRAYS, GenVertexArrays) X(BINDVERTEXARRAY, BindVertexArray) X(GENBUFFERS, GenBuffers)             \
  X(BINDBUFFER, BindBuffer) X(BUFFERDATA, BufferData) X(VERTEXATTRIBPOINTER, VertexAttribPointer)               \
  X(ENABLEVERTEXATTRIBARRAY, EnableVertexAttribArray) X(DRAWARRAYS, DrawArrays) X(GENTEXTURES, GenTextures)     \
  X(BINDTEXTURE, BindTexture) X(TEXIMAGE2D, TexImage2D) X(TEXPARAMETERI, TexParameteri)                         \
  X(ACTIVETEXTURE, ActiveTexture) X(DELETESHADER, DeleteShader) X(DELETEPROGRAM, DeleteProgram)                 \
  X(DELETEBUFFERS, DeleteBuffers) X(DELETEVERTEXARRAYS, DeleteVertexArrays)                                     \
  X(DELETEFRAMEBUFFERS, DeleteFramebuffers) X(DELETERENDERBUFFERS, DeleteRenderbuffers)                         \
  X(DELETETEXTURES, DeleteTextures) X(READBUFFER, ReadBuffer)

struct Gl {
#define X(UP, Name) PFNGL##UP##PROC Name = nullptr;
  BELTSIM_GL_FUNCTIONS(X)
#undef X
  explicit Gl(const GlContext& ctx) {
#define X(UP, Name)                                                                              \
  Name = reinterpret_cast<PFNGL##UP##PROC>(ctx.proc("gl" #Name));                               \
  if (!Name) throw std::runtime_error(std::string("OpenGL function gl" #Name " not available from ") + \
                                      backend_name(ctx.backend()));
    BELTSIM_GL_FUNCTIONS(X)
#undef X
  }
};

struct GlRenderer::Impl {
  GlContext& ctx;
  Gl gl;
  int w, h, samples;
  GLuint solid = 0, text = 0;
  GLint solid_vp = -1, text_vp = -1, text_atlas = -1;
  GLuint vao_solid = 0, vbo_solid = 0, vao_text = 0, vbo_text = 0;
  GLuint fbo_ms = 0, rb_ms = 0, fbo = 0, rb = 0, atlas = 0;
  const Font* atlas_font = nullptr;
  long atlas_version = -1;

  Impl(GlContext& c, int width, int height, int s) : ctx(c), gl(c), w(width), h(height), samples(s) {}

  GLuint compile(GLenum type, const std::string& name) {
    const GLuint sh = gl.CreateShader(type);
    const char* src = shader_source(name);
    gl.ShaderSource(sh, 1, &src, nullptr);
    gl.CompileShader(sh);
    GLint ok = 0;
    gl.GetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (!ok) {
      char log[2048] = {0};
      gl.GetShaderInfoLog(sh, sizeof log, nullptr, log);
      throw std::runtime_error("shader " + name + " does not compile: " + log);
    }
    return sh;
  }
  GLuint program(const std::string& base) {
    const GLuint vs = compile(GL_VERTEX_SHADER, base + ".vert"), fs = compile(GL_FRAGMENT_SHADER, base + ".frag");
    const GLuint p = gl.CreateProgram();
    gl.AttachShader(p, vs);
    gl.AttachShader(p, fs);
    gl.LinkProgram(p);
    gl.DeleteShader(vs);
    gl.DeleteShader(fs);
    GLint ok = 0;
    gl.GetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
      char log[2048] = {0};
      gl.GetProgramInfoLog(p, sizeof log, nullptr, log);
      throw std::runtime_error("shader program " + base + " does not link: " + log);
    }
    return p;
  }
  void check(const char* where) {
    if (const GLenum e = gl.GetError(); e != GL_NO_ERROR) {
      char b[96];
      std::snprintf(b, sizeof b, "OpenGL error 0x%04x in %s", e, where);
      throw std::runtime_error(b);
    }
  }
};

GlRenderer::GlRenderer(GlContext& ctx, int width, int height, int samples)
    : impl_(std::make_unique<Impl>(ctx, width, height, samples)) {
  Impl& d = *impl_;
  Gl& gl = d.gl;
  d.solid = d.program("solid");
  d.text = d.program("text");
  d.solid_vp = gl.GetUniformLocation(d.solid, "viewport");
  d.text_vp = gl.GetUniformLocation(d.text, "viewport");
  d.text_atlas = gl.GetUniformLocation(d.text, "atlas");

  // vertex layouts match SolidVertex {x, y, rgba} and GlyphVertex {x, y, u, v, rgba}
  gl.GenVertexArrays(1, &d.vao_solid);
  gl.GenBuffers(1, &d.vbo_solid);
  gl.BindVertexArray(d.vao_solid);
  gl.BindBuffer(GL_ARRAY_BUFFER, d.vbo_solid);
  gl.VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(SolidVertex), reinterpret_cast<void*>(0));
  gl.VertexAttribPointer(1, 4, GL_FLOAT, GL_FALSE, sizeof(SolidVertex), reinterpret_cast<void*>(offsetof(SolidVertex, c)));
  gl.VertexAttribPointer(2, 2, GL_FLOAT, GL_FALSE, sizeof(SolidVertex), reinterpret_cast<void*>(offsetof(SolidVertex, da)));
  gl.EnableVertexAttribArray(0);
  gl.EnableVertexAttribArray(1);
  gl.EnableVertexAttribArray(2);
  gl.GenVertexArrays(1, &d.vao_text);
  gl.GenBuffers(1, &d.vbo_text);
  gl.BindVertexArray(d.vao_text);
  gl.BindBuffer(GL_ARRAY_BUFFER, d.vbo_text);
  gl.VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(GlyphVertex), reinterpret_cast<void*>(0));
  gl.VertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, sizeof(GlyphVertex), reinterpret_cast<void*>(offsetof(GlyphVertex, u)));
  gl.VertexAttribPointer(2, 4, GL_FLOAT, GL_FALSE, sizeof(GlyphVertex), reinterpret_cast<void*>(offsetof(GlyphVertex, c)));
  gl.EnableVertexAttribArray(0);
  gl.EnableVertexAttribArray(1);
  gl.EnableVertexAttribArray(2);
  gl.BindVertexArray(0);

  // the colour buffer read back; with samples > 1 a multisampled one is drawn into and resolved
  gl.GenRenderbuffers(1, &d.rb);
  gl.BindRenderbuffer(GL_RENDERBUFFER, d.rb);
  gl.RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
  gl.GenFramebuffers(1, &d.fbo);
  gl.BindFramebuffer(GL_FRAMEBUFFER, d.fbo);
  gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, d.rb);
  if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
    throw std::runtime_error("the framebuffer (" + std::to_string(width) + "x" + std::to_string(height) +
                             ") is incomplete");
  if (samples > 1) {
    gl.GenRenderbuffers(1, &d.rb_ms);
    gl.BindRenderbuffer(GL_RENDERBUFFER, d.rb_ms);
    gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, width, height);
    gl.GenFramebuffers(1, &d.fbo_ms);
    gl.BindFramebuffer(GL_FRAMEBUFFER, d.fbo_ms);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, d.rb_ms);
    if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
      throw std::runtime_error("the multisampled framebuffer (" + std::to_string(samples) + " samples) is incomplete");
  }

  gl.GenTextures(1, &d.atlas);
  gl.BindTexture(GL_TEXTURE_2D, d.atlas);
  // glyphs are placed on whole pixels, texel for pixel: nearest sampling keeps them crisp
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  d.check("setting up the renderer");
}

GlRenderer::~GlRenderer() {
  Impl& d = *impl_;
  Gl& gl = d.gl;
  gl.DeleteTextures(1, &d.atlas);
  gl.DeleteFramebuffers(1, &d.fbo);
  gl.DeleteRenderbuffers(1, &d.rb);
  if (d.fbo_ms) gl.DeleteFramebuffers(1, &d.fbo_ms), gl.DeleteRenderbuffers(1, &d.rb_ms);
  gl.DeleteBuffers(1, &d.vbo_solid);
  gl.DeleteBuffers(1, &d.vbo_text);
  gl.DeleteVertexArrays(1, &d.vao_solid);
  gl.DeleteVertexArrays(1, &d.vao_text);
  gl.DeleteProgram(d.solid);
  gl.DeleteProgram(d.text);
}

void GlRenderer::render(const DrawList& list, Image& out) {
  Impl& d = *impl_;
  Gl& gl = d.gl;
  if (list.width != d.w || list.height != d.h)
    throw std::runtime_error("draw list of " + std::to_string(list.width) + "x" + std::to_string(list.height) +
                             " for a renderer of " + std::to_string(d.w) + "x" + std::to_string(d.h));
  gl.BindFramebuffer(GL_FRAMEBUFFER, d.fbo_ms ? d.fbo_ms : d.fbo);
  gl.Viewport(0, 0, d.w, d.h);
  gl.ClearColor(list.background.r, list.background.g, list.background.b, 1);
  gl.Clear(GL_COLOR_BUFFER_BIT);
  gl.Enable(GL_BLEND);
  gl.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  if (d.fbo_ms) gl.Enable(GL_MULTISAMPLE);

  gl.UseProgram(d.solid);
  gl.Uniform2f(d.solid_vp, static_cast<float>(d.w), static_cast<float>(d.h));
  gl.BindVertexArray(d.vao_solid);
  gl.BindBuffer(GL_ARRAY_BUFFER, d.vbo_solid);
  gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(list.triangles.size() * sizeof(SolidVertex)),
                list.triangles.data(), GL_STREAM_DRAW);
  gl.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(list.triangles.size()));

  if (!list.glyphs.empty() && list.font) {
    gl.ActiveTexture(GL_TEXTURE0);
    gl.BindTexture(GL_TEXTURE_2D, d.atlas);
    if (d.atlas_font != list.font || d.atlas_version != list.font->version()) {
      gl.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
      gl.TexImage2D(GL_TEXTURE_2D, 0, GL_R8, Font::atlas_size, Font::atlas_size, 0, GL_RED, GL_UNSIGNED_BYTE,
                    list.font->atlas().data());
      d.atlas_font = list.font;
      d.atlas_version = list.font->version();
    }
    gl.UseProgram(d.text);
    gl.Uniform2f(d.text_vp, static_cast<float>(d.w), static_cast<float>(d.h));
    gl.Uniform1i(d.text_atlas, 0);
    gl.BindVertexArray(d.vao_text);
    gl.BindBuffer(GL_ARRAY_BUFFER, d.vbo_text);
    gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(list.glyphs.size() * sizeof(GlyphVertex)),
                  list.glyphs.data(), GL_STREAM_DRAW);
    gl.DrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(list.glyphs.size()));
  }
  gl.BindVertexArray(0);

  // resolve the samples (if any), then read back (row 0 is the image's top row, see solid.vert)
  if (d.fbo_ms) {
    gl.BindFramebuffer(GL_READ_FRAMEBUFFER, d.fbo_ms);
    gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, d.fbo);
    gl.BlitFramebuffer(0, 0, d.w, d.h, 0, 0, d.w, d.h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  }
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, d.fbo);
  gl.ReadBuffer(GL_COLOR_ATTACHMENT0);
  gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
  if (out.width != d.w || out.height != d.h) out = Image(d.w, d.h);
  gl.ReadPixels(0, 0, d.w, d.h, GL_RGB, GL_UNSIGNED_BYTE, out.rgb.data());
  d.check("rendering a frame");
  // where the text is, clipped to the picture (text may run off an edge; none of it counts then)
  out.text_boxes.clear();
  for (const PixelRect& r : list.text_rects) {
    const int x0 = std::max(r.x, 0), y0 = std::max(r.y, 0);
    const int x1 = std::min(r.x + r.w, d.w), y1 = std::min(r.y + r.h, d.h);
    if (x1 > x0 && y1 > y0) out.text_boxes.push_back({x0, y0, x1 - x0, y1 - y0});
  }
}

std::string GlRenderer::gl_renderer() const {
  return reinterpret_cast<const char*>(impl_->gl.GetString(GL_RENDERER));
}
std::string GlRenderer::gl_version() const { return reinterpret_cast<const char*>(impl_->gl.GetString(GL_VERSION)); }
int GlRenderer::width() const { return impl_->w; }
int GlRenderer::height() const { return impl_->h; }

}  // namespace beltsim::render
