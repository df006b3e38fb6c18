#include "script/console.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iterator>
#include <regex>
#include <set>
#include <vector>

#include "beltsim_version.hpp"
#include "io/input_file.hpp"
#include "io/output_dir.hpp"
#include "lauxlib.h"
#include "live/live_server.hpp"
#include "lua.h"
#include "script/console_input.hpp"
#include "script/console_print.hpp"
#include "script/console_session.hpp"
#include "script/context.hpp"
#include "script/docall.hpp"
#include "script/interpreter.hpp"
#include "script/limits.hpp"
#include "script/live_feed.hpp"
#include "script/lua_run.hpp"
#include "script/progress.hpp"
#include "script/signals.hpp"
#include "sweep/results.hpp"

namespace beltsim::script {

namespace {

// the console's commands are the chunk "stdin": its errors read "stdin:LINE:", as lua.c's
constexpr const char* kChunkName = "=stdin";

enum class Compile { ok, incomplete, error };

// lua.c: try "return <chunk>" first, so that an expression prints its value
Compile compile(lua_State* L, const std::string& chunk, bool& expression) {
  const std::string ret = "return " + chunk + ";";
  if (luaL_loadbufferx(L, ret.data(), ret.size(), kChunkName, "t") == LUA_OK) {
    expression = true;
    return Compile::ok;
  }
  lua_pop(L, 1);
  expression = false;
  const int status = luaL_loadbufferx(L, chunk.data(), chunk.size(), kChunkName, "t");
  if (status == LUA_OK) return Compile::ok;
  size_t len = 0;
  const char* msg = lua_tolstring(L, -1, &len);
  if (status == LUA_ERRSYNTAX && len >= 5 && std::strcmp(msg + len - 5, "<eof>") == 0) {
    lua_pop(L, 1);
    return Compile::incomplete;
  }
  return Compile::error;
}

// an output lost that the message names is not named again at exit (main.cpp)
void report(const CallError& e, const char* prefix = "") {
  say("%s%s\n%s", prefix, e.message.c_str(), shown_traceback(e.traceback).c_str());
  std::fflush(stderr);
  mark_output_failure_shown(e.message);
}

// runs the compiled chunk on the stack top and prints its results, each a call through docall
// within the command's instruction budget. True when the chunk ran without error (else `failure`
// holds the error's message); `printed`: it returned values, which were printed.
bool execute(lua_State* L, std::string& failure, bool& printed) {
  printed = false;
  const int base = lua_gettop(L) - 1;  // below the chunk
  begin_call(L);                       // the instruction budget is per command; no Ctrl-C pending
  CallError error;
  if (!docall(L, 0, LUA_MULTRET, &error, "stdin")) {
    report(error);
    failure = error.message;
    return false;
  }
  if (lua_gettop(L) > base) {
    // the results, printed (a __tostring is Lua code); the command itself has run
    printed = true;
    lua_pushcfunction(L, print_values);
    lua_insert(L, base + 1);
    if (!docall(L, lua_gettop(L) - base - 1, 0, &error, "stdin")) report(error, "printing the result: ");
  }
  lua_settop(L, base);
  return true;
}

// the global table's string keys, sorted
std::vector<std::string> global_names(lua_State* L) {
  std::vector<std::string> names;
  lua_pushglobaltable(L);
  lua_pushnil(L);
  while (lua_next(L, -2) != 0) {
    if (lua_type(L, -2) == LUA_TSTRING) names.emplace_back(lua_tostring(L, -2));
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  std::sort(names.begin(), names.end());
  return names;
}

// what the banner says of the script's globals: the names it left, or how to leave one (a
// script's locals end with it, and a batch script such as paper_dry.lua keeps none)
std::string globals_line(const std::string& script, const std::vector<std::string>& before,
                         const std::vector<std::string>& after) {
  std::vector<std::string> added;
  std::set_difference(after.begin(), after.end(), before.begin(), before.end(), std::back_inserter(added));
  const std::string name = std::filesystem::path(script).filename().string();
  if (added.empty())
    return name +
           " left no globals (its locals end with it): write sim = drive:start{...} without `local` to "
           "keep a simulation here, as scripts/live_dry.lua does\n";
  std::string s = "globals from " + name + ":";
  for (size_t k = 0; k < added.size(); ++k) s += (k ? ", " : " ") + added[k];
  return s + "\n";
}

// a bare word lua.c's users type (Python's): `help` runs help(), `exit` and `quit` leave as Ctrl-D
// does, unless the session gave the name a value of its own
enum class Word { none, help, leave };
Word bare_word(lua_State* L, const std::string& chunk) {
  const size_t b = chunk.find_first_not_of(" \t"), e = chunk.find_last_not_of(" \t");
  const std::string w = b == std::string::npos ? "" : chunk.substr(b, e - b + 1);
  const bool help = w == "help", leave = w == "exit" || w == "quit" || w == "exit()" || w == "quit()";
  if (!help && !leave) return Word::none;
  const std::string global = w.substr(0, 4);
  lua_getglobal(L, global.c_str());
  const int type = lua_type(L, -1);
  lua_pop(L, 1);
  if (help) return type == LUA_TFUNCTION ? Word::help : Word::none;  // the API's help, not a value of the user's
  return type == LUA_TNIL ? Word::leave : Word::none;
}

// the names a command declared with `local` (`local a, b = ...`, `local function f`): at the
// prompt each lives for its own command only
std::vector<std::string> declared_locals(const std::string& chunk) {
  static const std::regex decl(
      R"((?:^|[\n;])\s*local\s+(?:function\s+)?([A-Za-z_]\w*(?:\s*<\w+>)?(?:\s*,\s*[A-Za-z_]\w*(?:\s*<\w+>)?)*))");
  static const std::regex name(R"([A-Za-z_]\w*)");
  std::vector<std::string> names;
  for (std::sregex_iterator d(chunk.begin(), chunk.end(), decl), end; d != end; ++d) {
    const std::string list = (*d)[1].str();
    for (std::sregex_iterator n(list.begin(), list.end(), name); n != end; ++n)
      if (const std::string w = n->str(); w != "const" && w != "close") names.push_back(w);
  }
  return names;
}

// a failed command's note when its error is about a nil and it uses a name an earlier command
// declared `local` that is no global now: that local ended with its own command
std::string local_note(lua_State* L, const std::string& chunk, const std::string& failure,
                       const std::set<std::string>& earlier_locals) {
  if (failure.find("nil") == std::string::npos) return "";
  std::vector<std::string> names;
  for (const std::string& n : earlier_locals) {
    if (!std::regex_search(chunk, std::regex("(^|[^.:\\w])" + n + "\\b"))) continue;
    const bool global = lua_getglobal(L, n.c_str()) != LUA_TNIL;
    lua_pop(L, 1);
    if (!global) names.push_back(n);
  }
  if (names.empty()) return "";
  std::string list;
  for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
  return "note: " + list + (names.size() > 1 ? " were" : " was") +
         " declared `local` on an earlier line, and a local at the prompt lasts for its own line only: "
         "declare it without `local` to keep it\n";
}

}  // namespace

int run_console(const std::optional<std::string>& script, const std::vector<std::string>& args, const Overrides& o,
                const Safety& safety, const ConsoleSettings& settings) {
  const bool interactive = isatty(STDIN_FILENO);
  // the folder session.lua goes to (the runs' default: out/<script name>, or out/console): one that
  // holds a study of `beltsim sweep` is refused before the script runs, as a run into it is
  // (sweep::study_folder_refusal); session.lua among the study's points was read for part of it
  const std::string session_dir = o.has("out") ? o.run.out_dir : script ? default_out_dir(*script) : "out/console";
  if (const std::vector<std::string> names = sweep::study_parameters(session_dir); !names.empty()) {
    std::string varied;
    for (const std::string& n : names) varied += (varied.empty() ? "" : ", ") + n;
    say("beltsim: console: the folder %s, where this session's runs and session.lua would go, holds a "
        "study of `beltsim sweep` (its points vary %s): give the console a folder of its own (--out DIR), "
        "or remove %s first\n",
        session_dir.c_str(), varied.c_str(), session_dir.c_str());
    return 1;
  }
  Interpreter lua(safety);
  lua.set_overrides(o);
  lua.set_stop_flag(&stop_flag());
  if (o.serve) lua.serve(*o.serve);
  const Interruptible on_signal(lua);
  lua_State* L = lua.state();
  Context& ctx = lua.context();
  const bool tty_out = isatty(STDOUT_FILENO);
  ctx.interactive = true;
  ctx.on_picture = [tty_out, mode = settings.images](const std::string& png) {
    std::string why;
    if (!(tty_out || mode != term::ImageMode::automatic) || !term::show_image_in_terminal(png, stdout, mode, &why))
      std::printf("picture: %s\n", png.c_str());
    std::fflush(stdout);
  };
  // arg as lua.c makes it: arg[0] the script, arg[1..] what follows --
  lua_createtable(L, static_cast<int>(args.size()), 1);
  if (script) lua_pushstring(L, script->c_str()), lua_rawseti(L, -2, 0);
  for (size_t k = 0; k < args.size(); ++k)
    lua_pushstring(L, args[k].c_str()), lua_rawseti(L, -2, static_cast<int>(k + 1));
  lua_setglobal(L, "arg");

  bool failed = false;
  SessionStart start{session_dir, script, "", args, o.set, settings.replay_options, {}, "", ""};
  std::string& script_text = start.script_text;  // as it was when the session began, for session.lua
  std::string globals;      // the banner's line on the script's globals
  if (script) {
    const std::vector<std::string> before = global_names(L);
    try {  // a regular file only, as run_file reads it (which says why not)
      InputFile in(*script);
      script_text = in.read_rest();
    } catch (const InputFileError&) {
    }
    try {
      lua.run_file(*script);
      for (const std::string& m : lua.unread_args(*script)) say("beltsim: warning: %s\n", m.c_str());
      globals = globals_line(*script, before, global_names(L));
    } catch (const ScriptError& e) {
      say("beltsim: %s\n%s", e.what(), shown_traceback(e.traceback).c_str());  // as run's
      mark_output_failure_shown(e.what());
      failed = true;
      start.scenario_error = e.what();
    }
    // a run that a stop signal stopped (the first: the later ones were refused) is replayed to there
    if (!ctx.stopped_runs.empty()) {
      start.scenario_stop = ctx.stopped_runs.front().second;
      start.scenario_stopped_by = pending_signal_name();
    }
    command_done();
  } else {
    ctx.default_out = "out/console";
  }

  if (interactive) {
    std::printf("beltsim %s console (Lua 5.4): help() lists the API; Ctrl-C stops a run, Ctrl-D leaves\n%s",
                kBeltsimVersion, globals.c_str());
    std::fflush(stdout);
  }
  // session.lua, written again after each command; the replay gets --out DIR/replay when every
  // run of the session went into session_dir: a session whose runs named their own folders is
  // replayed into them again. A session that resumed a checkpoint names session_dir in it
  // (beltsim.replay_of): its replay resumes its own copies of the checkpoints saved there
  SessionFile session(start);
  std::vector<std::string> commands;
  const auto write_session = [&] {
    bool runs_in_dir = true;
    for (const std::string& d : ctx.run_dirs) runs_in_dir = runs_in_dir && d == run_dir_key(session_dir);
    return session.write(commands, runs_in_dir, ctx.resumed);
  };
  const auto record = [&](std::string command) {
    commands.push_back(std::move(command));
    write_session();
  };
  {
    ConsoleInput input(interactive, settings.history, L);
    // the pages' changes while the console waits at its prompt (--serve's, and each sim:serve{}'s):
    // applied as they come, on this thread (no command runs), to the simulation each page shows,
    // and recorded in session.lua; a page that opens gets the picture of now
    input.on_wake(
        [&] {
          std::vector<int> fds;
          if (ctx.serve) fds.push_back(ctx.serve->wake_fd());
          for (const auto& [key, served] : ctx.served) fds.push_back(served.first->wake_fd());
          return fds;
        },
        [&] {
          std::vector<PageChange> changes;
          if (ctx.serve) {
            ctx.serve->clear_wake();
            LiveFeed(ctx.serve.get(), ctx.stop, &changes, ctx.page_key).apply_waiting(ctx.page_sim);
          }
          // a copy: a change cannot close a simulation, but the map must not move under the loop
          const auto served = ctx.served;
          for (const auto& [key, s] : served) {
            s.first->clear_wake();
            LiveFeed(s.first, ctx.stop, &changes, key).apply_waiting(s.second);
          }
          if (const std::string s = at_prompt(L, changes); !s.empty()) record(s);
        });
    std::string chunk, line, failure;
    std::set<std::string> earlier_locals;  // declared `local` by a command before (local_note)
    bool printed = false;  // the command's values were printed (session.lua prints them again)
    long ended = 0;  // progress lines ended before the command (progress.hpp)
    while (!terminating()) {
      const ConsoleInput::Got got = input.read(chunk.empty() ? "> " : ">> ", line);
      if (got == ConsoleInput::Got::end) {
        if (interactive) {
          std::printf("\n");
        } else if (!chunk.empty() && !terminating()) {
          say("beltsim: stdin: unfinished input at the end: %s\n", chunk.c_str());
          failed = true;
        }
        break;
      }
      if (got == ConsoleInput::Got::cancelled) {
        chunk.clear();
        continue;
      }
      chunk = chunk.empty() ? line : chunk + "\n" + line;
      if (chunk.find_first_not_of(" \t") == std::string::npos) {
        chunk.clear();
        continue;
      }
      const Word word = bare_word(L, chunk);
      if (word == Word::leave) break;
      if (word == Word::help) chunk = "help()";
      bool expression = false;
      const Compile c = compile(L, chunk, expression);
      if (c == Compile::incomplete) continue;
      if (c == Compile::error) {
        say("%s\n", lua_tostring(L, -1));
        lua_pop(L, 1);
        failed = true;
      } else if (ctx.stopped_runs.clear(), ctx.page_changes.clear(), ended = progress_lines_ended(),
                 ctx.interrupted = false, execute(L, failure, printed)) {
        record(replayable(L, chunk, expression, printed, ctx.stopped_runs, ctx.page_changes));
      } else {
        // it ran up to its error: what it changed before (a run stopped where its callback raised)
        // is replayed too
        record(failed_replayable(L, chunk, expression, failure, ctx.stopped_runs, ctx.page_changes));
        if (const std::string note = local_note(L, chunk, failure, earlier_locals); !note.empty())
          say("%s", note.c_str());
        failed = true;
      }
      for (const std::string& n : declared_locals(chunk)) earlier_locals.insert(n);
      // the terminal echoed ^C where a run (a live simulation's or a scene:run) was stopped; unless
      // a progress line ended that line, the next prompt would follow it there ("^C> ")
      if (interactive && tty_out && ctx.interrupted && progress_lines_ended() == ended) std::printf("\n");
      command_done();
      chunk.clear();
    }
  }
  // the finalisers below run with a fresh budget (~Interpreter)
  // once more at the end (a write that failed is tried again)
  const bool written = write_session();
  if (written && !commands.empty()) say("beltsim: the session's commands are in %s\n", session.path().c_str());
  // the interpreter's end closes every simulation (their finalisers flush and finalise outputs)
  if (terminating()) return stopped_status();
  if (!written) return 1;
  return interactive ? 0 : (failed ? 1 : 0);
}

}  // namespace beltsim::script
