// MP4 video through the FFmpeg libraries (libavformat, libavcodec with libx264, libswscale):
// H.264, yuv420p, BT.709 tagged (TV range), one keyframe per second of video, written as a
// fragmented MP4 (movflags=frag_keyframe+empty_moov+default_base_moof) so that a file whose
// writer never got to close() — a crash, a kill — still plays up to its last complete fragment.
// close() (also called by the destructor) drains the encoder and writes the trailer; a video that
// got no frame is removed instead (a header alone is a file no player opens: a trial's run stopped
// before its first frame left one of 808 bytes).
#pragma once

#include <memory>
#include <string>

#include "media/image.hpp"

namespace beltsim {

struct VideoOptions {
  int width = 1280, height = 720;  // even (yuv420p halves the chroma planes)
  int fps = 30;                    // frames per second of video
  // x264 quality and speed: superfast at crf 23 gives the size of veryfast at crf 20 on our
  // frames, 30 % faster (measured: 75 against 58 frames/s with rendering, 1280×720)
  int crf = 23;                     // constant rate factor: lower is better and larger
  std::string preset = "superfast";
  // written unnamed in its folder (WholeFile: O_TMPFILE, else NAME.part) and named by close()
  // alone, so that an earlier file of the name is replaced by a finished video only and a video
  // never closed (an error, a kill) leaves nothing: `beltsim render`'s, which redraws a video that
  // may exist. A run's is written in place instead, so that a killed run leaves its fragments
  bool whole = false;
};

// the name a video written whole is given when it is closed without every frame it was to have
// (beltsim render stopped): "clip.mp4" gives "clip.partial.mp4"
std::string partial_video_path(const std::string& path);

class VideoWriter {
 public:
  // The file's missing folders are made (io/output_dir.hpp, output_place). Throws
  // std::runtime_error naming the path and FFmpeg's reason.
  VideoWriter(const std::string& path, const VideoOptions& opt);
  ~VideoWriter();
  VideoWriter(const VideoWriter&) = delete;
  VideoWriter& operator=(const VideoWriter&) = delete;

  // appends one frame (same size as the options); frames are 1/fps apart
  void add(const Image& frame);
  // flushes the encoder and finalises the file; further add() calls throw. Without a frame added
  // the file is removed instead (VideoOptions::whole: never named). A video written whole is
  // named `as` when given (a path in the same folder, partial_video_path), else its own path
  void close(const std::string& as = "");
  long frames() const;
  const std::string& path() const;

  // how many encoders this process has opened (a run without frames opens none: tested)
  static long encoders_created();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace beltsim
