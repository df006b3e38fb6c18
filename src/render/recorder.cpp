#include "render/recorder.hpp"

#include <condition_variable>
#include <cstdio>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

#include "media/png_writer.hpp"
#include "media/video_writer.hpp"
#include "render/draw_list.hpp"
#include "render/gl_renderer.hpp"
#include "render/text.hpp"

namespace beltsim::render {

namespace {

// Writes the rendered frames (PNG files, the video) on a thread of its own, so that encoding a
// frame (most of a frame's cost: x264 and the RGB to YUV conversion) overlaps the integration and
// the rendering of the next. At most kQueued frames wait; a written frame's buffer is reused. A
// write that fails stops the writing: the frames queued after it are dropped, and its error is
// rethrown on the run's thread at every frame queued from then on (as a video writer that failed
// refuses every frame after), or by finish() when no frame followed it.
class FrameWriter {
 public:
  using Write = std::function<void(const Image&, long)>;
  explicit FrameWriter(Write write) : write_(std::move(write)), thread_([this] { loop(); }) {}
  ~FrameWriter() {
    {
      std::lock_guard<std::mutex> lock(m_);
      stop_ = true;
    }
    wake_.notify_all();
    thread_.join();  // after writing what is queued
  }
  FrameWriter(const FrameWriter&) = delete;
  FrameWriter& operator=(const FrameWriter&) = delete;

  // a buffer to render the next frame into (a written frame's, or a new one)
  Image spare() {
    std::lock_guard<std::mutex> lock(m_);
    if (spare_.empty()) return Image{};
    Image img = std::move(spare_.back());
    spare_.pop_back();
    return img;
  }
  // queues frame `number`; waits while kQueued frames wait; rethrows a failed write
  void push(Image img, long number) {
    std::unique_lock<std::mutex> lock(m_);
    done_.wait(lock, [&] { return queue_.size() < kQueued || error_; });
    if (error_) {
      reported_ = true;
      std::rethrow_exception(error_);
    }
    queue_.push_back({std::move(img), number});
    lock.unlock();
    wake_.notify_one();
  }
  // waits until every queued frame is written (or dropped after a failure); returns the frames
  // written so far
  long wait() {
    std::unique_lock<std::mutex> lock(m_);
    done_.wait(lock, [&] { return queue_.empty() && !busy_; });
    return written_;
  }
  // wait(), then the failed write's error if no push() has rethrown it (and from then on none)
  std::exception_ptr finish() {
    wait();
    std::lock_guard<std::mutex> lock(m_);
    if (reported_) return nullptr;
    reported_ = error_ != nullptr;
    return error_;
  }

 private:
  static constexpr std::size_t kQueued = 2;
  struct Item {
    Image img;
    long number;
  };
  void loop() {
    std::unique_lock<std::mutex> lock(m_);
    for (;;) {
      wake_.wait(lock, [&] { return stop_ || !queue_.empty(); });
      if (queue_.empty()) return;  // stop_, and nothing left to write
      Item it = std::move(queue_.front());
      queue_.pop_front();
      const bool drop = error_ != nullptr;  // after a failure the rest of the queue is dropped
      busy_ = true;
      lock.unlock();
      std::exception_ptr failed;
      if (!drop) {
        try {
          write_(it.img, it.number);
        } catch (...) {
          failed = std::current_exception();
        }
      }
      lock.lock();
      busy_ = false;
      if (failed) error_ = failed;
      if (!drop && !failed) written_++;
      spare_.push_back(std::move(it.img));
      done_.notify_all();
    }
  }
  Write write_;
  std::mutex m_;
  std::condition_variable wake_, done_;  // a frame queued or stop; a frame written or dropped
  std::deque<Item> queue_;
  std::vector<Image> spare_;
  std::exception_ptr error_;  // the first failed write's
  bool reported_ = false;     // error_ has been rethrown or returned
  bool busy_ = false, stop_ = false;
  long written_ = 0;
  std::thread thread_;  // last: it starts once the members above are made
};

class FrameRecorder final : public FrameSink {
 public:
  FrameRecorder(const Scene& sc, const FrameSettings& fs)
      : fs_(fs), font_(), builder_(sc, fs, &font_), ctx_(make_gl_context(default_gl_backend())),
        gl_(*ctx_, fs.width, fs.height) {
    // the folders are made when missing; neither they nor the files in them are ever opened
    // through a link (io/output_dir.hpp)
    if (!fs.png_dir.empty()) png_dir_ = std::make_unique<OutputDir>(fs.png_dir);
    if (!fs.video_path.empty()) {
      VideoOptions vo;
      vo.width = fs.width, vo.height = fs.height, vo.fps = static_cast<int>(fs.fps);
      vo.whole = fs.video_whole_frames > 0;
      video_ = std::make_unique<VideoWriter>(fs.video_path, vo);
    }
    writer_ = std::make_unique<FrameWriter>([this](const Image& img, long number) { write(img, number); });
  }
  void frame(double t, const double* y, const Drive& drive, const Observation* obs) override {
    builder_.build(t, y, list_, &drive, obs);
    ctx_->make_current();  // another context (a snapshot's) may have been current since
    Image image = writer_->spare();
    gl_.render(list_, image);
    writer_->push(std::move(image), fs_.first_number + n_);
    n_++;
  }
  // the video is closed even after a failed write, so that what was written plays; the failed
  // write's error comes first. A video written whole without all its frames gets the partial name
  void finish() override {
    const std::exception_ptr failed = writer_->finish();
    try {
      if (video_)
        video_->close(fs_.video_whole_frames > 0 && video_->frames() < fs_.video_whole_frames
                          ? partial_video_path(fs_.video_path)
                          : "");
    } catch (...) {
      if (!failed) throw;
    }
    if (failed) std::rethrow_exception(failed);
  }
  // the frames written (it waits for those queued)
  long frames_written() const override { return writer_->wait(); }

 private:
  // on the writer's thread
  void write(const Image& image, long number) {
    if (png_dir_ && number % fs_.png_every == 0) {
      char name[32];
      std::snprintf(name, sizeof name, "frame_%05ld.png", number);
      write_png(*png_dir_, name, image);
    }
    if (video_) video_->add(image);
  }
  FrameSettings fs_;
  Font font_;
  FrameBuilder builder_;
  std::unique_ptr<GlContext> ctx_;
  GlRenderer gl_;
  std::unique_ptr<OutputDir> png_dir_;
  std::unique_ptr<VideoWriter> video_;
  DrawList list_;
  long n_ = 0;  // frames rendered (the next one's number is fs_.first_number + n_)
  // last: destroyed first, so that its thread has ended before the writers it calls go
  std::unique_ptr<FrameWriter> writer_;
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

void FrameDrawer::set_pulley_lines(const std::vector<std::string>& lines) {
  p_->builder.set_pulley_lines(lines);
}

Image FrameDrawer::draw(double t, const double* y, const Drive& drive, const Observation* obs,
                        const std::vector<double>* values) {
  Image image;
  p_->builder.build(t, y, p_->list, &drive, obs, values);
  p_->gl.render(p_->list, image);
  return image;
}

void render_snapshot(const Scene& sc, const FrameSettings& fs, double t, const double* y, const Drive& drive,
                     const std::string& png, const Observation* obs) {
  FrameDrawer drawer(sc, fs);
  const Image image = drawer.draw(t, y, drive, obs);
  const OutputPlace place = output_place(png);  // its folder made when missing
  write_png(place.dir, place.name, image);
}

}  // namespace beltsim::render
