// The console's input: lines from readline on a terminal (line editing, persistent history,
// completion), plain lines from a pipe otherwise. Either way the wait for input takes the stop
// signals (signals.hpp): Ctrl-C drops the line being typed, SIGTERM and SIGHUP end the input.
#pragma once

#include <functional>
#include <string>
#include <vector>

struct lua_State;

namespace beltsim::script {

class ConsoleInput {
 public:
  // interactive: readline with the history file `history` and completion from L
  ConsoleInput(bool interactive, const std::string& history, lua_State* L);
  ~ConsoleInput();
  ConsoleInput(const ConsoleInput&) = delete;
  ConsoleInput& operator=(const ConsoleInput&) = delete;

  enum class Got { line, cancelled, end };
  // the next line (without its line end): Got::line; Got::cancelled when Ctrl-C dropped it;
  // Got::end at the end of the input (Ctrl-D, the pipe's end, SIGTERM, SIGHUP)
  Got read(const char* prompt, std::string& line);
  // while waiting for input, one of the descriptors fds() gives readable (the live views'
  // controls, live_server.hpp wake_fd; asked anew for each wait) runs f on this thread, and the
  // wait goes on; fds null: none
  void on_wake(std::function<std::vector<int>()> fds, std::function<void()> f);

 private:
  bool interactive_;
  std::string history_;
};

}  // namespace beltsim::script
