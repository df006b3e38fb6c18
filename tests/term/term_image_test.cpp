// term/term_image: a forced ImageMode (BELTSIM_TERM_IMAGES) writes even into a file: "symbols" gives ANSI
// colours and block characters in exactly the cells asked, "sixel" a DCS sequence (ESC P ... q),
// "kitty" an APC one (ESC _ G); without a forced mode nothing is written where the output is not
// a terminal, and every refusal says why.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "media/png_writer.hpp"
#include "term/term_image.hpp"
#include "support/scratch.hpp"

namespace beltsim::term {
namespace {

namespace fs = std::filesystem;

// a 320×180 picture: a colour gradient with a dark diagonal
std::string picture() {
  const fs::path p = beltsim::test::scratch_dir("beltsim_term_test") / "picture.png";
  Image img(320, 180);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      std::uint8_t* px = img.pixel(x, y);
      const bool line = std::abs(x * 180 / 320 - y) < 4;
      px[0] = line ? 20 : static_cast<std::uint8_t>(x * 255 / 319);
      px[1] = line ? 20 : static_cast<std::uint8_t>(y * 255 / 179);
      px[2] = line ? 20 : 160;
    }
  write_png(p.string(), img);
  return p.string();
}

// runs show_image_in_terminal into a temporary file (not a terminal) and returns what it wrote
struct Shown {
  bool ok = false;
  std::string text, why;
};
Shown show(const char* mode, CellSize size = {}) {
  static const std::string png = picture();
  std::FILE* f = std::tmpfile();
  Shown s;
  const std::optional<ImageMode> m = image_mode(mode ? mode : "");
  EXPECT_TRUE(m) << mode;
  s.ok = show_image_in_terminal(png, f, m.value_or(ImageMode::off), &s.why, size);
  std::rewind(f);
  char buf[4096];
  for (size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) s.text.append(buf, n);
  std::fclose(f);
  return s;
}

// the cells of one line: escape sequences dropped, UTF-8 characters counted once
int cells(const std::string& line) {
  int n = 0;
  for (size_t i = 0; i < line.size(); ++i) {
    if (line[i] == '\x1b' && i + 1 < line.size() && line[i + 1] == '[') {
      i += 2;
      while (i < line.size() && !(line[i] >= '@' && line[i] <= '~')) ++i;
      continue;
    }
    if ((static_cast<unsigned char>(line[i]) & 0xC0) != 0x80) ++n;
  }
  return n;
}

TEST(TermImage, SymbolsHaveColoursBlocksAndTheCellsAsked) {
  const Shown s = show("symbols", {40, 12});
  ASSERT_TRUE(s.ok) << s.why;
  EXPECT_NE(s.text.find("\x1b[38;2;"), std::string::npos);  // truecolor foreground
  EXPECT_NE(s.text.find(";48;2;"), std::string::npos);      // and background in the same sequence
  // block elements U+2580..U+259F are E2 96 80..9F in UTF-8
  bool block = false;
  for (size_t i = 0; i + 2 < s.text.size() && !block; ++i)
    block = s.text.compare(i, 2, "\xE2\x96") == 0 && static_cast<unsigned char>(s.text[i + 2]) >= 0x80 &&
            static_cast<unsigned char>(s.text[i + 2]) <= 0x9F;
  EXPECT_TRUE(block);
  // 12 lines of 40 cells
  int lines = 0;
  for (size_t a = 0, b; (b = s.text.find('\n', a)) != std::string::npos; a = b + 1, ++lines)
    EXPECT_EQ(cells(s.text.substr(a, b - a)), 40) << "line " << lines;
  EXPECT_EQ(lines, 12);
  EXPECT_EQ(s.text.back(), '\n');
}

TEST(TermImage, SymbolsKeepTheAspectWhenOnlyTheWidthIsGiven) {
  // 320×180 in 80 columns of cells twice as high as wide: 80·180/320/2 = 22.5 rows
  const Shown s = show("symbols");
  ASSERT_TRUE(s.ok) << s.why;
  int lines = 0;
  for (char c : s.text) lines += c == '\n';
  EXPECT_GE(lines, 22);
  EXPECT_LE(lines, 23);
  EXPECT_EQ(cells(s.text.substr(0, s.text.find('\n'))), 80);  // no terminal: 80 columns
}

TEST(TermImage, SixelIsADcsSequence) {
  const Shown s = show("sixel", {40, 12});
  ASSERT_TRUE(s.ok) << s.why;
  ASSERT_GT(s.text.size(), 100u);
  EXPECT_EQ(s.text.substr(0, 2), "\x1bP");
  const size_t q = s.text.find('q');
  ASSERT_NE(q, std::string::npos);
  EXPECT_LT(q, 16u);                                        // ESC P p1;p2;p3 q
  EXPECT_NE(s.text.find("\x1b\\"), std::string::npos);      // ended by ST
}

TEST(TermImage, KittyIsAnApcSequence) {
  const Shown s = show("kitty", {40, 12});
  ASSERT_TRUE(s.ok) << s.why;
  EXPECT_EQ(s.text.substr(0, 3), "\x1b_G");
}

TEST(TermImage, NothingWithoutATerminalOrWhenOff) {
  Shown s = show(nullptr);
  EXPECT_FALSE(s.ok);
  EXPECT_TRUE(s.text.empty());
  EXPECT_NE(s.why.find("not a terminal"), std::string::npos) << s.why;
  s = show("off");
  EXPECT_FALSE(s.ok);
  EXPECT_TRUE(s.text.empty());
  EXPECT_NE(s.why.find("off"), std::string::npos) << s.why;
  EXPECT_FALSE(image_mode("ascii-art"));
}

TEST(TermImage, AnUnreadablePngIsAReason) {
  std::string why;
  std::FILE* f = std::tmpfile();
  EXPECT_FALSE(show_image_in_terminal("/nonexistent/x.png", f, ImageMode::symbols, &why));
  std::fclose(f);
  EXPECT_NE(why.find("/nonexistent/x.png"), std::string::npos) << why;
}

}  // namespace
}  // namespace beltsim::term
