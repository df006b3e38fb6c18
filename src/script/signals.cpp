#include "script/signals.hpp"

#include <fcntl.h>
#include <pthread.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <mutex>
#include <string>
#include <thread>

#include "script/interpreter.hpp"
#include "script/progress.hpp"

namespace beltsim::script {

namespace {

// Atomics, not volatile sig_atomic_t: the watchdog thread reads them while the handler (on the
// main thread, see on_signal) writes them; lock-free, so safe in a handler
std::atomic<bool> g_stop{false};
std::atomic<int> g_first{0};    // the first stop signal of the process
std::atomic<int> g_pending{0};  // the stop under way (a console command's Ctrl-C is done with at its end)
std::atomic<bool> g_at_prompt{false}, g_prompt_sigint{false};
std::atomic<Interpreter*> g_lua{nullptr};
int g_wake[2] = {-1, -1};  // the handler writes the signal's number, the watchdog reads it
pthread_t g_main;          // the thread that installed the handlers: the one that runs Lua
static_assert(std::atomic<int>::is_always_lock_free && std::atomic<bool>::is_always_lock_free &&
              std::atomic<Interpreter*>::is_always_lock_free);

// the watchdog's interrupt() against an interpreter going away (never destroyed: the watchdog
// may still run while the process exits)
std::mutex& lua_mutex() {
  static auto* m = new std::mutex;
  return *m;
}

// the line a second stop signal ends the process with: it quits at once, so the outputs are not
// closed (docs/outputs.md, Signals). One write(2) of a line built without allocating (safe in a
// handler)
void say_quit(int sig) {
  char line[320];
  size_t n = 0;
  for (const char* part : {"\nbeltsim: ", signal_name(sig),
                           " while stopping: quitting at once, without finishing the outputs: their rows so far are "
                           "kept whole, but parameters.csv gets no end rows and a video holds only its finished "
                           "fragments\n"})
    for (const char* c = part; *c && n < sizeof line; ++c) line[n++] = *c;
  [[maybe_unused]] const ssize_t w = write(STDERR_FILENO, line, n);
}

void on_signal(int sig) {
  const int saved_errno = errno;
  // a signal sent to the process may land on any thread that does not block it (the encoder's,
  // llvmpipe's): it goes on to the main thread, whose Lua state the handler interrupts and whose
  // waits (the console's ppoll) it must wake
  if (!pthread_equal(pthread_self(), g_main)) {
    pthread_kill(g_main, sig);
    errno = saved_errno;
    return;
  }
  if (sig == SIGINT && g_at_prompt.load()) {
    g_prompt_sigint.store(true);  // the console's ppoll returns EINTR and clears the line
    errno = saved_errno;
    return;
  }
  int none = 0;
  if (!g_pending.compare_exchange_strong(none, sig)) {  // a stop is under way: this one ends the process
    say_quit(sig);
    restore_echo();  // a progress line's (progress.hpp): the process ends without unwinding
    std::signal(sig, SIG_DFL);
    std::raise(sig);  // blocked in this thread until this handler returns, then fatal
    return;
  }
  int zero = 0;
  g_first.compare_exchange_strong(zero, sig);
  g_stop.store(true);                              // a run stops at its last finished step
  if (auto* lua = g_lua.load()) lua->interrupt();  // Lua code stops at its next instructions
  const char c = static_cast<char>(sig);
  [[maybe_unused]] const ssize_t n = write(g_wake[1], &c, 1);  // non-blocking: never waits here
  errno = saved_errno;
}

void say_raw(const std::string& s) {
  [[maybe_unused]] const ssize_t n = write(STDERR_FILENO, s.data(), s.size());
}

// waits while the host runs Lua code; true when it has been inside one Lua call for kGrace
// without leaving it (the mode unchanged); `still` says whether to go on watching, `tick` runs
// at every look
template <class Still, class Tick>
bool stuck_in_lua(Still still, Tick tick) {
  using clock = std::chrono::steady_clock;
  bool inside = false;
  unsigned seen = 0;
  clock::time_point since;
  while (still()) {
    tick();
    const unsigned changes = lua_mode_changes();
    if (lua_mode() != LuaMode::kLua) {
      inside = false;
    } else if (!inside || changes != seen) {
      inside = true;
      seen = changes;
      since = clock::now();
    } else if (clock::now() - since >= kGrace) {
      return true;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

void interrupt_lua() {
  const std::lock_guard<std::mutex> lock(lua_mutex());
  if (auto* lua = g_lua.load()) lua->interrupt();
}

void watchdog() {
  for (;;) {
    char c = 0;
    const ssize_t n = read(g_wake[0], &c, 1);
    if (n != 1) {
      if (n < 0 && errno == EINTR) continue;
      return;
    }
    const int sig = c;
    if (sig == SIGINT) {
      // a Ctrl-C that Lua does not honour: say what the next one does (once)
      if (stuck_in_lua([] { return g_pending.load() == SIGINT; }, [] {}))
        say_raw(
            "\nbeltsim: the Lua code under way does not stop (a long C call such as a string pattern, or code that "
            "runs with hooks off); Ctrl-C again ends beltsim\n");
      continue;
    }
    // SIGTERM, SIGHUP: Lua code that goes on after a stopped run is interrupted again; Lua that
    // does not return ends the process
    if (stuck_in_lua([] { return true; }, interrupt_lua)) {
      say_raw(std::string("\nbeltsim: the Lua code under way did not stop within ") + std::to_string(kGrace.count()) +
              " ms of " + signal_name(sig) +
              " (a long C call such as a string pattern, or code that runs with hooks off); "
              "ending now; the outputs written so far are kept\n");
      restore_echo();
      std::signal(sig, SIG_DFL);
      kill(getpid(), sig);
      return;
    }
  }
}

}  // namespace

void install_stop_signals() {
  static bool installed = false;
  if (installed) return;
  installed = true;
  g_main = pthread_self();
  if (pipe2(g_wake, O_CLOEXEC) == 0) {
    fcntl(g_wake[1], F_SETFL, O_NONBLOCK);
    // the watchdog takes no signals itself (they go to the threads that run the handlers' work)
    sigset_t all, old;
    sigfillset(&all);
    pthread_sigmask(SIG_SETMASK, &all, &old);
    std::thread(watchdog).detach();
    pthread_sigmask(SIG_SETMASK, &old, nullptr);
  }
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&sa.sa_mask, s);  // one handler at a time in a thread
  sa.sa_flags = SA_RESTART;  // the console's waits (ppoll) return EINTR all the same
  for (int s : {SIGINT, SIGTERM, SIGHUP}) sigaction(s, &sa, nullptr);
}

std::atomic<bool>& stop_flag() {
  return g_stop;
}
int stop_signal() {
  return g_first.load();
}
int pending_signal() {
  return g_pending.load();
}
const char* signal_name(int sig) {
  return sig == SIGINT ? "Ctrl-C" : sig == SIGHUP ? "SIGHUP" : "SIGTERM";
}
const char* pending_signal_name() {
  const int sig = g_pending.load();
  return signal_name(sig ? sig : SIGINT);
}
bool terminating() {
  const int s = g_pending.load();
  return s == SIGTERM || s == SIGHUP;
}

int stopped_status() {
  const int sig = terminating() ? g_pending.load() : g_first != 0 ? g_first.load() : SIGINT;
  say("beltsim: %s; the outputs written so far are kept\n", sig == SIGTERM  ? "terminated"
                                                            : sig == SIGHUP ? "hung up (SIGHUP)"
                                                                            : "interrupted");
  return 128 + sig;
}

void set_at_prompt(bool at_prompt) {
  g_at_prompt.store(at_prompt);
}
bool take_prompt_interrupt() {
  return g_prompt_sigint.exchange(false);
}

void command_done() {
  int sigint = SIGINT;
  if (g_pending.compare_exchange_strong(sigint, 0) || g_pending.load() == 0) g_stop.store(false);
}

Interruptible::Interruptible(Interpreter& lua) {
  g_lua.store(&lua);
}
Interruptible::~Interruptible() {
  const std::lock_guard<std::mutex> lock(lua_mutex());
  g_lua.store(nullptr);
}

}  // namespace beltsim::script
