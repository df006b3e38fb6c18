// The script's own files never leave the sandbox's folders (src/script/sandbox_files.cpp,
// io/beneath.hpp; docs/limits-and-safety.md): io.open, io.lines, io.input, io.output, dofile,
// loadfile and require open their file by walking from the folder one component at a time, so a
// symbolic link planted under the output folder (to a file outside that exists or not, a chain of
// links, a relative target, a linked folder) is refused and never followed, `..` cannot climb out,
// a FIFO does not block the script, and a second hard link is never written through.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "run_script.hpp"
#include "script/interpreter.hpp"
#include "support/files.hpp"
#include "support/scenes.hpp"
#include "support/scratch.hpp"

namespace beltsim::script {
namespace sandbox_links_test {

using beltsim::test::slurp;
using beltsim::test::spit;

namespace fs = std::filesystem;

constexpr const char* kSecret = "the user's own file\n";

// <tmp>/beltsim_sandbox_links_test_<pid>/{scripts,out,outside}: the script's folder, the output
// folder and a folder beside them holding bashrc (the user's file)
struct Folders {
  fs::path base, scripts, out, outside;
  explicit Folders(const std::string& name) {
    base = beltsim::test::scratch_dir("beltsim_sandbox_links_test") / name;
    fs::remove_all(base);
    scripts = base / "scripts", out = base / "out", outside = base / "outside";
    for (const fs::path& d : {scripts, out, outside}) fs::create_directories(d);
    spit(outside / "bashrc", kSecret);
  }
  // runs the text as scripts/sandbox.lua with the output folder out/; the error, or ""
  std::string run(const std::string& text) const {
    Interpreter lua;
    return test::run_script(lua, scripts / "sandbox.lua", text, out);
  }
  // nothing outside but the user's file, as it was
  void expect_outside_untouched() const {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(outside)) names.push_back(e.path().filename().string());
    EXPECT_EQ(names, std::vector<std::string>{"bashrc"});
    EXPECT_EQ(slurp(outside / "bashrc"), kSecret);
  }
};

// Lua's quoting of a path
std::string q(const fs::path& p) { return "'" + p.string() + "'"; }

void expect_has(const std::string& msg, const std::vector<std::string>& parts) {
  for (const auto& p : parts) EXPECT_NE(msg.find(p), std::string::npos) << "'" << p << "' not in: " << msg;
}

// every way a script writes a file, as a line of Lua writing `path`
std::vector<std::string> writes(const fs::path& path) {
  const std::string p = q(path);
  return {"io.open(" + p + ", 'w'):write('x')", "io.open(" + p + ", 'a'):write('x')",
          "io.open(" + p + ", 'w+'):write('x')", "io.open(" + p + ", 'a+'):write('x')",
          "io.open(" + p + ", 'wb'):write('x')", "io.output(" + p + ") io.write('x')"};
}

// each write of out/x refused with the link named, for a link (chain) made by plant()
void expect_writes_refused(const Folders& f, const std::function<void()>& plant, const std::string& link_named) {
  for (const std::string& call : writes(f.out / "x")) {
    plant();
    const std::string msg = f.run("local a\n" + call + "\n");
    expect_has(msg, {"sandbox.lua:2: ", "writing '" + (f.out / "x").string() + "' is not allowed",
                     link_named + " is a symbolic link", "--trusted"});
    f.expect_outside_untouched();
    EXPECT_TRUE(fs::is_symlink(f.out / "x"));
  }
}

TEST(SandboxLinks, ALinkToAMissingFileOutsideIsNotFollowed) {
  const Folders f("missing_target");
  expect_writes_refused(f, [&] {
    fs::remove(f.out / "x");
    fs::create_symlink(f.outside / "new", f.out / "x");
  }, (f.out / "x").string());
}

TEST(SandboxLinks, AChainOfLinksIsNotFollowed) {
  const Folders f("chain");
  expect_writes_refused(f, [&] {
    fs::remove(f.out / "x"), fs::remove(f.out / "y");
    fs::create_symlink(f.out / "y", f.out / "x");
    fs::create_symlink(f.outside / "new", f.out / "y");
  }, (f.out / "x").string());
}

TEST(SandboxLinks, ARelativeTargetIsNotFollowed) {
  const Folders f("relative");
  expect_writes_refused(f, [&] {
    fs::remove(f.out / "x");
    fs::create_symlink(fs::path("..") / "outside" / "new", f.out / "x");
  }, (f.out / "x").string());
}

TEST(SandboxLinks, ALinkToAnExistingFileIsNotFollowed) {
  const Folders f("existing");
  expect_writes_refused(f, [&] {
    fs::remove(f.out / "x");
    fs::create_symlink(f.outside / "bashrc", f.out / "x");
  }, (f.out / "x").string());
  // nor read through
  for (const std::string& call : {"io.open(" + q(f.out / "x") + ")", "io.lines(" + q(f.out / "x") + ")",
                                  "io.input(" + q(f.out / "x") + ")", "dofile(" + q(f.out / "x") + ")",
                                  "loadfile(" + q(f.out / "x") + ")"})
    expect_has(f.run("local a\n" + call + "\n"), {"sandbox.lua:2: ", "reading '" + (f.out / "x").string() + "'",
                                                   (f.out / "x").string() + " is a symbolic link"});
}

TEST(SandboxLinks, ALinkedFolderIsNotEntered) {
  const Folders f("folder");
  fs::create_directories(f.out / "sub");
  // to a folder outside, and to one inside: no link is followed beneath the folders
  for (const fs::path& target : {f.outside, f.out / "sub"}) {
    fs::remove(f.out / "d");
    fs::create_directory_symlink(target, f.out / "d");
    for (const std::string& call : writes(f.out / "d" / "new"))
      expect_has(f.run("local a\n" + call + "\n"), {"sandbox.lua:2: ", (f.out / "d").string() + " is a symbolic link"});
    expect_has(f.run("io.open(" + q(f.out / "d" / "bashrc") + ")\n"),
               {"sandbox.lua:1: io.open: reading", (f.out / "d").string() + " is a symbolic link"});
    f.expect_outside_untouched();
    EXPECT_TRUE(fs::is_empty(f.out / "sub"));
  }
  // nor one in the script's folder, read by require
  fs::create_directory_symlink(f.outside, f.scripts / "lib");
  spit(f.outside / "more.lua", "return 'more'\n");
  expect_has(f.run("require('lib.more')\n"), {"sandbox.lua:1: ", (f.scripts / "lib").string() + " is a symbolic link"});
}

TEST(SandboxLinks, DotDotCannotClimbOut) {
  const Folders f("dotdot");
  fs::create_directories(f.out / "sub");
  for (const fs::path& p : {f.out / ".." / "outside" / "new", f.out / "sub" / ".." / ".." / "outside" / "new"})
    for (const std::string& call : writes(p))
      expect_has(f.run("local a\n" + call + "\n"), {"sandbox.lua:2: ", "is not allowed in a scenario script"});
  f.expect_outside_untouched();
  // `..` that stays inside is a path like any other
  EXPECT_EQ(f.run("assert(io.open(" + q(f.out / "sub" / ".." / "in.txt") + ", 'w')):write('in')\n"), "");
  EXPECT_EQ(slurp(f.out / "in.txt"), "in");
}

TEST(SandboxLinks, AHardLinkIsNotWrittenThrough) {
  const Folders f("hard");
  fs::create_hard_link(f.outside / "bashrc", f.out / "h");
  for (const std::string& call : writes(f.out / "h"))
    expect_has(f.run("local a\n" + call + "\n"), {"sandbox.lua:2: ", "writing '" + (f.out / "h").string() + "'",
                                                   "2 hard links"});
  EXPECT_EQ(slurp(f.outside / "bashrc"), kSecret);
}

// a FIFO planted in the output folder is refused at once, where it would block the script for ever
TEST(SandboxLinks, AFifoDoesNotBlockTheScript) {
  const Folders f("fifo");
  ASSERT_EQ(::mkfifo((f.out / "p").c_str(), 0600), 0);
  for (const std::string& call : {"io.open(" + q(f.out / "p") + ", 'w')", "io.open(" + q(f.out / "p") + ")",
                                  "io.lines(" + q(f.out / "p") + ")", "io.output(" + q(f.out / "p") + ")"}) {
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      ::alarm(5);
      const std::string msg = f.run(call + "\n");
      _exit(msg.find("not a regular file") != std::string::npos ? 0 : 1);
    }
    int status = 0;
    ::waitpid(pid, &status, 0);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << call << ": blocked, or not refused";
  }
}

// the output folder itself a link: nothing is written where it points
TEST(SandboxLinks, AnOutputFolderThatIsALinkIsRefused) {
  const Folders f("out_link");
  fs::remove_all(f.out);
  fs::create_directory_symlink(f.outside, f.out);
  for (const std::string& call : writes(f.out / "new"))
    expect_has(f.run("local a\n" + call + "\n"), {"sandbox.lua:2: ", f.out.string() + " is a symbolic link"});
  f.expect_outside_untouched();
}

// the paths a script gives beltsim itself (sim:save, sim:show, a run's out) follow no link under
// the folders either: one on the way is refused by the sandbox with the link named, one as the
// file itself by beltsim's writers (io/output_dir.hpp), before anything is written
TEST(SandboxLinks, BeltsimsOwnPathsFollowNoLinkEither) {
  const Folders f("own");
  fs::create_directories(f.out / "sub" / "e");
  fs::create_directory_symlink(f.out / "sub", f.out / "d");  // inside, and still refused
  fs::create_symlink(f.outside / "new.chk", f.out / "x.chk");
  const std::string live = beltsim::test::two_pulley() + "local sim = s:start{ progress = false }\n";
  const std::string line = ":" + std::to_string(std::count(live.begin(), live.end(), '\n') + 1) + ": ";
  const std::string link = " is a symbolic link (the sandbox follows no link in its folders)";
  expect_has(f.run(live + "sim:save(" + q(f.out / "d" / "e" / "y.chk") + ")\n"),
             {line + "sim:save: writing", (f.out / "d").string() + link});
  expect_has(f.run(live + "sim:show{ file = " + q(f.out / "d" / "e" / "y.png") + " }\n"),
             {line + "sim:show: writing", (f.out / "d").string() + link});
  expect_has(f.run(live + "sim:save(" + q(f.out / "d" / "y.chk") + ")\n"),
             {line + "sim:save: writing", (f.out / "d").string() + link});
  expect_has(f.run(live + "sim:save(" + q(f.out / "x.chk") + ")\n"),
             {line + "sim:save: ", (f.out / "x.chk").string() + ": it is a symbolic link (beltsim never writes"});
  // a run's out beside the script (no --out, which would replace it)
  fs::create_directories(f.outside / "sub");
  fs::create_directory_symlink(f.outside, f.scripts / "d");
  Interpreter lua;
  expect_has(test::run_script(lua, f.scripts / "run.lua", beltsim::test::two_pulley() + "s:run{ t_end = 0.001, out = " +
                                                                q(f.scripts / "d" / "sub" / "run") + " }\n"),
             {"run.out: writing", (f.scripts / "d").string() + link});
  fs::remove(f.outside / "sub");
  f.expect_outside_untouched();
  EXPECT_TRUE(fs::is_empty(f.out / "sub" / "e"));
}

// what a script may do it still does, with Lua's own answers for what is missing
TEST(SandboxLinks, OrdinaryFilesWorkAsInLua) {
  const Folders f("ordinary");
  const std::string c = q(f.out / "a" / "b" / "c.txt");
  EXPECT_EQ(f.run("local f = assert(io.open(" + c + ", 'w'))\n"  // the folders made
                  "f:write('1\\n2\\n') f:close()\n"
                  "local n = 0 for l in io.lines(" + c + ") do n = n + tonumber(l) end\n"
                  "assert(n == 3)\n"
                  "for a, b in io.lines(" + c + ", 'n', 'n') do assert(a == 1 and b == 2) end\n"
                  "local g, err, code = io.open(" + q(f.out / "none.txt") + ")\n"
                  "assert(g == nil and err:find('none.txt: No such file', 1, true) and code == 2, err)\n"
                  "assert(not pcall(io.lines, " + q(f.out / "none.txt") + "))\n"
                  "assert(select(2, loadfile(" + q(f.out / "none.txt") + ")):find('cannot open'))\n"
                  "io.output(" + q(f.out / "o.txt") + ") io.write('o') io.close()\n"
                  "io.input(" + q(f.out / "o.txt") + ") assert(io.read('a') == 'o') io.close(io.input())\n"
                  "local h = assert(io.open(" + q(f.out / "o.txt") + ", 'r+')) h:seek('end') h:write('p') h:close()\n"
                  "assert(io.open(" + q(f.out / "o.txt") + ", 'a')):write('q')\n"
                  "collectgarbage()\n"),
            "");
  EXPECT_EQ(slurp(f.out / "o.txt"), "opq");
  spit(f.scripts / "mod.lua", "#!/usr/bin/env lua\nreturn debug.traceback('x')\n");
  EXPECT_EQ(f.run("assert(require('mod'):find('mod.lua:2'))\n"
                  "assert(dofile(" + q(f.scripts / "mod.lua") + "):find('mod.lua:2'))\n"),
            "");
}

}  // namespace sandbox_links_test
}  // namespace beltsim::script
