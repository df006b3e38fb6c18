#include "script/console_session.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include "io/number_text.hpp"
#include "io/output_dir.hpp"
#include "io/shell_word.hpp"
#include "lauxlib.h"
#include "lua.h"
#include "script/console_print.hpp"
#include "script/progress.hpp"
#include "script/signals.hpp"

namespace beltsim::script {

namespace {

// the name of the global holding the value with this address, or ""
std::string global_named(lua_State* L, const void* p) {
  std::string name;
  lua_pushglobaltable(L);
  lua_pushnil(L);
  while (lua_next(L, -2)) {
    if (lua_type(L, -2) == LUA_TSTRING && lua_topointer(L, -1) == p) name = lua_tostring(L, -2);
    lua_pop(L, 1);
  }
  lua_pop(L, 1);
  return name;
}

// `text` as a Lua long string: [==[ ... ]==] with as many '=' as it takes
std::string long_string(const std::string& text) {
  std::string eq;
  while (text.find("]" + eq + "]") != std::string::npos) eq += '=';
  return "[" + eq + "[\n" + text + "\n]" + eq + "]";  // the first newline is not part of the string
}

// true when `text` compiles as a Lua chunk (nothing is run)
bool compiles(lua_State* L, const std::string& text) {
  const bool ok = luaL_loadbufferx(L, text.data(), text.size(), "=session", "t") == LUA_OK;
  lua_pop(L, 1);
  return ok;
}

// true when the word occurs in text as a word (perhaps inside a string or a comment: then the
// command is only wrapped when it need not be, which changes nothing)
bool has_word(const std::string& text, const char* word) {
  return std::regex_search(text, std::regex(std::string("\\b") + word + "\\b"));
}

// text as Lua comments, each line after "-- "
std::string commented(const std::string& text) {
  std::string c = "-- " + text;
  for (size_t k = 0; k < c.size(); ++k)
    if (c[k] == '\n') c.insert(k + 1, "-- ");
  return c;
}

// the command as the prompt showed it typed, as comments: "-- > first line", "-- >> next line"
std::string typed(const std::string& chunk) {
  std::string c = "-- > ";
  for (const char ch : chunk) c += ch == '\n' ? std::string("\n-- >> ") : std::string(1, ch);
  return c;
}

// the command as statements valid anywhere in session.lua, doing what it did at the prompt.
// printed: the prompt printed the values the chunk returned
std::string as_statements(lua_State* L, const std::string& chunk, bool expression, bool printed) {
  std::string out;
  if (expression) {
    // a call is a statement as it is (a run, a reading: the replay makes the call, its values
    // are not printed again); any other expression was typed to see its value, all it did: it
    // is printed again as the prompt showed it (print() gave "table: 0x55d0..." for a table)
    if (compiles(L, chunk)) return chunk;
    out = "beltsim.print(" + chunk + ")";
    if (!compiles(L, out)) out = "beltsim.print(" + chunk + "\n)";  // a comment at its end
    printed = true;
  } else if (has_word(chunk, "return")) {
    // `return` ends the command, not the replay
    out = printed ? "beltsim.print((function(...)\n" + chunk + "\nend)())"
                  : "do (function(...)\n" + chunk + "\nend)() end";
  } else if (has_word(chunk, "local") || chunk.find("::") != std::string::npos) {
    out = "do\n" + chunk + "\nend";  // its locals and labels stay in the command, as at the prompt
  } else {
    out = chunk;
  }
  // a command replayed inside beltsim.print(...) follows its line as it was typed
  if (compiles(L, out)) return printed && out != chunk ? typed(chunk) + "\n" + out : out;
  // not expected: kept as a comment rather than break the replay
  return commented("(not replayable) " + chunk);
}

// the global naming the simulation whose userdata is p, in a statement of session.lua
std::string sim_name(lua_State* L, const void* p) {
  const std::string name = p ? global_named(L, p) : "";
  return name.empty() ? "-- (a simulation not held by a global) sim" : name;
}

// text (a command, the scenario) whose scene:run a stop signal `by` stopped at t: between
// beltsim.stop_at(t) and beltsim.stop_at(), so that the replay's run stops there too, and the runs
// after it are refused as they were
std::string stopped_at(double t, const char* by, const std::string& text) {
  return "beltsim.stop_at(" + number_text(t) + ")  -- " + by + " stopped its run at t = " + number_text(t) + " s\n" +
         text + "\nbeltsim.stop_at()";
}

}  // namespace

namespace {

// a command whose run Ctrl-C stopped becomes run_to(where it stopped), so the replay stops at the
// same step end (and gives the same outputs)
// A command during which the live view's page changed a simulation becomes, the same way, the runs
// to where each change came and the changes, in the order they were applied (page_changes holds
// the ends of its runs too). keep: a command that kept its run's result (r = sim:advance(20))
// keeps it in the replay too, on its last run (the run's end: r.t and r.interrupted as at the
// prompt, r.steps and r.wall those of the last run alone when the page split it)
std::string stopped_or_changed(lua_State* L, const std::string& chunk, const StoppedRuns& stopped,
                               const std::vector<PageChange>& page, bool keep) {
  std::string out = commented(chunk);
  out += page.empty() ? std::string("  -- stopped by ") + pending_signal_name()
                      : std::string("  -- changed from the live view while it ran");
  static const std::regex kept(R"(^\s*((local\s+)?[A-Za-z_][A-Za-z0-9_.]*\s*=\s*)([A-Za-z_][A-Za-z0-9_]*)\s*:\s*)"
                               R"((advance|run_to)\s*\([^\n]*\)\s*;?\s*$)");
  std::smatch m;
  // the one simulation the command ran (the one it names), else none whose result is kept
  const void* sim = !page.empty() ? page[0].sim : !stopped.empty() ? stopped[0].first : nullptr;
  for (const PageChange& c : page) keep = keep && c.sim == sim;
  for (const auto& [p, t] : stopped) keep = keep && p == sim;
  keep = keep && sim && std::regex_match(chunk, m, kept) && m[3].str() == sim_name(L, sim);
  std::map<const void*, double> at;  // where each simulation stands in the replay
  bool run_last = false;             // the last statement is a run of sim
  const auto run = [&](const void* p, double t) {
    const auto it = at.find(p);
    if (it != at.end() && it->second == t) return;
    out += "\n" + sim_name(L, p) + ":run_to(" + number_text(t) + ")";
    at[p] = t, run_last = p == sim;
  };
  for (const PageChange& c : page) {
    run(c.sim, c.t);
    if (!c.call.empty()) out += "\n" + sim_name(L, c.sim) + ":" + c.call, run_last = false;
  }
  for (const auto& [p, t] : stopped) run(p, t);
  if (!keep) return out;
  // the result is the last run's: a run that ended where the page's last change came (Ctrl-C in a
  // pause) gets one of no steps, to where it stands, to hold it
  if (!run_last) out += "\n" + sim_name(L, sim) + ":run_to(" + number_text(at[sim]) + ")";
  return out.insert(out.rfind('\n') + 1, m[1].str());
}

}  // namespace

std::string replayable(lua_State* L, const std::string& chunk, bool expression, bool printed,
                       const StoppedRuns& stopped, const std::vector<PageChange>& page) {
  if (stopped.empty() && page.empty()) return as_statements(L, chunk, expression, printed);
  if (page.empty() && !stopped[0].first)
    return stopped_at(stopped[0].second, pending_signal_name(), as_statements(L, chunk, expression, printed));
  return stopped_or_changed(L, chunk, stopped, page, true);
}

std::string failed_replayable(lua_State* L, const std::string& chunk, bool expression, const std::string& error,
                              const StoppedRuns& stopped, const std::vector<PageChange>& page) {
  std::string said = error.substr(0, error.find('\n'));
  said = "-- failed at the prompt: " + said;
  const std::string wrapped = said + "\npcall(function()\n" + as_statements(L, chunk, expression, false) + "\nend)";
  if (page.empty() && !stopped.empty() && !stopped[0].first && compiles(L, wrapped))
    return stopped_at(stopped[0].second, pending_signal_name(), wrapped);
  // (an assignment that failed kept nothing: its runs are replayed, the variable left as it was)
  if (!stopped.empty() || !page.empty()) return said + "\n" + stopped_or_changed(L, chunk, stopped, page, false);
  // Lua code that a stop signal interrupted (while true do end) may never end: its replay would
  // run to the instruction limit and end the replay there. Kept as a comment
  if (const int sig = pending_signal(); sig != 0)
    return said + "\n-- (" + signal_name(sig) + " interrupted it at the prompt: not replayed, as it may not end)\n" +
           commented(chunk);
  if (compiles(L, wrapped)) return wrapped;
  return said + "\n" + commented("(not replayable) " + chunk);
}

std::string at_prompt(lua_State* L, const std::vector<PageChange>& page) {
  std::string out;
  for (const PageChange& c : page)
    if (!c.call.empty())
      out += (out.empty() ? "" : "\n") + sim_name(L, c.sim) + ":" + c.call + "  -- from the live view";
  return out;
}

std::string SessionFile::path() const {
  return name_.empty() ? "" : (std::filesystem::path(start_.dir) / name_).string();
}

bool SessionFile::write(const std::vector<std::string>& commands, bool runs_in_dir, bool resumed) {
  if (commands.empty()) return true;
  namespace fs = std::filesystem;
  const std::string& dir = start_.dir;
  const std::optional<std::string>& script = start_.script;
  const std::vector<ScriptArg>& sets = start_.sets;
  // never over an earlier session's record (a console resumed in its folder): session_2.lua, ...
  for (int k = 2; name_.empty(); ++k) {
    const std::string name = k == 2 ? "session.lua" : "session_" + std::to_string(k - 1) + ".lua";
    std::error_code ec;  // (a folder that cannot be read: the write says why)
    if (fs::symlink_status(fs::path(dir) / name, ec).type() == fs::file_type::not_found || ec) name_ = name;
  }
  const std::string path = this->path();
  std::ostringstream f;  // written whole (io/output_dir.hpp: never through a link, never half)
  // the replay's outputs in DIR/replay, beside the session's and apart from every other replay's
  // (without --out all went to out/session, one session's pictures left among another's)
  const std::string replay_out = (fs::path(dir) / "replay").string();
  f << "-- The commands of a beltsim console session, in order (one that raised an error under pcall).\n"
    << "-- Replay with: beltsim run " << shell_word(path);
  if (runs_in_dir) f << " --out " << shell_word(replay_out);
  // the options that changed the session's runs (--rtol, --integrator, --no-frames, ...), as typed
  for (const std::string& w : start_.options) f << " " << shell_word(w);
  // beltsim.args as in the session, each --set quoted for the shell
  for (const ScriptArg& a : sets) f << " --set " << shell_word(a.key + "=" + a.text);
  f << "\n";
  if (runs_in_dir)
    f << "-- (its outputs in " << replay_out << ", beside this session's; its relative paths, sim:save's,\n"
      << "-- sim:show's and sim:plot's, are taken there, as the session's were in its folder)\n";
  f << "-- An expression the prompt printed (not a call) is printed by beltsim.print, as the prompt\n"
    << "-- showed it, after the command as it was typed (-- > r).\n";
  // before the scenario, which may resume a checkpoint too
  if (resumed)
    f << "-- The session resumed a checkpoint: its replay resumes, for one in this session's folder, its own\n"
      << "-- copy (the same path in the replay's output folder), and writes nothing into this session's folder.\n"
      << "beltsim.replay_of(" << quoted(dir.data(), dir.size()) << ")\n";
  // the keys are read by the commands below, after the scenario's first run: read here first,
  // so that the replay's first run does not stop on them as unread (lua_api.hpp, check_unread_args)
  if (!sets.empty()) {
    f << "local _ = {";
    for (size_t k = 0; k < sets.size(); ++k)
      f << (k ? ", " : "") << "beltsim.args[" << quoted(sets[k].key.data(), sets[k].key.size()) << "]";
    f << "}\n";
  }
  if (script) {
    // the scenario's text is copied in (as it was when the session began), so the replay needs
    // no access to the scenario's folder, which the sandbox would refuse (docs/console.md)
    f << "-- The scenario " << *script << " is copied below as it was when the session began; its errors\n"
      << "-- name it and its own lines. A scenario that reads files beside it, or whose runs wrote outside\n"
      << "-- this file's folder (out = ..., an argument naming a folder), needs: beltsim run --trusted\n";
    f << "arg = { [0] = " << quoted(script->data(), script->size());
    for (const std::string& a : start_.args) f << ", " << quoted(a.data(), a.size());
    f << " }\n";
    // as luaL_loadfile reads a file: no UTF-8 byte order mark, a first line "#..." skipped (kept
    // as a comment, so the line numbers stay)
    std::string script_text = start_.script_text;
    if (script_text.rfind("\xEF\xBB\xBF", 0) == 0) script_text.erase(0, 3);
    if (!script_text.empty() && script_text[0] == '#') script_text.insert(0, "--");
    const std::string chunkname = "@" + *script;
    const std::string load =
        "assert(load(" + long_string(script_text) + ", " + quoted(chunkname.data(), chunkname.size()) + ", \"t\"))";
    // one that failed at the console's start (its runs after a stopped one refused) under pcall, as a
    // command that failed, so that the replay goes on
    const std::string& failed = start_.scenario_error;
    std::string text = failed.empty() ? load + "()"
                                      : "-- failed at the console's start: " + failed.substr(0, failed.find('\n')) +
                                            "\npcall(" + load + ")";
    if (start_.scenario_stop) text = stopped_at(*start_.scenario_stop, start_.scenario_stopped_by.c_str(), text);
    f << text << "\n";
  }
  for (const std::string& c : commands) f << c << "\n";
  try {
    write_file_whole(OutputDir(dir), name_, f.str());  // the folder made when missing
    failed_.clear();
  } catch (const std::exception& e) {  // recorded: the exit status says so (app/main.cpp)
    if (failed_ != e.what()) say("beltsim: %s\n", e.what());
    failed_ = e.what();
    mark_output_failure_shown(e.what());
    return false;
  }
  return true;
}

}  // namespace beltsim::script
