#include "media/video_writer.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "io/output_dir.hpp"
#include "media/shared_library.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/opt.h>
#include <libswscale/swscale.h>
}

namespace beltsim {

namespace {

// the functions of FFmpeg used here, from its libraries opened at the first video
// (media/shared_library.hpp: not linked, so that a run without a video does not load FFmpeg and
// the hundred libraries its codecs pull in); the sonames and Debian packages from the headers'
// major versions
// clang-format off
#define BELTSIM_AVUTIL_FUNCTIONS(X)                                                                       \
  X(av_dict_free) X(av_dict_set) X(av_frame_alloc) X(av_frame_free) X(av_frame_get_buffer)                \
  X(av_frame_make_writable) X(av_free) X(av_freep) X(av_log_set_level) X(av_malloc) X(av_opt_set)          \
  X(av_strerror)
#define BELTSIM_AVCODEC_FUNCTIONS(X)                                                                      \
  X(av_packet_alloc) X(av_packet_free) X(av_packet_rescale_ts) X(avcodec_alloc_context3)                  \
  X(avcodec_find_encoder) X(avcodec_find_encoder_by_name) X(avcodec_free_context) X(avcodec_open2)        \
  X(avcodec_parameters_from_context) X(avcodec_receive_packet) X(avcodec_send_frame)
#define BELTSIM_AVFORMAT_FUNCTIONS(X)                                                                     \
  X(av_interleaved_write_frame) X(av_write_trailer) X(avformat_alloc_output_context2)                     \
  X(avformat_free_context) X(avformat_new_stream) X(avformat_write_header) X(avio_alloc_context)          \
  X(avio_context_free) X(avio_flush) X(avio_seek)
#define BELTSIM_SWSCALE_FUNCTIONS(X)                                                                      \
  X(sws_scale) X(sws_freeContext) X(sws_getContext) X(sws_getCoefficients) X(sws_setColorspaceDetails)
// clang-format on
#define BELTSIM_OPEN(lib, LIB, FUNCTIONS)                                                \
  {                                                                                      \
    const char* soname = #lib ".so." AV_STRINGIFY(LIB##_VERSION_MAJOR);                  \
    void* library = open_shared_library(soname, #lib AV_STRINGIFY(LIB##_VERSION_MAJOR)); \
    FUNCTIONS(BELTSIM_SHARED_LOAD)                                                       \
  }

struct FfmpegApi {
  BELTSIM_AVUTIL_FUNCTIONS(BELTSIM_SHARED_DECLARE)
  BELTSIM_AVCODEC_FUNCTIONS(BELTSIM_SHARED_DECLARE)
  BELTSIM_AVFORMAT_FUNCTIONS(BELTSIM_SHARED_DECLARE)
  BELTSIM_SWSCALE_FUNCTIONS(BELTSIM_SHARED_DECLARE)
  FfmpegApi() {
    BELTSIM_OPEN(libavutil, LIBAVUTIL, BELTSIM_AVUTIL_FUNCTIONS)
    BELTSIM_OPEN(libavcodec, LIBAVCODEC, BELTSIM_AVCODEC_FUNCTIONS)
    BELTSIM_OPEN(libavformat, LIBAVFORMAT, BELTSIM_AVFORMAT_FUNCTIONS)
    BELTSIM_OPEN(libswscale, LIBSWSCALE, BELTSIM_SWSCALE_FUNCTIONS)
  }
};

#undef BELTSIM_OPEN

// opened once, on the first call (a failure throws, and the next call tries again)
const FfmpegApi& ff() {
  static const FfmpegApi api;
  return api;
}

}  // namespace

// the file under the muxer: a descriptor opened by OutputDir (never through a link) written by
// the AVIOContext's callbacks; the first write error is kept (errno)
// (outside the anonymous namespace: VideoWriter::Impl holds one)
struct VideoFile {
  int fd = -1;
  int error = 0;
};

namespace {

std::atomic<long> g_encoders{0};

std::string av_message(int err) {
  char buf[AV_ERROR_MAX_STRING_SIZE] = {0};
  ff().av_strerror(err, buf, sizeof buf);
  return buf;
}

int write_packet(void* opaque, uint8_t* buf, int size) {
  auto* f = static_cast<VideoFile*>(opaque);
  for (int done = 0; done < size;) {
    const ssize_t n = ::write(f->fd, buf + done, static_cast<size_t>(size - done));
    if (n > 0) {
      done += static_cast<int>(n);
    } else if (!(n < 0 && errno == EINTR)) {
      if (f->error == 0) f->error = n < 0 ? errno : ENOSPC;
      return AVERROR(f->error);
    }
  }
  return size;
}

int64_t seek(void* opaque, int64_t offset, int whence) {
  auto* f = static_cast<VideoFile*>(opaque);
  if (whence == AVSEEK_SIZE) {
    const off_t here = ::lseek(f->fd, 0, SEEK_CUR), end = ::lseek(f->fd, 0, SEEK_END);
    ::lseek(f->fd, here, SEEK_SET);
    return end < 0 ? AVERROR(errno) : end;
  }
  const off_t r = ::lseek(f->fd, static_cast<off_t>(offset), whence & ~AVSEEK_FORCE);
  return r < 0 ? AVERROR(errno) : r;
}

}  // namespace

struct VideoWriter::Impl {
  std::string path;
  VideoOptions opt;
  AVFormatContext* fmt = nullptr;
  AVCodecContext* enc = nullptr;
  AVStream* stream = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* pkt = nullptr;
  SwsContext* sws = nullptr;
  long n = 0;
  bool open = false;     // header written, trailer not yet
  bool io_open = false;
  VideoFile file;
  std::unique_ptr<OutputDir> dir;  // the video's folder and its name there
  std::string name;
  std::unique_ptr<WholeFile> whole;  // VideoOptions::whole: the unnamed file (its fd is file.fd)
  int64_t whole_end = 0;             // [bytes] where the header or the last whole fragment ends
  int64_t header_end = 0;            // [bytes] where the header ends (whole_end there: no frame on disk)

  [[noreturn]] void fail(const std::string& what, int err = 0) {
    const std::string m = "video " + path + ": " + what + (err ? ": " + av_message(err) : "");
    if (dir) note_output_failure(m);  // once the file is made, a video that fails is an output lost
    throw std::runtime_error(m);
  }

  // after each packet handed to the muxer: a write that failed (a full disk) ends the video at its
  // last whole fragment, which plays; the error names the file. Before the first fragment is whole
  // on disk the file is a header alone, which no player opens: it is removed, as a video closed
  // without a frame is (a trial's disk filled at the first fragment and left 782 bytes, said to be
  // "its whole fragments")
  void check_written() {
    if (file.error == 0 && fmt->pb->error == 0) {
      whole_end = ff().avio_seek(fmt->pb, 0, SEEK_CUR);
      return;
    }
    const int err = file.error ? file.error : EIO;
    open = false;
    if (whole_end <= header_end) {
      if (!whole) dir->remove(name);  // (a whole file is given up with the writer)
      output_error(path, std::string(std::strerror(err)) + " (no frame reached the disk: the video is removed)");
    }
    const bool cut = ::ftruncate(file.fd, whole_end) == 0;
    output_error(path, std::string(std::strerror(err)) +
                           (cut ? " (the video keeps its whole fragments, " + std::to_string(whole_end) + " bytes)"
                                : " (its last fragment is torn)"));
  }

  // send a frame (or nullptr to flush) and write every packet the encoder has ready
  void encode(AVFrame* f) {
    int r = ff().avcodec_send_frame(enc, f);
    if (r < 0) fail("encoding failed", r);
    for (;;) {
      r = ff().avcodec_receive_packet(enc, pkt);
      if (r == AVERROR(EAGAIN) || r == AVERROR_EOF) return;
      if (r < 0) fail("encoding failed", r);
      ff().av_packet_rescale_ts(pkt, enc->time_base, stream->time_base);
      pkt->stream_index = stream->index;
      r = ff().av_interleaved_write_frame(fmt, pkt);  // takes the packet's reference
      if (r < 0 && file.error == 0) fail("writing failed", r);
      check_written();
    }
  }

  void close_io() {
    if (!io_open) return;
    io_open = false;
    ff().avio_flush(fmt->pb);
    ff().av_freep(&fmt->pb->buffer);
    ff().avio_context_free(&fmt->pb);
    if (file.fd >= 0 && !whole) ::close(file.fd);  // a whole file's is closed by its commit or discard
    file.fd = -1;
  }

  void release() {
    close_io();
    ff().sws_freeContext(sws), sws = nullptr;
    ff().av_packet_free(&pkt);
    ff().av_frame_free(&frame);
    ff().avcodec_free_context(&enc);
    ff().avformat_free_context(fmt), fmt = nullptr;
  }
};

VideoWriter::VideoWriter(const std::string& path, const VideoOptions& opt) : impl_(std::make_unique<Impl>()) {
  Impl& d = *impl_;
  d.path = path;
  d.opt = opt;
  // FFmpeg and x264 report their settings at the info level: keep the terminal for warnings
  static const bool quiet = (ff().av_log_set_level(AV_LOG_WARNING), true);
  (void)quiet;
  try {
    if (opt.width <= 0 || opt.height <= 0 || opt.width % 2 || opt.height % 2)
      d.fail("width and height must be even and positive (got " + std::to_string(opt.width) + "x" +
             std::to_string(opt.height) + ")");
    if (opt.fps <= 0 || opt.fps > 240) d.fail("frame rate must be in 1..240 (got " + std::to_string(opt.fps) + ")");
    int r = ff().avformat_alloc_output_context2(&d.fmt, nullptr, "mp4", path.c_str());
    if (r < 0 || !d.fmt) d.fail("cannot create the MP4 muxer", r);
    const AVCodec* codec = ff().avcodec_find_encoder_by_name("libx264");
    if (!codec) codec = ff().avcodec_find_encoder(AV_CODEC_ID_H264);
    if (!codec) d.fail("no H.264 encoder in this FFmpeg build (libx264 expected)");
    d.stream = ff().avformat_new_stream(d.fmt, nullptr);
    d.enc = ff().avcodec_alloc_context3(codec);
    d.pkt = ff().av_packet_alloc();
    d.frame = ff().av_frame_alloc();
    if (!d.stream || !d.enc || !d.pkt || !d.frame) d.fail("out of memory");
    AVCodecContext* c = d.enc;
    c->width = opt.width;
    c->height = opt.height;
    c->time_base = AVRational{1, opt.fps};
    c->framerate = AVRational{opt.fps, 1};
    c->gop_size = opt.fps;  // a keyframe, hence a fragment, per second of video
    c->pix_fmt = AV_PIX_FMT_YUV420P;
    c->color_primaries = AVCOL_PRI_BT709;
    c->color_trc = AVCOL_TRC_BT709;
    c->colorspace = AVCOL_SPC_BT709;
    c->color_range = AVCOL_RANGE_MPEG;
    if (d.fmt->oformat->flags & AVFMT_GLOBALHEADER) c->flags |= AV_CODEC_FLAG_GLOBAL_HEADER;
    ff().av_opt_set(c->priv_data, "preset", opt.preset.c_str(), 0);
    ff().av_opt_set(c->priv_data, "crf", std::to_string(opt.crf).c_str(), 0);
    if ((r = ff().avcodec_open2(c, codec, nullptr)) < 0) d.fail("cannot open the H.264 encoder", r);
    g_encoders++;
    if ((r = ff().avcodec_parameters_from_context(d.stream->codecpar, c)) < 0) d.fail("codec parameters", r);
    d.stream->time_base = c->time_base;
    d.stream->avg_frame_rate = c->framerate;

    d.frame->format = c->pix_fmt;
    d.frame->width = c->width;
    d.frame->height = c->height;
    if ((r = ff().av_frame_get_buffer(d.frame, 0)) < 0) d.fail("frame buffer", r);
    d.frame->color_primaries = c->color_primaries;
    d.frame->color_trc = c->color_trc;
    d.frame->colorspace = c->colorspace;
    d.frame->color_range = c->color_range;
    d.sws = ff().sws_getContext(opt.width, opt.height, AV_PIX_FMT_RGB24, opt.width, opt.height, AV_PIX_FMT_YUV420P,
                                SWS_BICUBIC, nullptr, nullptr, nullptr);
    if (!d.sws) d.fail("cannot create the RGB to YUV converter");
    // full-range sRGB in, BT.709 TV-range YUV out: without this swscale uses BT.601 and the
    // colours shift
    const int* bt709 = ff().sws_getCoefficients(SWS_CS_ITU709);
    ff().sws_setColorspaceDetails(d.sws, bt709, 1, bt709, 0, 0, 1 << 16, 1 << 16);

    {
      OutputPlace place = output_place(path);
      d.dir = std::make_unique<OutputDir>(std::move(place.dir));
      d.name = place.name;
      if (opt.whole) {
        d.whole = std::make_unique<WholeFile>(*d.dir, d.name);
        d.file.fd = d.whole->fd();
      } else {
        d.file.fd = d.dir->open_file(d.name, false);
      }
    }
    constexpr int kBuffer = 32768;
    auto* buffer = static_cast<unsigned char*>(ff().av_malloc(kBuffer));
    d.fmt->pb = buffer ? ff().avio_alloc_context(buffer, kBuffer, 1, &d.file, nullptr, write_packet, seek) : nullptr;
    if (!d.fmt->pb) {
      ff().av_free(buffer);
      if (!d.whole) ::close(d.file.fd);
      d.file.fd = -1;
      d.fail("out of memory");
    }
    d.fmt->flags |= AVFMT_FLAG_CUSTOM_IO;
    // hand each fragment to the file as soon as it is complete (not when the 32 kB I/O buffer
    // fills), so a killed process leaves every finished fragment on disk
    d.fmt->flags |= AVFMT_FLAG_FLUSH_PACKETS;
    d.io_open = true;
    AVDictionary* mux = nullptr;
    ff().av_dict_set(&mux, "movflags", "frag_keyframe+empty_moov+default_base_moof", 0);
    r = ff().avformat_write_header(d.fmt, &mux);
    ff().av_dict_free(&mux);
    if (r >= 0) ff().avio_flush(d.fmt->pb);
    if (r < 0 || d.file.error || d.fmt->pb->error) {
      // nothing playable was written: no file is left
      const int err = d.file.error;
      d.close_io();
      if (!d.whole) d.dir->remove(d.name);  // (a whole file is given up with the writer)
      if (err) output_error(path, std::strerror(err));
      d.fail("cannot write the header", r);
    }
    d.whole_end = d.header_end = ff().avio_seek(d.fmt->pb, 0, SEEK_CUR);
    d.open = true;
  } catch (...) {
    d.release();
    throw;
  }
}

VideoWriter::~VideoWriter() {
  // a video written whole that was not closed is given up (its WholeFile, released with impl_):
  // the earlier file of its name stays
  if (!impl_->whole) {
    try {
      close();
    } catch (...) {  // a destructor must not throw; the fragments written so far still play
    }
  }
  impl_->release();
}

void VideoWriter::add(const Image& img) {
  Impl& d = *impl_;
  if (!d.open) d.fail("add() after close()");
  if (img.width != d.opt.width || img.height != d.opt.height)
    d.fail("frame of " + std::to_string(img.width) + "x" + std::to_string(img.height) + " in a video of " +
           std::to_string(d.opt.width) + "x" + std::to_string(d.opt.height));
  int r = ff().av_frame_make_writable(d.frame);
  if (r < 0) d.fail("frame buffer", r);
  const uint8_t* src[1] = {img.rgb.data()};
  const int stride[1] = {3 * img.width};
  ff().sws_scale(d.sws, src, stride, 0, img.height, d.frame->data, d.frame->linesize);
  d.frame->pts = d.n++;
  d.encode(d.frame);
}

void VideoWriter::close(const std::string& as) {
  Impl& d = *impl_;
  if (!d.open) return;
  d.open = false;  // whatever happens below, do not try twice
  if (d.n == 0) {  // a header alone: no player opens it, so no file is left
    d.close_io();
    if (d.whole)
      d.whole->discard();
    else
      d.dir->remove(d.name);
    return;
  }
  try {
    d.encode(nullptr);
    const int r = ff().av_write_trailer(d.fmt);
    if (d.file.error == 0 && d.fmt->pb->error == 0) ff().avio_flush(d.fmt->pb);
    if (d.file.error || d.fmt->pb->error) d.check_written();  // throws, the video cut to its whole fragments
    if (r < 0) d.fail("cannot write the trailer", r);
  } catch (...) {
    d.close_io();
    throw;
  }
  const int fd = d.file.fd;
  d.file.fd = -1;
  d.close_io();
  if (d.whole) {
    d.whole->commit(as.empty() ? "" : std::filesystem::path(as).filename().string());
    return;
  }
  if (::close(fd) != 0) output_error(d.path, std::strerror(errno));
}

std::string partial_video_path(const std::string& path) {
  std::filesystem::path p(path);
  const std::string ext = p.extension().string();
  return p.replace_extension(".partial" + ext).string();
}

long VideoWriter::frames() const { return impl_->n; }
const std::string& VideoWriter::path() const { return impl_->path; }
long VideoWriter::encoders_created() { return g_encoders.load(); }

}  // namespace beltsim
