// The PNG and video writers on their own: a PNG round trip; an MP4 read back by ffprobe (codec,
// frame count, duration, pixel format, colour tags); a video whose writer is killed before it
// closes still plays up to its last whole fragment; one without a frame leaves no file, as does one
// whose disk filled before its first fragment; one written whole replaces an earlier file only when
// closed.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include "media/png_writer.hpp"
#include "media/video_writer.hpp"
#include "support/file_size_limit.hpp"
#include "support/scratch.hpp"

namespace beltsim {
namespace {

namespace fs = std::filesystem;

fs::path temp_dir() { return beltsim::test::scratch_dir("beltsim_io_test"); }

Image pattern(int w, int h, int k) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      uint8_t* p = img.pixel(x, y);
      p[0] = static_cast<uint8_t>(x * 255 / w), p[1] = static_cast<uint8_t>(y * 255 / h);
      p[2] = static_cast<uint8_t>((x / 8 + k) % 2 ? 230 : 20);  // moving stripes
    }
  return img;
}

// key=value lines of ffprobe for the first video stream and the container
std::map<std::string, std::string> probe(const fs::path& file) {
  const std::string cmd = "ffprobe -v error -select_streams v:0 -count_frames -show_entries "
                          "stream=codec_name,nb_read_frames,pix_fmt,color_space,color_primaries,width,height "
                          "-show_entries format=duration,format_name -of default=nw=1 '" + file.string() + "' 2>&1";
  std::map<std::string, std::string> out;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return out;
  char line[512];
  while (std::fgets(line, sizeof line, p)) {
    std::string s(line);
    while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
    const size_t eq = s.find('=');
    if (eq != std::string::npos) out[s.substr(0, eq)] = s.substr(eq + 1);
    else out["error"] += s;
  }
  out["status"] = std::to_string(pclose(p));
  return out;
}

TEST(Png, RoundTrip) {
  const Image img = pattern(37, 21, 1);
  const fs::path f = temp_dir() / "round.png";
  write_png(f.string(), img);
  const Image back = read_png(f.string());
  ASSERT_EQ(back.width, 37);
  ASSERT_EQ(back.height, 21);
  EXPECT_EQ(back.rgb, img.rgb);
  EXPECT_THROW(write_png("/proc/no/such/dir/x.png", img), std::runtime_error);  // a folder that cannot be made
  EXPECT_THROW(read_png((temp_dir() / "missing.png").string()), std::runtime_error);
  // missing folders on the way are made, as for every output
  const fs::path deep = temp_dir() / "png_made" / "a" / "b.png";
  write_png(deep.string(), img);
  EXPECT_EQ(read_png(deep.string()).rgb, img.rgb);
}

// a frame's text boxes travel in the PNG (a tEXt chunk, `beltsim compare --ignore-text`); a picture
// without them reads back without them
TEST(Png, TextBoxesRoundTrip) {
  Image img = pattern(37, 21, 1);
  img.text_boxes = {{0, 0, 37, 5}, {3, 7, 12, 9}, {30, 19, 7, 2}};
  const fs::path f = temp_dir() / "boxes.png";
  write_png(f.string(), img);
  const Image back = read_png(f.string());
  EXPECT_EQ(back.rgb, img.rgb);
  EXPECT_EQ(back.text_boxes, img.text_boxes);
  img.text_boxes.clear();
  write_png(f.string(), img);
  EXPECT_TRUE(read_png(f.string()).text_boxes.empty());
}

TEST(Video, ReadBackByFfprobe) {
  const fs::path f = temp_dir() / "clip.mp4";
  VideoOptions o;
  o.width = 96, o.height = 64, o.fps = 30;
  const long before = VideoWriter::encoders_created();
  {
    VideoWriter v(f.string(), o);
    for (int k = 0; k < 45; ++k) v.add(pattern(96, 64, k));
    v.close();
    EXPECT_EQ(v.frames(), 45);
  }
  EXPECT_EQ(VideoWriter::encoders_created(), before + 1);
  auto p = probe(f);
  EXPECT_EQ(p["codec_name"], "h264") << p["error"];
  EXPECT_EQ(p["nb_read_frames"], "45");
  EXPECT_EQ(p["pix_fmt"], "yuv420p");
  EXPECT_EQ(p["color_space"], "bt709");
  EXPECT_EQ(p["color_primaries"], "bt709");
  EXPECT_EQ(p["width"], "96");
  EXPECT_NEAR(std::stod(p["duration"].empty() ? "0" : p["duration"]), 1.5, 0.05);
}

TEST(Video, RejectsOddSizesAndWrongFrames) {
  VideoOptions o;
  o.width = 95, o.height = 64;
  EXPECT_THROW(VideoWriter((temp_dir() / "odd.mp4").string(), o), std::runtime_error);
  o.width = 96;
  VideoWriter v((temp_dir() / "size.mp4").string(), o);
  EXPECT_THROW(v.add(pattern(64, 64, 0)), std::runtime_error);
  EXPECT_THROW(VideoWriter("/proc/no/such/dir/x.mp4", o), std::runtime_error);  // a folder that cannot be made
  VideoWriter made((temp_dir() / "video_made" / "a" / "v.mp4").string(), o);    // missing folders made
  EXPECT_TRUE(fs::is_directory(temp_dir() / "video_made" / "a"));
}

// A process killed while writing (no close, no trailer): the fragmented MP4 still plays the
// fragments completed before (one per second of video: GOP = fps).
TEST(Video, KilledWriterLeavesAPlayableFile) {
  const fs::path f = temp_dir() / "killed.mp4";
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    VideoOptions o;
    o.width = 96, o.height = 64, o.fps = 30;
    auto* v = new VideoWriter(f.string(), o);  // never closed or destroyed
    for (int k = 0; k < 100; ++k) v->add(pattern(96, 64, k));
    _exit(0);  // as abrupt as a kill: no destructors, no atexit
  }
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  auto p = probe(f);
  EXPECT_EQ(p["codec_name"], "h264") << p["error"];
  const int frames = std::stoi(p["nb_read_frames"].empty() ? "0" : p["nb_read_frames"]);
  // 100 frames sent; the encoder's look-ahead holds back a few, the unfinished fragment is lost
  EXPECT_GE(frames, 60) << p["error"];
  EXPECT_LE(frames, 100);
}

// A video closed (or destroyed) without a frame is a header alone, which no player opens (a trial's
// run stopped before its first frame left one of 808 bytes): no file is left.
TEST(Video, NoFrameLeavesNoFile) {
  VideoOptions o;
  o.width = 96, o.height = 64;
  const fs::path closed = temp_dir() / "no_frame.mp4", destroyed = temp_dir() / "no_frame_destroyed.mp4";
  {
    VideoWriter v(closed.string(), o);
    EXPECT_TRUE(fs::exists(closed));  // made at once (a run's video is written as it goes)
    v.close();
    EXPECT_FALSE(fs::exists(closed));
  }
  { VideoWriter v(destroyed.string(), o); }
  EXPECT_FALSE(fs::exists(destroyed));
}

// A disk that fills before the first fragment (a second of video) reaches it: what is on disk is
// the header alone, which no player opens (a user's trial on a 400 kB tmpfs was left a file of
// 782 bytes, "the video keeps its whole fragments, 782 bytes"): it is removed, and the error says
// that no frame reached the disk. A disk that fills later keeps the fragments before.
TEST(Video, DiskFullBeforeTheFirstFragmentLeavesNoFile) {
  VideoOptions o;
  o.width = 96, o.height = 64, o.fps = 30;
  const fs::path f = temp_dir() / "full_at_once.mp4";
  enum { kRemoved = 0, kNoError = 1, kMessage = 2, kLeft = 3, kNoHeader = 4 };
  // the header (under 1 kB) fits, the first fragment (30 frames) does not
  const int status = test::exit_status_under_file_size_limit(2048, [&] {
    try {
      VideoWriter v(f.string(), o);
      if (!fs::exists(f)) return int(kNoHeader);
      for (int k = 0; k < 100; ++k) v.add(pattern(96, 64, k));
      v.close();
    } catch (const std::exception& e) {
      const std::string m = e.what();
      std::fprintf(stderr, "%s\n", m.c_str());
      if (m != "cannot write " + f.string() + ": File too large (no frame reached the disk: the video is removed)")
        return int(kMessage);
      return int(fs::exists(f) ? kLeft : kRemoved);
    }
    return int(kNoError);
  });
  EXPECT_EQ(status, kRemoved);
  EXPECT_FALSE(fs::exists(f));
  // with room for a fragment or two, the whole fragments stay and play
  const fs::path g = temp_dir() / "full_later.mp4";
  const int later = test::exit_status_under_file_size_limit(16 * 1024, [&] {
    try {
      VideoWriter v(g.string(), o);
      for (int k = 0; k < 1000; ++k) v.add(pattern(96, 64, k));
      v.close();
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s\n", e.what());
      return std::string(e.what()).find("(the video keeps its whole fragments, ") != std::string::npos ? 0 : 2;
    }
    return 1;
  });
  EXPECT_EQ(later, 0);
  const std::string frames = probe(g)["nb_read_frames"];
  EXPECT_GE(std::stoi(frames.empty() ? "0" : frames), 30);
}

// VideoOptions::whole (beltsim render's): an earlier file of the name is left as it was until the
// video is closed, and for good when it is closed under another name or never closed
TEST(Video, WrittenWholeReplacesTheEarlierFileOnlyWhenClosed) {
  VideoOptions o;
  o.width = 96, o.height = 64, o.whole = true;
  const fs::path f = temp_dir() / "whole.mp4", partial = temp_dir() / "whole.partial.mp4";
  EXPECT_EQ(partial_video_path(f.string()), partial.string());
  const auto earlier = [&] {
    std::ifstream in(f, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()) == "earlier";
  };
  fs::remove(partial);
  std::ofstream(f) << "earlier";
  {
    VideoWriter v(f.string(), o);
    for (int k = 0; k < 10; ++k) v.add(pattern(96, 64, k));
    EXPECT_TRUE(earlier());
  }  // never closed: given up
  EXPECT_TRUE(earlier());
  {
    VideoWriter v(f.string(), o);
    for (int k = 0; k < 10; ++k) v.add(pattern(96, 64, k));
    v.close(partial.string());
  }
  EXPECT_TRUE(earlier());
  EXPECT_EQ(probe(partial)["nb_read_frames"], "10");
  {
    VideoWriter v(f.string(), o);
    v.close();  // no frame: nothing named
  }
  EXPECT_TRUE(earlier());
  {
    VideoWriter v(f.string(), o);
    for (int k = 0; k < 12; ++k) v.add(pattern(96, 64, k));
    EXPECT_TRUE(earlier());
    v.close();
  }
  EXPECT_EQ(probe(f)["nb_read_frames"], "12");
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(temp_dir()))
    if (e.path().filename().string().rfind("whole", 0) == 0) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"whole.mp4", "whole.partial.mp4"}));  // no .part left
}

}  // namespace
}  // namespace beltsim
