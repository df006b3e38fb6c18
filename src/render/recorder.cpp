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
// the rendering of the next: on the 2-core machine the paper's dry drive with its 301 frames takes
// 4.8-5.7 s instead of 6.2-7.4 s with the writes in line (1.8 s of it integrating). At most
// kQueued frames wait; a frame's buffer comes back for the next one. A write that fails stops the
// writing and its error is rethrown on the run's thread, at its next frame or when the run drains
// or finishes the queue; the frames before it are on disk as before.
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
    thread_.join();
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
  // queues frame `number`; waits while kQueued frames wait; rethrows a failed write not yet
  // reported (and then queues nothing: the writing has stopped)
  void push(Image img, long number) {
    std::unique_lock<std::mutex> lock(m_);
    done_.wait(lock, [&] { return queue_.size() < kQueued || error_; });
    if (error_) {
      if (std::exception_ptr e = take_error()) std::rethrow_exception(e);
      return;
    }
    queue_.push_back({std::move(img), number});
    lock.unlock();
    wake_.notify_one();
  }
  // waits until every queued frame is written (or dropped after a failure: the writer thread then
  // touches nothing of the run's); returns a failed write not yet reported, which counts as
  // reported from then on
  std::exception_ptr drain() {
    std::unique_lock<std::mutex> lock(m_);
    done_.wait(lock, [&] { return queue_.empty() && !busy_; });
    return take_error();
  }

 private:
  static constexpr size_t kQueued = 2;
  // (under the lock) the failed write's error the first time, null after
  std::exception_ptr take_error() {
    if (reported_) return nullptr;
    reported_ = error_ != nullptr;
    return error_;
  }
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
      busy_ = true;
      lock.unlock();
      std::exception_ptr failed;
      if (!error_seen_) {  // after a failure the rest of the queue is dropped
        try {
          write_(it.img, it.number);
        } catch (...) {
          failed = std::current_exception();
        }
      }
      lock.lock();
      busy_ = false;
      if (failed) error_ = failed, error_seen_ = true;
      spare_.push_back(std::move(it.img));
      done_.notify_all();
    }
  }
  Write write_;
  std::mutex m_;
  std::condition_variable wake_, done_;  // a frame queued or stop; a frame written
  std::deque<Item> queue_;
  std::vector<Image> spare_;
  std::exception_ptr error_;
  bool error_seen_ = false;  // the writer thread's own copy of "error_ is set", read without the lock
  bool reported_ = false;    // error_ has been rethrown or returned once
  bool busy_ = false, stop_ = false;
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
      if (const size_t slash = fs.video_path.rfind('/'); slash != std::string::npos && slash > 0)
        OutputDir(fs.video_path.substr(0, slash));  // made when missing
      VideoOptions vo;
      vo.width = fs.width, vo.height = fs.height, vo.fps = static_cast<int>(fs.fps);
      video_ = std::make_unique<VideoWriter>(fs.video_path, vo);
    }
    writer_ = std::make_unique<FrameWriter>([this](const Image& img, long number) { write(img, number); });
  }
  ~FrameRecorder() override { writer_.reset(); }  // the thread ends before the writers it uses go
  void frame(double t, const double* y, const Drive& drive, const Observation* obs) override {
    builder_.build(t, y, list_, &drive, obs);
    ctx_->make_current();  // another context (a snapshot's) may have been current since
    Image image = writer_->spare();
    gl_.render(list_, image);
    writer_->push(std::move(image), fs_.first_number + n_);
    n_++;
  }
  // the video is closed even after a failed write, so that what was written plays
  void finish() override {
    const std::exception_ptr failed = writer_->drain();
    if (video_) video_->close();
    if (failed) std::rethrow_exception(failed);
  }
  // the frames rendered, each written (it waits for the queue)
  long frames_written() const override {
    if (const std::exception_ptr failed = writer_->drain()) std::rethrow_exception(failed);
    return n_;
  }

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
  std::unique_ptr<FrameWriter> writer_;  // last: made once the writers it calls are
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
