// The process's stop signals, one module for every command that has outputs to close (`beltsim
// run`, `wp`, `modes`, `sweep`, `render` and the console).
//
// SIGINT (Ctrl-C), SIGTERM and SIGHUP (the terminal closed, handled as SIGTERM): a run stops at its
// last finished step (the stop flag), Lua code raises "interrupted!" at its next slice of
// instructions (Interpreter::interrupt), and the outputs are closed (CSV rows whole, the video
// finalised). A second stop signal while the first is under way ends the process at once (its
// default action). In the console a Ctrl-C at the prompt only clears the line, and one during a
// command is done with when the command ends (command_done).
//
// A watchdog thread, which needs nothing from Lua, ends the process when Lua does not stop: after
// SIGTERM or SIGHUP, when the host has been inside Lua code (a docall, not beltsim's own C++ work
// such as a run or a video's finalisation) for kGrace without returning, it takes the signal's
// default action; meanwhile it interrupts Lua again every few milliseconds, so that Lua code that
// goes on after a stopped run stops too. This covers what the Lua hook cannot: one long C call such
// as a backtracking string pattern, or a finaliser with --trusted (Lua runs them with hooks off).
// After a Ctrl-C that Lua has not honoured within kGrace it says that a second one ends beltsim.
#pragma once

#include <atomic>
#include <chrono>

#include "script/lua_clock.hpp"  // InsideLua, HostWork: what the host is doing

namespace beltsim::script {

class Interpreter;

inline constexpr std::chrono::milliseconds kGrace{500};

// installs the handlers of SIGINT, SIGTERM and SIGHUP and starts the watchdog (once, from the
// main thread: a signal that lands on another thread is passed on to it; later calls do nothing)
void install_stop_signals();
// the flag a run polls: set by a stop signal
std::atomic<bool>& stop_flag();
// the first stop signal the process received (SIGINT, SIGTERM or SIGHUP), or 0
int stop_signal();
// SIGTERM or SIGHUP was received: the process is to end
bool terminating();
// the stop under way: the signal that stopped the console's command now running (SIGINT, SIGTERM
// or SIGHUP), or 0
int pending_signal();
// "Ctrl-C" (SIGINT), "SIGTERM" or "SIGHUP"
const char* signal_name(int sig);
// the name of the signal that stopped the command now running (pending_signal), "Ctrl-C" when
// none is under way (a run the page paused, stopped by a Ctrl-C since done with)
const char* pending_signal_name();
// after a stop: "beltsim: interrupted|terminated|hung up; the outputs written so far are kept" on
// stderr, and 128 + the signal's number
int stopped_status();

// the console: a Ctrl-C while the prompt waits clears the line instead (take_prompt_interrupt)
void set_at_prompt(bool at_prompt);
// true (once) when a Ctrl-C came while at the prompt
bool take_prompt_interrupt();
// the console's command has ended: the stop flag is lowered and a Ctrl-C it received is done with
// (the next one stops the next command instead of ending the process)
void command_done();

// the interpreter whose Lua code the signals interrupt, for the guard's lifetime
class Interruptible {
 public:
  explicit Interruptible(Interpreter& lua);
  ~Interruptible();
  Interruptible(const Interruptible&) = delete;
  Interruptible& operator=(const Interruptible&) = delete;
};

}  // namespace beltsim::script
