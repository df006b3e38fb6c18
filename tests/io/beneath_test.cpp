// The one routine that opens a path beneath a folder (io/beneath.hpp): no symbolic link is
// followed anywhere on the way (a dangling one is never given a target), `..` is refused, a FIFO
// is refused without blocking, a hard-linked file is never written (and never emptied), the
// missing folders are made only when asked, and C's modes mean what fopen makes of them.
#include "io/beneath.hpp"

#include <gtest/gtest.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <filesystem>
#include <string>

#include "support/files.hpp"
#include "support/scratch.hpp"

namespace beltsim {
namespace beneath_test {

using test::slurp;
using test::spit;

namespace fs = std::filesystem;

constexpr const char* kSecret = "the user's own file\n";

// <scratch>/NAME/{in,outside/bashrc}, `in` opened as the folder the paths are beneath
struct Tree {
  fs::path in, outside;
  FolderFd root;
  explicit Tree(const std::string& name) {
    const fs::path base = beltsim::test::scratch_dir("beltsim_beneath_test") / name;
    fs::remove_all(base);
    in = base / "in", outside = base / "outside";
    fs::create_directories(in);
    fs::create_directories(outside);
    spit(outside / "bashrc", kSecret);
    root = FolderFd(::open(in.c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC));
  }
  // the error of opening rel (the descriptor closed when it opened)
  BeneathError open(const std::string& rel, const char* mode, bool make = false) const {
    FileMode m = *file_mode(mode);
    m.make_folders = make;
    BeneathError e;
    const int fd = file_beneath(root.get(), rel, m, &e);
    if (fd >= 0) ::close(fd), e = BeneathError{BeneathError::kSystem, 0, 0, "opened"};
    return e;
  }
};

void expect_error(const BeneathError& e, BeneathError::Kind kind, const std::string& at) {
  EXPECT_EQ(e.kind, kind) << e.reason();
  EXPECT_EQ(e.at, at);
}

TEST(Beneath, CModes) {
  for (const char* bad : {"", "x", "rw", "r++", "+", "wt", "ab+"}) EXPECT_FALSE(file_mode(bad)) << bad;
  const FileMode r = *file_mode("rb"), rp = *file_mode("r+"), w = *file_mode("w"), ap = *file_mode("a+b");
  EXPECT_TRUE(r.read && !r.write && !r.create && !r.empty);
  EXPECT_TRUE(rp.read && rp.write && !rp.create && !rp.empty);
  EXPECT_TRUE(!w.read && w.write && w.create && w.empty && !w.append);
  EXPECT_TRUE(ap.read && ap.write && ap.create && !ap.empty && ap.append);
}

TEST(Beneath, NoLinkIsFollowed) {
  const Tree t("links");
  fs::create_symlink(t.outside / "new", t.in / "dangling");
  fs::create_symlink(t.outside / "bashrc", t.in / "existing");
  fs::create_directory_symlink(t.outside, t.in / "folder");
  fs::create_directories(t.in / "sub");
  fs::create_directory_symlink(t.in / "sub", t.in / "inside");
  for (const char* mode : {"r", "r+", "w", "a", "w+", "a+"}) {
    expect_error(t.open("dangling", mode), BeneathError::kLink, "dangling");
    expect_error(t.open("existing", mode), BeneathError::kLink, "existing");
    expect_error(t.open("folder/bashrc", mode), BeneathError::kLink, "folder");
    expect_error(t.open("folder/new", mode, true), BeneathError::kLink, "folder");
    expect_error(t.open("inside/x", mode, true), BeneathError::kLink, "inside");
  }
  EXPECT_FALSE(fs::exists(t.outside / "new"));
  EXPECT_EQ(slurp(t.outside / "bashrc"), kSecret);
  EXPECT_TRUE(fs::is_empty(t.in / "sub"));
  BeneathError e;
  EXPECT_LT(folder_beneath(t.root.get(), "sub/../folder", false, &e), 0);
  expect_error(e, BeneathError::kDotDot, "sub/..");
}

TEST(Beneath, DotDotIsRefused) {
  const Tree t("dotdot");
  fs::create_directories(t.in / "sub");
  expect_error(t.open("../outside/bashrc", "r"), BeneathError::kDotDot, "..");
  expect_error(t.open("sub/../../outside/new", "w", true), BeneathError::kDotDot, "sub/..");
  expect_error(t.open("sub/..", "r"), BeneathError::kDotDot, "sub/..");
  EXPECT_FALSE(fs::exists(t.outside / "new"));
}

TEST(Beneath, OnlyOwnRegularFilesAreWritten) {
  const Tree t("files");
  fs::create_hard_link(t.outside / "bashrc", t.in / "hard");
  const BeneathError e = t.open("hard", "w");
  expect_error(e, BeneathError::kHardLinks, "hard");
  EXPECT_EQ(e.reason(), "it has 2 hard links");
  EXPECT_EQ(slurp(t.outside / "bashrc"), kSecret) << "emptied before the check";
  expect_error(t.open("hard", "r"), BeneathError::kSystem, "opened");  // read: the file's owner linked it
  ASSERT_EQ(::mkfifo((t.in / "fifo").c_str(), 0600), 0);
  expect_error(t.open("fifo", "w"), BeneathError::kNotRegular, "fifo");  // no reader: would block
  expect_error(t.open("fifo", "r"), BeneathError::kNotRegular, "fifo");
  fs::create_directories(t.in / "dir");
  const BeneathError d = t.open("dir", "r");
  EXPECT_EQ(d.kind, BeneathError::kSystem);
  EXPECT_EQ(d.err, EISDIR);
  const BeneathError m = t.open("none/x", "w");
  EXPECT_EQ(m.kind, BeneathError::kSystem);
  EXPECT_EQ(m.err, ENOENT);
  EXPECT_EQ(m.at, "none");
  EXPECT_FALSE(fs::exists(t.in / "none")) << "folders are made only when asked";
}

TEST(Beneath, FilesAreWrittenAsCsModesSay) {
  const Tree t("modes");
  BeneathError made;
  const FolderFd sub(folder_beneath(t.root.get(), "a/./b/", true, &made));
  ASSERT_GE(sub.get(), 0) << made.reason();
  const auto write = [&](const char* mode, const std::string& text) {
    BeneathError e;
    const int fd = file_beneath(t.root.get(), "a/b/f.txt", *file_mode(mode), &e);
    ASSERT_GE(fd, 0) << e.reason();
    ASSERT_EQ(::write(fd, text.data(), text.size()), static_cast<ssize_t>(text.size()));
    ::close(fd);
  };
  write("w", "one");
  EXPECT_EQ(slurp(t.in / "a" / "b" / "f.txt"), "one");
  write("a", "two");
  EXPECT_EQ(slurp(t.in / "a" / "b" / "f.txt"), "onetwo");
  write("r+", "X");
  EXPECT_EQ(slurp(t.in / "a" / "b" / "f.txt"), "Xnetwo");
  write("w+", "three");
  EXPECT_EQ(slurp(t.in / "a" / "b" / "f.txt"), "three");
}

}  // namespace beneath_test
}  // namespace beltsim
