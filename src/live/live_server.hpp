// The live view's HTTP server (docs/live-view.md): one page, its plotting library's two files
// (Debian's libjs-dygraphs, read from where Debian puts them), and a stream of the run's samples
// (server-sent events), on cpp-httplib's threads. Nothing here touches a simulation: the loop that
// owns it publishes samples (publish, cheap: a copy under a lock) and the server's threads send
// them. A client that reads slowly skips samples (it gets the latest ones); the history a client
// gets when it connects is bounded (thinned as the run grows). Every request needs the token
// (?token=...) printed at the start, or gets 403.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

namespace httplib {
class Server;
}

namespace beltsim::live {

struct ServeSettings {
  std::string host = "127.0.0.1";  // any other address must be asked for
  int port = 0;                    // 0: a free port
  // where the page's plotting library lives (Debian's libjs-dygraphs)
  std::string assets = "/usr/share/javascript/dygraphs";
};

// a control from the page (POST /control?do=...): pause, continue, run_to (value: t [s]), torque
// (pulley, value [N·m]), wet (from, to [m], value: μ), save (name: a bare file name)
struct Command {
  std::string what;
  std::string pulley;
  double value = 0;
  double from = 0, to = 0;
  std::string name;
};
// the control of a request's parameters (param: its value, "" when absent); "" or why it is refused
std::string read_command(const std::function<std::string(const char*)>& param, Command& c);

// where the renderer drew an element in a frame (its centre, in pixels from the picture's top left)
// and its belt coordinate s [m] (scene/scene_types.hpp, ElementSite::s): the page picks a stretch on the picture
struct ElementAt {
  double x = 0, y = 0, s = 0;
};

// one sample as the page gets it
struct Sample {
  double t = 0;                // [s] simulated time
  double ratio = 0;            // wall seconds per simulated second so far
  double h = 0;                // [s] the last step's size
  std::vector<double> values;  // the columns' values (begin_run)
};

class LiveServer {
 public:
  // binds host:port and serves on threads of its own; throws std::runtime_error naming host:port
  // when it cannot bind, and naming the file when the plotting library is missing
  explicit LiveServer(const ServeSettings& s);
  ~LiveServer();  // stops serving: the streams end, the threads are joined
  LiveServer(const LiveServer&) = delete;
  LiveServer& operator=(const LiveServer&) = delete;

  int port() const { return port_; }
  const std::string& token() const { return token_; }
  std::string url() const;  // http://host:port/?token=...

  // ---- from the owning loop ----------------------------------------------------------------
  // a run starts: its name (the output folder) and the columns its samples carry; the history is
  // cleared unless key (the simulation's Simulation::id, never 0) is that of the run before (a
  // live simulation going on). Not its address: a simulation gone leaves it to the next one (two
  // scene:run{} in a row), whose run kept the first's plot, name and columns
  void begin_run(std::uint64_t key, const std::string& name, std::vector<std::string> columns,
                 std::vector<std::string> pulleys);
  void publish(Sample s);
  // the run's state as the page shows it ("running", "paused", "finished", ...)
  void set_status(const std::string& status);
  // the run the page shows has ended and left no simulation to change (a scene:run{} done): until
  // the next begin_run every control is refused at once (409, "refused: torque: WHY"), and those
  // waiting are dropped, the status saying so
  void refuse_controls(const std::string& why);
  // the latest frame (a JPEG file's bytes), drawn at t, with where its elements are on it (the belt
  // `length` [m] long): the page's picture (the stream says "event: frame" with its t, the page
  // gets /frame.jpg and /frame.json); the frame before is dropped
  void set_frame(std::string jpeg, double t, const std::vector<ElementAt>& elements, double length);
  // the latest frame has been fetched by a page (or there is none yet): a next one is worth drawing
  bool frame_wanted() const;
  // a control is waiting (cheap: one atomic load, for every step)
  bool commands_pending() const { return pending_.load(std::memory_order_relaxed) > 0; }
  // the next control, in the order they came; wait: up to 0.2 s for one
  std::optional<Command> take(bool wait);
  // the server is being stopped
  bool stopping() const;
  // the number of streams open now
  int clients() const;
  // readable when a control has come (an eventfd): a console waiting at its prompt polls it beside
  // its input; clear_wake() reads it empty
  int wake_fd() const { return wake_fd_; }
  void clear_wake();
  // a page has opened its stream since the last call (it also makes wake_fd readable): a console
  // at its prompt draws the picture where the simulation stands for it
  bool take_page_opened();

  // the history kept for a client that connects later is thinned to at most this many samples
  static constexpr size_t kHistory = 4000;
  // a client further behind than this many samples skips to the latest
  static constexpr size_t kBehind = 200;
  // controls waiting beyond this many are refused (503)
  static constexpr size_t kCommands = 64;

 private:
  struct Entry {
    std::uint64_t seq;
    Sample s;
  };
  // where one stream stands: the run, the last sample and the status it was sent
  struct Cursor {
    std::uint64_t run = 0, seq = 0, status = 0, frame = 0;
  };
  void routes();
  void wake();  // wake_fd readable
  std::string stream_text(Cursor& c);

  ServeSettings settings_;
  std::string token_, assets_js_, assets_css_;
  int port_ = 0;
  int wake_fd_ = -1;
  std::unique_ptr<httplib::Server> http_;
  std::thread thread_;

  mutable std::mutex m_;
  std::condition_variable cv_;
  bool stopping_ = false;
  int clients_ = 0;
  bool page_opened_ = false;
  // the run's number (a stream that has sent none is at 0), the last sample's, the status's
  std::uint64_t run_ = 1, seq_ = 0, status_serial_ = 1;
  std::uint64_t key_ = 0;  // the run's simulation (Simulation::id; 0: none yet)
  std::string run_name_, status_ = "waiting";
  std::vector<std::string> columns_, pulleys_;
  std::deque<Command> commands_;
  std::string refusal_;  // refuse_controls' reason ("": controls are queued)
  std::atomic<int> pending_{0};
  std::shared_ptr<const std::string> frame_;             // the latest frame, sent as it is when asked for
  std::shared_ptr<const std::string> frame_json_;        // its t and elements (/frame.json)
  std::uint64_t frame_serial_ = 0, fetched_serial_ = 0;  // the latest frame's, the last one fetched
  double frame_t_ = 0;
  std::deque<Entry> history_, recent_;  // thinned from the start; the last kBehind
  size_t thin_ = 1, skipped_ = 0;       // keep one sample in thin_ (the history thinned as it grows)
};

// the page (live/page.cpp)
const char* page_html();

}  // namespace beltsim::live
