// The sandbox (src/script/sandbox.cpp; docs/limits-and-safety.md; the limits are limits_test.cpp's):
// every forbidden function raises an error naming file:line and --trusted; files only under the
// output folder (read, write) and the script's folder (read); no precompiled chunk anywhere; the
// API's userdata keep their metatables and fail cleanly once finalised.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "io/output_dir.hpp"
#include "run_script.hpp"
#include "script/interpreter.hpp"
#include "support/files.hpp"
#include "support/scenes.hpp"
#include "support/scratch.hpp"

namespace beltsim::script {
namespace sandbox_test {

using beltsim::test::slurp;
using test::expect_has;

namespace fs = std::filesystem;

// <tmp>/beltsim_sandbox_test_<pid>/{scripts,out}: the script's folder and the output folder
fs::path root() {
  const fs::path d = beltsim::test::scratch_dir("beltsim_sandbox_test");
  fs::create_directories(d / "scripts");
  fs::create_directories(d / "out");
  return d;
}
fs::path scripts() { return root() / "scripts"; }
fs::path out() { return root() / "out"; }

// runs the text as scripts/<name> with the output folder out/; the error message, or ""
std::string run(Interpreter& lua, const std::string& text, const std::string& name = "sandbox.lua") {
  return test::run_script(lua, scripts() / name, text, out());
}

std::string run(const std::string& text, const Safety& s = {}) {
  Interpreter lua(s);
  return run(lua, text);
}

// Lua's quoting of a path
std::string q(const fs::path& p) {
  std::string s = "'";
  s += p.string();
  s += "'";
  return s;
}

const std::string kScene = beltsim::test::two_pulley();

// the same scene assigned to `sc`
std::string sc_scene() {
  beltsim::test::TwoPulley p;
  p.assign = "sc = ";
  return beltsim::test::two_pulley(p);
}

// ---- forbidden functions ---------------------------------------------------------------------

TEST(Sandbox, EveryForbiddenFunctionNamesFileLineAndTrusted) {
  const std::vector<std::string> calls = {
      "os.execute('true')",  "os.remove('x')",      "os.rename('a', 'b')",   "os.exit(3)",
      "os.tmpname()",        "os.setlocale('C')",   "io.popen('ls')",        "io.tmpfile()",
      "string.dump(print)",  "('x').dump(print)",   "package.loadlib('a', 'b')", "package.searchpath('a', 'b')",
      "debug.getinfo(1)",    "debug.sethook()",     "debug.getregistry()",   "debug.getlocal(1, 1)",
      "debug.setmetatable(1, {})", "debug.getupvalue(print, 1)", "debug.setupvalue(print, 1, 1)",
      "debug.upvaluejoin(print, 1, print, 1)", "debug.debug()", "debug.getuservalue(io.stdout)",
  };
  for (const std::string& call : calls) {
    const std::string name = call.substr(0, call.find('('));
    const std::string msg = run("local x = 1\n\n" + call + "\n");
    const std::string shown = name == "('x').dump" ? "string.dump" : name;
    expect_has(msg, {"sandbox.lua:3: ", shown + " is not allowed in a scenario script", "--trusted"});
  }
}

TEST(Sandbox, WhatScenarioScriptsUseIsThere) {
  EXPECT_EQ(run("assert(string.format('%.1f', math.pi) == '3.1')\n"
                "assert(table.concat({1, 2}, ',') == '1,2')\n"
                "assert(utf8.len('μ') == 1)\n"
                "local co = coroutine.wrap(function() coroutine.yield(1) end)\n"
                "assert(co() == 1)\n"
                "assert(type(os.time()) == 'number' and type(os.clock()) == 'number')\n"
                "assert(type(os.date('%Y')) == 'string' and os.difftime(2, 1) == 1)\n"
                "assert(os.getenv('PATH') ~= nil)\n"
                "assert(type(debug.traceback('x')) == 'string')\n"
                "assert(load('return 6*7')() == 42)\n"
                "assert(pcall(error, 'x') == false)\n"
                "assert(package.loaded.string == string and package.loaded.os == os)\n"
                "assert(require('string') == string)\n"),
            "");
}

TEST(Sandbox, TrustedRestoresTheFullLibraries) {
  Safety s;
  s.trusted = true;
  EXPECT_EQ(run("assert(os.execute('true'))\n"
                "assert(debug.getinfo(1).currentline == 2)\n"
                "assert(io.open('/etc/hostname') or true)\n"
                "assert(type(string.dump(function() end)) == 'string')\n"
                "assert(package.loadlib ~= nil and package.path ~= nil)\n",
                s),
            "");
}

// ---- files -----------------------------------------------------------------------------------

TEST(Sandbox, FilesUnderTheOutputFolderCanBeWrittenAndRead) {
  const fs::path f = out() / "notes" / "a.txt";
  fs::remove_all(out() / "notes");
  EXPECT_EQ(run("local f = assert(io.open(" + q(f) + ", 'w'))\n"  // the missing folder is made
                "f:write('belt\\n') f:close()\n"
                "assert(io.open(" + q(f) + "):read('l') == 'belt')\n"
                "local n = 0 for l in io.lines(" + q(f) + ") do n = n + 1 end assert(n == 1)\n"
                "assert(io.open(" + q(f) + ", 'a')):close()\n"
                "io.output(" + q(out() / "b.txt") + ") io.write('x') io.close() io.output(io.stdout)\n"),
            "");
  EXPECT_EQ(slurp(f), "belt\n");
  EXPECT_EQ(slurp(out() / "b.txt"), "x");
}

TEST(Sandbox, TheScriptsFolderIsReadOnly) {
  std::ofstream(scripts() / "data.txt") << "42\n";
  EXPECT_EQ(run("assert(io.open(" + q(scripts() / "data.txt") + "):read('n') == 42)\n"), "");
  expect_has(run("\nio.open(" + q(scripts() / "data.txt") + ", 'w')\n"),
             {"sandbox.lua:2: io.open: writing", "data.txt", "not allowed", "--trusted"});
  expect_has(run("\nio.open(" + q(scripts() / "data.txt") + ", 'r+')\n"), {"sandbox.lua:2: io.open: writing"});
  expect_has(run("\nio.output(" + q(scripts() / "new.txt") + ")\n"), {"sandbox.lua:2: io.output: writing"});
  EXPECT_FALSE(fs::exists(scripts() / "new.txt"));
}

TEST(Sandbox, FilesElsewhereAreRefused) {
  const std::string escape = (out() / ".." / ".." / ".." / "etc" / "passwd").string();
  for (const std::string& call : std::vector<std::string>{
           "io.open('/etc/passwd')", "io.open('" + escape + "')", "io.open('/tmp/beltsim_x', 'w')",
           "io.lines('/etc/passwd')", "io.input('/etc/passwd')", "dofile('/etc/passwd')", "loadfile('/etc/passwd')",
        "io.open('" + (scripts() / ".." / "x.txt").string() + "')"}) {
    const std::string msg = run("local x\n" + call + "\n");
    expect_has(msg, {"sandbox.lua:2: ", "is not allowed in a scenario script", "--trusted", fs::canonical(out()).string()});
  }
  // relative paths too (from the working folder, as Lua has it)
  const fs::path cwd = fs::current_path();
  fs::current_path(out());
  expect_has(run("io.open('../../../../../../../../etc/passwd')\n"), {"sandbox.lua:1: io.open: reading"});
  fs::current_path(cwd);
}

TEST(Sandbox, SymbolicLinksCannotLeaveTheFolders) {
  const fs::path link = out() / "etc_link";
  fs::remove(link);
  fs::create_directory_symlink("/etc", link);
  expect_has(run("io.open(" + q(link / "passwd") + ")\n"), {"sandbox.lua:1: io.open: reading", "not allowed"});
  expect_has(run("io.open(" + q(link / "new.txt") + ", 'w')\n"), {"sandbox.lua:1: io.open: writing"});
  fs::remove(link);
}

// the paths a script gives beltsim itself obey the same folders: a run's out and frame paths,
// sim:save, sim:show{file}, sim:plot{file} are written under the output folder or the script's
// folder, beltsim.resume reads from them, and a checkpoint cannot name outputs elsewhere
TEST(Sandbox, BeltsimsOwnPathsStayInTheFolders) {
  const fs::path elsewhere = root() / "elsewhere";
  fs::remove_all(elsewhere);
  auto refused = [&](const std::string& text, const std::string& what, const std::string& path) {
    Interpreter lua;  // no --out: the output folder is out/<script> in the working folder
    const std::string msg = test::run_script(lua, scripts() / "paths.lua", text);
    expect_has(msg, {"paths.lua:", what + ": writing '" + path + "' is not allowed in a scenario script",
                     fs::canonical(scripts()).string() + " (the script's folder)", "--trusted"});
  };
  const std::string e = elsewhere.string();
  refused(std::string(kScene) + "s:run{ t_end = 0.001, out = '" + e + "' }\n", "run.out", e);
  refused(std::string(kScene) + "s:start{ out = '" + e + "' }\n", "start.out", e);
  refused(std::string(kScene) + "s:start{ out = " + q(scripts() / "r") + ", frames = { video = '" + e + "/v.mp4' } }\n",
          "start.frames.video", e + "/v.mp4");
  refused(std::string(kScene) + "s:start{ out = " + q(scripts() / "r") + ", frames = { png = '" + e + "' } }\n",
          "start.frames.png", e);
  // a live simulation whose outputs go to a folder beside the script (allowed)
  const std::string live =
      std::string(kScene) + "local sim = s:start{ out = " + q(scripts() / "r") + ", progress = false }\n";
  refused(live + "sim:save('" + e + "/x.chk')\n", "sim:save", e + "/x.chk");
  const std::string dots = (scripts() / "r" / ".." / ".." / "elsewhere" / "x.chk").string();
  refused(live + "sim:save('" + dots + "')\n", "sim:save", dots);
  refused(live + "sim:show{ file = '" + e + "/x.png' }\n", "sim:show", e + "/x.png");
  refused(live + "sim:plot{ 'driver.omega', file = '" + e + "/x.png' }\n", "sim:plot", e + "/x.png");
  EXPECT_FALSE(fs::exists(elsewhere));
  {
    Interpreter lua;
    expect_has(test::run_script(lua, scripts() / "paths.lua", "beltsim.resume('/etc/passwd')\n"),
               {"paths.lua:1: beltsim.resume: reading '/etc/passwd' is not allowed", "--trusted"});
  }
  // a checkpoint rewritten (with io.open, in the output folder) to continue its outputs elsewhere,
  // its checksum made to match again (a checksum finds damage; it guards nothing against a script)
  {
    Interpreter lua;
    const std::string chk = (out() / "x.chk").string();
    const std::string msg = run(lua, std::string(kScene) +
                                         "local sim = s:start{ progress = false }\n"
                                         "sim:advance(0.001)\n"
                                         "sim:save('" + chk + "')\n"
                                         "local f = assert(io.open('" + chk + "')) local text = f:read('a') f:close()\n"
                                         "local old = 'out \"' .. sim:stats().out .. '\"'\n"
                                         "local i = assert(text:find(old, 1, true), old)\n"
                                         "text = text:sub(1, i - 1) .. 'out \"" + e + "\"' .. text:sub(i + #old) "
                                         "local body = text:sub(1, text:find('checksum fnv1a64 ', 1, true) - 1) "
                                         "local h = 0xcbf29ce484222325 "
                                         "for k = 1, #body do h = (h ~ body:byte(k)) * 0x100000001b3 end "
                                         "text = body .. string.format('checksum fnv1a64 %016x\\n', h)\n"
                                         "f = assert(io.open('" + chk + "', 'w')) f:write(text) f:close()\n"
                                         "beltsim.resume('" + chk + "')\n");
    expect_has(msg, {"sandbox.lua:16: beltsim.resume: resume.out: writing '" + e + "' is not allowed", "--trusted"});
  }
  EXPECT_FALSE(fs::exists(elsewhere));
  // --trusted: written where they say
  {
    Safety trusted;
    trusted.trusted = true;
    Interpreter lua(trusted);
    fs::create_directories(elsewhere);
    EXPECT_EQ(test::run_script(lua, scripts() / "paths.lua", live + "sim:save('" + e + "/x.chk')\n"), "");
    EXPECT_TRUE(fs::exists(elsewhere / "x.chk"));
  }
  fs::remove_all(elsewhere);
  fs::remove_all(scripts() / "r");
}

// One writer per folder, against a script's own writes too: a folder that another beltsim holds
// (a child process holds its lock here, as a running simulation does) takes no write from a
// script, by any function, and its files stay as they were; reading it is allowed, and so is
// writing into the folder of this process's own simulation
TEST(Sandbox, AFolderAnotherBeltsimWritesIsNotWrittenByAScript) {
  const fs::path held = out() / "held";
  fs::remove_all(held);
  fs::create_directories(held / "frames");
  beltsim::test::spit(held / "timeseries.csv", "t,x\n0,1\n");
  int locked[2], done[2];
  ASSERT_EQ(::pipe2(locked, O_CLOEXEC), 0);
  ASSERT_EQ(::pipe2(done, O_CLOEXEC), 0);
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {  // the other beltsim: holds the folder until the test closes `done`
    ::close(done[1]);
    OutputDir d(held.string());
    d.lock();
    char c = 1;
    if (::write(locked[1], &c, 1) != 1) _exit(1);
    _exit(::read(done[0], &c, 1) == 0 ? 0 : 1);
  }
  ::close(locked[1]);
  ::close(done[0]);
  char c = 0;
  ASSERT_EQ(::read(locked[0], &c, 1), 1);
  const std::string ts = q(held / "timeseries.csv");
  const std::string holder =
      "the folder " + held.string() + " is in use by another beltsim (process " + std::to_string(pid) + ")";
  for (const std::string& write :
       {"io.open(" + ts + ", 'a')", "io.open(" + ts + ", 'w')", "io.open(" + ts + ", 'r+')", "io.output(" + ts + ")",
        "io.open(" + q(held / "new.txt") + ", 'w')", "io.open(" + q(held / "frames" / "f.png") + ", 'wb')",
        "io.open(" + q(held / "sub" / "new.txt") + ", 'w')"})
    expect_has(run("local x = 1\n" + write + "\n"),
               {"sandbox.lua:2: ", ": writing '", "' is not allowed in a scenario script: " + holder, "--trusted"});
  // beltsim's own writes for the script (a run there is refused by its own lock: outputs_test.py)
  expect_has(run(kScene + "local sim = s:start{ progress = false }\nsim:save(" + q(held / "a.ckpt") + ")\n"),
             {"sandbox.lua:9: sim:save: writing '", holder});
  expect_has(run(kScene + "s:start{ progress = false, frames = { png = " + q(held / "frames") + " } }\n"),
             {"sandbox.lua:8: start.frames.png: writing '", holder});
  EXPECT_EQ(run("assert(io.open(" + ts + "):read('a') == 't,x\\n0,1\\n')\n"), "");
  ::close(done[1]);
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_EQ(slurp(held / "timeseries.csv"), "t,x\n0,1\n");
  for (const char* made : {"new.txt", "frames/f.png", "sub", "a.ckpt"}) EXPECT_FALSE(fs::exists(held / made)) << made;
  // its holder gone, the folder takes writes again (the lock file stays in it)
  EXPECT_EQ(run("assert(io.open(" + q(held / "new.txt") + ", 'w')):close()\n"), "");
  // this process's own simulation writing there does not stop the script's writes
  EXPECT_EQ(run(kScene + "local sim = s:start{ out = " + q(held) + ", progress = false }\n"
                         "assert(io.open(" + q(held / "notes.txt") + ", 'w')):close()\n"
                         "sim:close()\n"),
            "");
  fs::remove_all(held);
}

TEST(Sandbox, RequireLoadsLuaFilesFromTheScriptsFolder) {
  std::ofstream(scripts() / "helper.lua") << "local calls = (calls or 0) + 1\nreturn { answer = 42 }\n";
  fs::create_directories(scripts() / "lib");
  std::ofstream(scripts() / "lib" / "more.lua") << "return 'more'\n";
  EXPECT_EQ(run("local h = require('helper')\n"
                "assert(h.answer == 42 and require('helper') == h, 'loaded once')\n"
                "assert(require('lib.more') == 'more')\n"),
            "");
  expect_has(run("\nrequire('lfs')\n"), {"sandbox.lua:2: module 'lfs' not found", "--trusted"});
  expect_has(run("\nrequire('../../x')\n"), {"sandbox.lua:2: require '../../x'", "--trusted"});
}

// ---- precompiled chunks ----------------------------------------------------------------------

TEST(Sandbox, PrecompiledChunksAreRefusedEverywhere) {
  // real bytecode, made by a trusted interpreter
  const fs::path luac = out() / "f.luac";
  Safety trusted;
  trusted.trusted = true;
  ASSERT_EQ(run("local f = assert(io.open(" + q(luac) + ", 'wb'))\n"
                "f:write(string.dump(function() return 1 end)) f:close()\n",
                trusted),
            "");
  ASSERT_EQ(slurp(luac).rfind("\x1bLua", 0), 0u);
  expect_has(run("load(string.dump(function() end))\n"), {"sandbox.lua:1: string.dump is not allowed"});
  expect_has(run("\nload('return 1', 'x', 'b')\n"), {"sandbox.lua:2: load: mode 'b'", "not loaded"});
  expect_has(run("\nloadfile(" + q(luac) + ", 'b')\n"), {"sandbox.lua:2: loadfile: mode 'b'"});
  // the bytes of a binary chunk, given as a string or a file, are refused with a reason
  EXPECT_EQ(run("local s = assert(io.open(" + q(luac) + ", 'rb')):read('a')\n"
                "local f, err = load(s)\n"
                "assert(f == nil and err:find('precompiled'), err)\n"
                "f, err = load(s, 'x', 'bt')\n"
                "assert(f == nil and err:find('precompiled'), err)\n"
                "f, err = loadfile(" + q(luac) + ")\n"
                "assert(f == nil and err:find('precompiled'), err)\n"),
            "");
  expect_has(run("\ndofile(" + q(luac) + ")\n"), {"sandbox.lua:2: dofile: ", "f.luac", "precompiled"});
  // and so is a main file of bytecode, even trusted
  fs::copy_file(luac, scripts() / "main.luac", fs::copy_options::overwrite_existing);
  Interpreter lua(trusted);
  try {
    lua.run_file((scripts() / "main.luac").string());
    ADD_FAILURE() << "a precompiled main file ran";
  } catch (const ScriptError& e) {
    expect_has(e.what(), {"binary"});
  }
}

// ---- the API's userdata ----------------------------------------------------------------------

TEST(Userdata, MetatablesAreProtected) {
  EXPECT_EQ(run(std::string(kScene) +
                "assert(getmetatable(s) == 'beltsim.Scene', tostring(getmetatable(s)))\n"
                "local sim = s:start{ progress = false }\n"
                "assert(getmetatable(sim) == 'beltsim.Simulation', tostring(getmetatable(sim)))\n"
                "assert(not pcall(setmetatable, s, {}))\n"
                "sim:close()\n"),
            "");
}

TEST(Sandbox, NoFinalisersInLua) {
  // Lua runs __gc with hooks off: a loop there could not be stopped
  expect_has(run("local x\nsetmetatable({}, { __gc = function() while true do end end })\n"),
             {"sandbox.lua:2: setmetatable: a __gc finaliser is not allowed", "--trusted"});
  EXPECT_EQ(run("local mt = { __index = function() return 1 end }\nassert(setmetatable({}, mt).x == 1)\n"), "");
}

// a finaliser (trusted: the sandbox has none) that runs after the scene's and the simulation's (it
// was marked first) reaches them finalised: every use is an error, none a crash
TEST(Userdata, FinalisedScenesAndSimulationsGiveErrors) {
  Safety trusted;
  trusted.trusted = true;
  EXPECT_EQ(run("local results = {}\n"
                "do\n"
                "  local sc, sim\n"
                "  setmetatable({}, { __gc = function()\n"
                "    for _, f in ipairs {\n"
                "      function() return sc:info() end, function() return sc:element_near{0, 0} end,\n"
                "      function() return sc:run{ t_end = 0.01 } end, function() return sc:start{} end,\n"
                "      function() return sim:run_to(1) end, function() return sim.t end,\n"
                "      function() return sim:pulley('driver') end, function() return sim:close() end,\n"
                "    } do results[#results + 1] = { pcall(f) } end\n"
                "    results.scene, results.sim = tostring(sc), tostring(sim)\n"
                "  end })\n" +
                sc_scene() +
                "  sim = sc:start{ progress = false }\n"
                "end\n"
                "collectgarbage() collectgarbage()\n"
                "assert(#results == 8, 'the finaliser ran: ' .. #results)\n"
                "for i, r in ipairs(results) do\n"
                "  assert(r[1] == false and r[2]:find('finalised'), i .. ': ' .. tostring(r[2]))\n"
                "end\n"
                "assert(results.scene:find('finalised') and results.sim:find('finalised'))\n",
                trusted),
            "");
}

// callbacks registered inside a coroutine that is gone when the simulation is finalised
TEST(Userdata, CallbacksOfACoroutineOutliveIt) {
  EXPECT_EQ(run(std::string(kScene) +
                "local sim = s:start{ progress = false }\n"
                "coroutine.wrap(function() sim:every(0.001, function() end) end)()\n"
                "collectgarbage() collectgarbage()\n"
                "sim:run_to(0.002)\n"
                "sim = nil\n"
                "collectgarbage() collectgarbage()\n"),
            "");
}

}  // namespace sandbox_test
}  // namespace beltsim::script
