#include "render/recorder.hpp"

#include <cstdio>

#include "media/png_writer.hpp"
#include "media/video_writer.hpp"
#include "render/draw_list.hpp"
#include "render/gl_renderer.hpp"
#include "render/text.hpp"

namespace beltsim::render {

namespace {

class FrameRecorder final : public FrameSink {
 public:
  FrameRecorder(const Scene& sc, const FrameSettings& fs)
      : fs_(fs), font_(), builder_(sc, fs, &font_), ctx_(make_gl_context(default_gl_backend())),
        gl_(*ctx_, fs.width, fs.height) {
    // the folders are made when missing; neither they nor the files in them are ever opened
    // through a link (io/output_dir.hpp)
    if (!fs.png_dir.empty()) png_dir_ = std::make_unique<OutputDir>(fs.png_dir);
    if (!fs.video_path.empty()) {
      if (const size_t slash = fs.video_path.rfind('/'); slash != std::string::npos && slash > 0)
        OutputDir(fs.video_path.substr(0, slash));  // made when missing
      VideoOptions vo;
      vo.width = fs.width, vo.height = fs.height, vo.fps = static_cast<int>(fs.fps);
      video_ = std::make_unique<VideoWriter>(fs.video_path, vo);
    }
  }
  void frame(double t, const double* y, const Drive& drive, const Observation* obs) override {
    builder_.build(t, y, list_, &drive, obs);
    ctx_->make_current();  // another context (a snapshot's) may have been current since
    gl_.render(list_, image_);
    const long number = fs_.first_number + n_;
    if (png_dir_ && number % fs_.png_every == 0) {
      char name[32];
      std::snprintf(name, sizeof name, "frame_%05ld.png", number);
      write_png(*png_dir_, name, image_);
    }
    if (video_) video_->add(image_);
    n_++;
  }
  void finish() override {
    if (video_) video_->close();
  }
  long frames_written() const override { return n_; }

 private:
  FrameSettings fs_;
  Font font_;
  FrameBuilder builder_;
  std::unique_ptr<GlContext> ctx_;
  GlRenderer gl_;
  std::unique_ptr<OutputDir> png_dir_;
  std::unique_ptr<VideoWriter> video_;
  DrawList list_;
  Image image_;
  long n_ = 0;
};

}  // namespace

std::unique_ptr<FrameSink> make_frame_recorder(const Scene& sc, const FrameSettings& fs) {
  return std::make_unique<FrameRecorder>(sc, fs);
}

struct FrameDrawer::Parts {
  Parts(const Scene& sc, const FrameSettings& fs)
      : builder(sc, fs, &font), ctx(make_gl_context(default_gl_backend())), gl(*ctx, fs.width, fs.height) {}
  Font font;
  FrameBuilder builder;
  std::unique_ptr<GlContext> ctx;
  GlRenderer gl;
  DrawList list;
};

FrameDrawer::FrameDrawer(const Scene& sc, const FrameSettings& fs) : p_(std::make_unique<Parts>(sc, fs)) {}
FrameDrawer::~FrameDrawer() = default;

const std::vector<ElementDraw>& FrameDrawer::drawn_elements() const {
  return p_->list.elements;
}

void FrameDrawer::set_caption(const std::string& caption) {
  p_->builder.set_caption(caption);
}

Image FrameDrawer::draw(double t, const double* y, const Drive& drive, const Observation* obs) {
  Image image;
  p_->builder.build(t, y, p_->list, &drive, obs);
  p_->gl.render(p_->list, image);
  return image;
}

void render_snapshot(const Scene& sc, const FrameSettings& fs, double t, const double* y, const Drive& drive,
                     const std::string& png, const Observation* obs) {
  FrameDrawer drawer(sc, fs);
  const Image image = drawer.draw(t, y, drive, obs);
  const OutputPlace place = output_place(png, true);  // its folder made when missing
  write_png(place.dir, place.name, image);
}

}  // namespace beltsim::render
