// scene:run{ frames = {...} }: bad options stop the script before anything is simulated, with
// file:line, the reason and the value; a run without frames opens no GL context and no encoder;
// a run with frames writes one PNG and one video frame per frame time; a diverging run leaves a
// video that plays; a run that ends before its first frame leaves no video, and says so.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "media/video_writer.hpp"
#include "render/gl_context.hpp"
#include "script/interpreter.hpp"
#include "run_script.hpp"
#include "support/scenes.hpp"
#include "support/scratch.hpp"

namespace beltsim::script {
namespace frames_test {

namespace fs = std::filesystem;

fs::path temp_dir() { return beltsim::test::scratch_dir("beltsim_frames_test"); }

const std::string kScene = [] {
  beltsim::test::TwoPulley p;
  p.elements = 60;
  return beltsim::test::two_pulley(p);
}();

// runs `run_line` after the scene (line 8 of the script); returns the error ("" when it ran)
std::string run(const std::string& run_line, const fs::path& out) {
  Interpreter lua;
  return test::run_script(lua, temp_dir() / "frames.lua", kScene + run_line + "\n", out);
}

std::string probe(const fs::path& file, const std::string& entry) {
  const std::string cmd = "ffprobe -v error -select_streams v:0 -count_frames -show_entries " + entry +
                          " -of default=nw=1:nk=1 '" + file.string() + "' 2>/dev/null";
  std::string out;
  if (FILE* p = popen(cmd.c_str(), "r")) {
    char b[256];
    while (std::fgets(b, sizeof b, p)) out += b;
    pclose(p);
  }
  while (!out.empty() && (out.back() == '\n' || out.back() == '\r')) out.pop_back();
  return out;
}

TEST(Frames, BadOptionsStopBeforeSimulating) {
  struct Case {
    std::string frames, expect;
  };
  const Case cases[] = {
      {"fps = 0, video = true", "run.frames.fps: must be in (0, 240] (got 0)"},
      {"fsp = 30, video = true", "unknown key 'fsp' in run.frames (did you mean 'fps'?)"},
      {"size = {1279, 720}, video = true", "even and in 16..8192 px (H.264 in yuv420p) (got 1279x720)"},
      {"quantity = 'tensoin', png = true", "unknown quantity 'tensoin' (did you mean 'tension'?); one of: tension"},
      {"range = {900, 0}, png = true", "run.frames.range: needs lo < hi (got {900, 0})"},
      {"magnify = -1, png = true", "run.frames.magnify: must be in (0, 1e4] (got -1)"},
      {"slowdown = 0, png = true", "run.frames.slowdown: must be > 0"},
      {"png = 5", "run.frames.png: true, false or a path expected, got number"},
      {"fps = 30", "neither png nor video asked for"},
      {"levels = 1, png = true", "run.frames.levels: must be 0 (continuous) or 2..64 (got 1)"},
      {"t_start = 5, png = true", "run.frames.t_start: must be <= t_end"},
      // an empty name is refused naming its key (it read "run.frames.png: neither png nor video
      // asked for ... (got none)" for both)
      {"video = ''", "run.frames.video: an empty file name"},
      {"png = ''", "run.frames.png: an empty folder name"},
      // a video is an MP4: another name got MP4 bytes
      {"video = 'clip.avi'",
       "run.frames.video: beltsim writes MP4 videos (H.264): give a name ending in .mp4 "
       "(got clip.avi)"},
      // one name for both (it read "cannot write out/.../frames: Is a directory")
      {"png = 'frames', video = 'frames'",
       "run.frames.video: the same name as png's folder of PNGs: the two names "
       "collide"},
      {"png = true, video = './frames/'", "the two names collide"},
  };
  for (const Case& c : cases) {
    const fs::path out = temp_dir() / "bad";
    fs::remove_all(out);
    const std::string msg = run("s:run{ t_end = 0.01, frames = { " + c.frames + " } }", out);
    EXPECT_NE(msg.find("frames.lua:8:"), std::string::npos) << msg;
    EXPECT_NE(msg.find(c.expect), std::string::npos) << "'" << c.expect << "' not in: " << msg;
    EXPECT_FALSE(fs::exists(out / "timeseries.csv")) << "simulated despite: " << msg;
  }
}

TEST(Frames, NoFramesNoContextNoEncoder) {
  const long contexts = render::gl_contexts_created(), encoders = VideoWriter::encoders_created();
  EXPECT_EQ(run("s:run{ t_end = 0.005 }", temp_dir() / "none"), "");
  EXPECT_EQ(run("s:run{ t_end = 0.005, frames = false }", temp_dir() / "none"), "");
  EXPECT_TRUE(fs::exists(temp_dir() / "none" / "timeseries.csv"));
  EXPECT_EQ(render::gl_contexts_created(), contexts);
  EXPECT_EQ(VideoWriter::encoders_created(), encoders);
}

// 0.02 s at 30 frames/s, ten times slower than life: frames every 1/300 s, at 0 ... 0.02 (7)
TEST(Frames, PngAndVideoOnePerFrameTime) {
  const long contexts = render::gl_contexts_created(), encoders = VideoWriter::encoders_created();
  const fs::path out = temp_dir() / "with";
  fs::remove_all(out);
  EXPECT_EQ(run("local r = s:run{ t_end = 0.02, frames = { fps = 30, slowdown = 10, size = {320, 180}, "
                "quantity = 'normal', png = true, video = 'clip.mp4' } }\n"
                "assert(r.frames == 7, 'frames: ' .. tostring(r.frames))",
                out),
            "");
  EXPECT_EQ(render::gl_contexts_created(), contexts + 1);
  EXPECT_EQ(VideoWriter::encoders_created(), encoders + 1);
  int pngs = 0;
  for (const auto& e : fs::directory_iterator(out / "frames")) pngs += e.path().extension() == ".png";
  EXPECT_EQ(pngs, 7);
  EXPECT_TRUE(fs::exists(out / "frames" / "frame_00006.png"));
  EXPECT_EQ(probe(out / "clip.mp4", "stream=codec_name"), "h264");
  EXPECT_EQ(probe(out / "clip.mp4", "stream=nb_read_frames"), "7");
  EXPECT_EQ(probe(out / "clip.mp4", "stream=width"), "320");
}

// a PNG's width and height from its IHDR chunk ({0, 0} when it is no PNG)
std::pair<int, int> png_size(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  unsigned char b[24] = {};
  if (!in.read(reinterpret_cast<char*>(b), sizeof b)) return {0, 0};
  auto be = [&](int at) { return (b[at] << 24) | (b[at + 1] << 16) | (b[at + 2] << 8) | b[at + 3]; };
  return {be(16), be(20)};
}

// odd sizes are only a video's problem (H.264 in yuv420p): PNGs alone take them (they were refused
// citing H.264 with no video asked for); a video still refuses them
TEST(Frames, OddSizesForPngsOnly) {
  const fs::path out = temp_dir() / "odd";
  fs::remove_all(out);
  EXPECT_EQ(run("s:run{ t_end = 0.004, frames = { size = {321, 181}, png = true } }", out), "");
  EXPECT_EQ(png_size(out / "frames" / "frame_00000.png"), std::make_pair(321, 181));
  EXPECT_NE(run("s:run{ t_end = 0.004, frames = { size = {321, 181}, png = true, video = true } }", out)
                .find("run.frames.size: width and height must be even and in 16..8192 px (H.264 in yuv420p) (got "
                      "321x181)"),
            std::string::npos);
}

// the runaway of lua_api_runs_test's divergence test, with a video: the error leaves it finalised
TEST(Frames, DivergenceLeavesAPlayableVideo) {
  const fs::path p = temp_dir() / "runaway.lua";
  std::ofstream(p) << beltsim::test::runaway() +
                      "s:run{ t_end = 0.01, frames = { fps = 25, slowdown = 100, size = {160, 90}, video = true } }\n";
  const fs::path out = temp_dir() / "runaway";
  Interpreter lua;
  Overrides o;
  o.run.out_dir = out.string(), o.give("out");
  lua.set_overrides(o);
  std::string msg;
  try {
    lua.run_file(p.string());
  } catch (const ScriptError& e) {
    msg = e.what();
  }
  ASSERT_NE(msg.find("diverged"), std::string::npos) << msg;
  EXPECT_EQ(probe(out / "frames.mp4", "stream=codec_name"), "h264");
  // frames every 0.4 ms up to the last sound step (measured: 3 frames, the steps grow long
  // before the runaway check fires at 4.6 ms)
  EXPECT_GE(std::stoi("0" + probe(out / "frames.mp4", "stream=nb_read_frames")), 2);
}

// A resumed run's frames go where the saved run's went: its video's continuation beside the video
// and its PNGs numbered on in the same folder, with the output folder given relative to the
// folder beltsim runs in (the default out/<script> is) as well as absolute. Checkpoints keep the
// paths as given; joined to the folder once more, they landed in rel/rel/.
TEST(Frames, AResumedRunsFramesGoWhereTheSavedRunsWent) {
  const fs::path dir = temp_dir() / "resumed";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path was = fs::current_path();
  fs::current_path(dir);
  struct Back {
    fs::path p;
    ~Back() { fs::current_path(p); }
  } back{was};
  // frames every 1/300 s: 0 ... 0.01 before the save (4), then 0.01333 ... 0.02 (3)
  std::ofstream("resume.lua") << kScene
                              << "local sim = s:start{ out = 'rel', frames = { fps = 30, "
                                 "slowdown = 10, size = {160, 90}, png = true, video = true } }\n"
                                 "sim:run_to(0.01)\nsim:save('ck.ckpt')\nsim:close()\n"
                                 "local r = beltsim.resume('rel/ck.ckpt')\nr:run_to(0.02)\nr:close()\n";
  Interpreter lua;
  std::string msg;
  try {
    lua.run_file("resume.lua");
  } catch (const ScriptError& e) {
    msg = e.what();
  }
  ASSERT_EQ(msg, "");
  EXPECT_FALSE(fs::exists("rel/rel")) << "the frames' paths were joined to the folder twice";
  EXPECT_EQ(probe("rel/frames.mp4", "stream=nb_read_frames"), "4");
  EXPECT_EQ(probe("rel/frames_resumed_0.010000.mp4", "stream=nb_read_frames"), "3");
  EXPECT_TRUE(fs::exists("rel/frames/frame_00003.png"));
  EXPECT_TRUE(fs::exists("rel/frames/frame_00006.png"));
}

// the lines of a text file (0 while it does not exist)
int lines_of(const fs::path& p) {
  std::ifstream f(p);
  return static_cast<int>(std::count(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>(), '\n'));
}

// Ctrl-C (the stop flag main() sets from SIGINT) ends the run early; the video is closed
// properly: its trailer (the fragmented MP4's 'mfra' index) is written and it plays.
TEST(Frames, CtrlCLeavesAFinishedVideo) {
  // the drive may shorten and retry implicit steps as it breaks loose (failed_step) before the Ctrl-C
  beltsim::test::expect_warnings({WarningKind::failed_step});
  const fs::path p = temp_dir() / "stopped.lua";
  std::ofstream(p) << kScene
                   << "s:run{ t_end = 1, frames = { size = {320, 180}, video = 'stopped.mp4' } }\n";
  const fs::path out = temp_dir() / "stopped";
  fs::remove_all(out);
  std::atomic<bool> stop{false};
  Interpreter lua;
  Overrides o;
  o.run.out_dir = out.string(), o.give("out");
  lua.set_overrides(o);
  lua.set_stop_flag(&stop);
  // Ctrl-C once the run is under way with its first frame rendered: the time series has rows
  // past t = 0 (the scene's build comes first, which a loaded machine can stretch; a stop then
  // ends the build with an error instead). 60 s at most.
  std::thread ctrl_c([&] {
    const fs::path csv = out / "timeseries.csv";
    for (int i = 0; i < 6000 && lines_of(csv) < 1 + 3; ++i)
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    stop = true;
  });
  EXPECT_NO_THROW(lua.run_file(p.string()));
  ctrl_c.join();
  EXPECT_TRUE(lua.interrupted());
  std::ifstream f(out / "stopped.mp4", std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  EXPECT_NE(bytes.find("mfra"), std::string::npos) << "no trailer: the writer was not closed";
  EXPECT_EQ(probe(out / "stopped.mp4", "stream=codec_name"), "h264");
  EXPECT_GE(std::stoi("0" + probe(out / "stopped.mp4", "stream=nb_read_frames")), 1);
}

// A run that ends before its first frame time (here a live simulation closed at 0.004 s; a trial's
// was stopped by Ctrl-C) left an MP4 of a header alone, which no player opens, without a word: no
// file, and a warning naming it
TEST(Frames, NoFrameBeforeTheEndNoVideo) {
  const fs::path out = temp_dir() / "no_frame";
  fs::remove_all(out);
  fs::create_directories(out);
  std::ofstream(out / "v.mp4") << "an earlier run's";  // replaced, as a run's outputs are
  testing::internal::CaptureStderr();
  const std::string msg =
      run("local sim = s:start{ frames = { t_start = 0.05, size = {320, 180}, video = 'v.mp4' } }\n"
          "sim:run_to(0.004)\nsim:close()",
          out);
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(msg, "");
  EXPECT_FALSE(fs::exists(out / "v.mp4"));
  EXPECT_NE(err.find("beltsim: warning: no frame was drawn before the run ended (frames from t = 0.05 s): no video, " +
                     (out / "v.mp4").string() + " is not written\n"),
            std::string::npos)
      << err;
}

}  // namespace frames_test
}  // namespace beltsim::script
