#include "script/console_input.hpp"

#include <poll.h>
#include <readline/history.h>
#include <readline/readline.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "script/console_complete.hpp"
#include "script/signals.hpp"

namespace beltsim::script {

namespace {

bool g_cancelled = false;  // Ctrl-C dropped the line being read
std::function<std::vector<int>()> g_wake_fds;  // ConsoleInput::on_wake
std::function<void()> g_on_wake;

// one character of input. The stop signals are blocked except while waiting in ppoll, so one that
// comes while readline is busy (echoing, redrawing) is seen at the next wait instead of being
// lost: SIGTERM or SIGHUP ends the input (EOF), a Ctrl-C at the prompt ends the line, emptied.
int next_char(FILE* f) {
  sigset_t block, orig;
  sigemptyset(&block);
  for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&block, s);
  for (;;) {
    sigprocmask(SIG_BLOCK, &block, &orig);
    if (terminating()) {  // the line is dropped (not run), then the input ends as for Ctrl-D
      sigprocmask(SIG_SETMASK, &orig, nullptr);
      if (rl_line_buffer) rl_replace_line("", 0);
      return EOF;
    }
    if (take_prompt_interrupt()) {
      sigprocmask(SIG_SETMASK, &orig, nullptr);
      g_cancelled = true;
      if (rl_line_buffer) rl_replace_line("", 0);
      return '\n';
    }
    std::vector<pollfd> p{{fileno(f), POLLIN, 0}};
    if (g_wake_fds)
      for (const int fd : g_wake_fds()) p.push_back({fd, POLLIN, 0});
    const int r = ppoll(p.data(), p.size(), nullptr, &orig);  // the signals may arrive only while waiting here
    sigprocmask(SIG_SETMASK, &orig, nullptr);
    if (r < 0) {
      if (errno == EINTR) continue;
      return EOF;
    }
    bool woken = false;
    for (size_t k = 1; k < p.size(); ++k) woken = woken || (p[k].revents & POLLIN);
    if (woken) {
      // what the wake prints (a live-view change's report) goes on lines of its own above the
      // prompt, which is drawn again under it with the line being typed, as readline programs
      // print what comes while they read (a user's trial saw a warning written after the "> "
      // and no prompt under it)
      const bool reading = rl_line_buffer && RL_ISSTATE(RL_STATE_READCMD);
      char* line = nullptr;
      const int point = rl_point;
      if (reading) {
        line = rl_copy_text(0, rl_end);
        rl_save_prompt();
        rl_replace_line("", 0);
        rl_redisplay();
      }
      g_on_wake();
      if (reading) {
        rl_restore_prompt();
        rl_replace_line(line, 0);
        rl_point = point;
        rl_redisplay();
        std::free(line);
      }
      if (!(p[0].revents & (POLLIN | POLLHUP))) continue;
    }
    unsigned char c;
    const ssize_t n = ::read(fileno(f), &c, 1);
    if (n == 1) return c;
    if (n == 0) return EOF;
    if (errno != EINTR) return EOF;
  }
}

}  // namespace

ConsoleInput::ConsoleInput(bool interactive, const std::string& history, lua_State* L)
    : interactive_(interactive), history_(history) {
  if (!interactive_) return;
  rl_readline_name = "beltsim";
  rl_catch_signals = 0;
  rl_getc_function = next_char;
  complete_from(L);
  rl_basic_word_break_characters = const_cast<char*>(" \t\n\"\\'><=;+-*/%^~#{}()[],");
  using_history();
  // append_history does not create the file: make it on first use
  if (std::FILE* f = std::fopen(history_.c_str(), "a")) std::fclose(f);
  read_history(history_.c_str());
}

ConsoleInput::~ConsoleInput() {
  on_wake(nullptr, nullptr);
  if (interactive_) complete_from(nullptr);
}

void ConsoleInput::on_wake(std::function<std::vector<int>()> fds, std::function<void()> f) {
  g_wake_fds = std::move(fds);
  g_on_wake = std::move(f);
}

ConsoleInput::Got ConsoleInput::read(const char* prompt, std::string& line) {
  line.clear();
  g_cancelled = false;
  set_at_prompt(true);
  if (interactive_) {
    char* in = readline(prompt);
    set_at_prompt(false);
    if (!in) return Got::end;
    line = in;
    std::free(in);
    if (g_cancelled) return Got::cancelled;
    if (!line.empty()) {
      add_history(line.c_str());
      append_history(1, history_.c_str());
      history_truncate_file(history_.c_str(), 1000);
    }
    return Got::line;
  }
  // a pipe: one byte at a time (no read-ahead past the line, which the commands do not share)
  for (;;) {
    const int c = next_char(stdin);
    if (g_cancelled) {
      set_at_prompt(false);
      return Got::cancelled;
    }
    if (c == EOF) {
      set_at_prompt(false);
      return line.empty() || terminating() ? Got::end : Got::line;
    }
    if (c == '\n') break;
    line += static_cast<char>(c);
  }
  set_at_prompt(false);
  return Got::line;
}

}  // namespace beltsim::script
