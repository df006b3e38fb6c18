#include "app/compare.hpp"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/options.hpp"
#include "io/input_file.hpp"
#include "io/output_dir.hpp"
#include "io/units.hpp"
#include "media/image_compare.hpp"
#include "media/png_writer.hpp"
#include "plot/csv_compare.hpp"
#include "script/script_args.hpp"

namespace beltsim::app {

namespace {

namespace fs = std::filesystem;

// compared, but the difference image could not be written (the exit status)
constexpr int kDiffNotWritten = 3;

// a file that cannot be read or is not a PNG or CSV of numbers (exit 2)
struct Unreadable : std::runtime_error {
  using std::runtime_error::runtime_error;
};

double non_negative(const std::string& option, const std::string& text) {
  const double x = number(option, text);
  if (!(x >= 0)) throw UsageError(option + " must be >= 0, got " + text);
  return x;
}

long whole(const std::string& option, const std::string& text, double hi) {
  const double x = number(option, text);
  if (!(x >= 0 && x <= hi && x == std::floor(x)))
    throw UsageError(option + " must be a whole number in [0, " + std::to_string(static_cast<long>(hi)) + "], got " + text);
  return static_cast<long>(x);
}

// true for a PNG (by its signature); throws Unreadable naming the file when it cannot be read (a
// regular file only: io/input_file.hpp)
bool is_png(const std::string& path) {
  try {
    InputFile f(path);
    static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    unsigned char head[8] = {};
    return std::fread(head, 1, 8, f.stream()) == 8 && std::memcmp(head, sig, 8) == 0;
  } catch (const InputFileError& e) {
    throw Unreadable(e.what());
  }
}

// --mask X,Y,W,H: four whole numbers [px], W and H > 0 (whether it meets the image is checked once
// the image is read)
PixelRect mask_rect(const std::string& text) {
  std::vector<std::string> parts;
  for (size_t at = 0;;) {
    const size_t comma = text.find(',', at);
    parts.push_back(text.substr(at, comma - at));
    if (comma == std::string::npos) break;
    at = comma + 1;
  }
  if (parts.size() != 4)
    throw UsageError("--mask needs X,Y,W,H (pixels from the top-left corner, width and height), got '" + text + "'");
  long v[4];
  for (int k = 0; k < 4; ++k) {
    const auto x = script::decimal(parts[k]);
    if (!x || *x != std::floor(*x) || std::abs(*x) > 1e9)
      throw UsageError("--mask " + text + ": X, Y, W and H must be whole numbers of pixels, got '" + parts[k] + "'");
    v[k] = static_cast<long>(*x);
  }
  if (v[2] <= 0 || v[3] <= 0) throw UsageError("--mask " + text + ": the width and height W and H must be > 0");
  return {static_cast<int>(v[0]), static_cast<int>(v[1]), static_cast<int>(v[2]), static_cast<int>(v[3])};
}

std::string size_text(const Image& i) {
  return std::to_string(i.width) + "x" + std::to_string(i.height);
}

// "A" or "B" (with its path when spelt otherwise) when the difference image's path names the same file (by device and
// inode, so through another spelling, a link or a second hard link too), else "": writing it there replaced the file
// compared, a golden reference perhaps (a user trial: `--diff gold/g.png` replaced the golden g.png with the
// red-on-grey picture, and the next compare failed against it)
std::string compared_file_at(const std::string& diff, const CompareOptions& o) {
  std::error_code ec;
  for (const std::string* f : {&o.a, &o.b})
    if (fs::equivalent(diff, *f, ec)) return (f == &o.a ? "A" : "B") + (*f == diff ? "" : " (" + *f + ")");
  return "";
}

int compare_pngs(const CompareOptions& o) {
  for (const auto& [given, name] : {std::pair{bool(o.rtol), "--rtol"},
                                    {!o.atol.empty(), "--atol"},
                                    {!o.col_tol.empty(), "--col-tol"},
                                    {!o.skip.empty(), "--skip"},
                                    {o.failing, "--failing"},
                                    {o.partial, "--partial"}})
    if (given) throw UsageError(std::string(name) + " is for CSV files; " + o.a + " and " + o.b + " are PNGs");
  ImageTolerance tol;
  if (o.tol) tol.level_tol = static_cast<int>(whole("--tol", *o.tol, 255));
  if (o.max_bad) tol.max_bad_pixels = whole("--max-bad", *o.max_bad, 1e15);
  if (o.diff) require_png("--diff", *o.diff);
  if (o.diff)
    if (const std::string f = compared_file_at(*o.diff, o); !f.empty())
      throw UsageError("--diff " + *o.diff + " is " + f +
                       ", a file compared: the difference image would replace it; "
                       "give it another name");
  std::vector<PixelRect> mask;
  for (const std::string& m : o.mask) mask.push_back(mask_rect(m));
  Image a, b;
  try {
    a = read_png(o.a);
    b = read_png(o.b);
  } catch (const std::exception& e) {
    throw Unreadable(e.what());
  }
  if (a.width != b.width || a.height != b.height) {
    std::printf("differ: the sizes differ: %s is %s, %s is %s\n", o.a.c_str(), size_text(a).c_str(), o.b.c_str(),
                size_text(b).c_str());
    return 1;
  }
  // a mask that misses the picture is a mistake (a typo, or the picture of another size): said, not ignored
  for (size_t k = 0; k < mask.size(); ++k) {
    const PixelRect& r = mask[k];
    if (r.x >= a.width || r.y >= a.height || r.x + r.w <= 0 || r.y + r.h <= 0)
      throw UsageError("--mask " + o.mask[k] + " lies wholly outside the " + size_text(a) + " pictures");
  }
  // the text of both frames: a label that moved or grew in one is left out where either has it
  if (o.ignore_text) {
    if (a.text_boxes.empty() && b.text_boxes.empty())
      throw UsageError("--ignore-text: " + o.a + " and " + o.b +
                       " carry no text boxes (made by another program or an older beltsim); leave regions out with "
                       "--mask X,Y,W,H");
    mask.insert(mask.end(), a.text_boxes.begin(), a.text_boxes.end());
    mask.insert(mask.end(), b.text_boxes.begin(), b.text_boxes.end());
  }
  const ImageComparison c = compare_images(a, b, tol.level_tol, mask);
  // a mask that covers the whole picture compares nothing: a golden test whose mask grew by
  // mistake (a wrong W,H) reported a match forever (a user trial)
  if (c.masked >= static_cast<long>(a.width) * a.height)
    throw UsageError(std::string(o.mask.empty()  ? "--ignore-text"
                                 : o.ignore_text ? "--mask and --ignore-text"
                                                 : "--mask") +
                     " left no pixel of the " + size_text(a) +
                     " pictures to compare: nothing was compared; leave "
                     "out less");
  const bool match = c.match(tol);
  std::string diff_note;
  bool diff_failed = false;
  if (!match || o.diff) {
    const fs::path pa(o.a);
    const std::string path = o.diff ? *o.diff : (pa.parent_path() / (pa.stem().string() + "_diff.png")).string();
    try {
      // (a --diff that is A or B was refused before anything was read)
      if (const std::string f = compared_file_at(path, o); !f.empty())
        throw std::runtime_error("the difference image's default name " + path + " (A's with _diff) is " + f +
                                 ", a file compared: not written over it; give the difference image another name "
                                 "with --diff PNG");
      write_png(path, c.diff);
      diff_note = std::string("; difference image (differing pixels red") + (mask.empty() ? "" : ", masked dark blue") +
                  "): " + path;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "beltsim compare: %s\n", e.what());
      mark_output_failure_shown(e.what());
      diff_failed = true;
    }
  }
  const std::string masked = mask.empty() ? "" : "; " + std::to_string(c.masked) + " pixels masked";
  std::printf("%s: %ld of %s pixels differ by more than %d levels (%ld allowed); largest difference %d levels%s%s%s\n",
              match ? "match" : "differ", c.bad, size_text(a).c_str(), tol.level_tol, tol.max_bad_pixels, c.worst,
              c.worst ? (" at x = " + std::to_string(c.worst_x) + ", y = " + std::to_string(c.worst_y)).c_str() : "",
              masked.c_str(), diff_note.c_str());
  // one meaning per status: 3 whenever the difference image could not be written, the line
  // above saying whether they match (docs/testing-your-scenario.md)
  return diff_failed ? kDiffNotWritten : match ? 0 : 1;
}

int compare_csvs(const CompareOptions& o) {
  for (const auto& [given, name] : {std::pair{bool(o.tol), "--tol"},
                                    {bool(o.max_bad), "--max-bad"},
                                    {bool(o.diff), "--diff"},
                                    {!o.mask.empty(), "--mask"},
                                    {o.ignore_text, "--ignore-text"}})
    if (given) throw UsageError(std::string(name) + " is for PNG files; " + o.a + " and " + o.b + " are not PNGs");
  plot::CsvTolerance tol;
  if (o.rtol) tol.rtol = non_negative("--rtol", *o.rtol);
  for (const std::string& item : o.atol) {
    const size_t eq = item.find('=');
    if (eq == std::string::npos) {
      if (tol.atol) throw UsageError("--atol A is given twice; give it once (and --atol UNIT=A for a unit's own)");
      tol.atol = non_negative("--atol", item);
      continue;
    }
    const std::string unit = typed_unit(item.substr(0, eq));
    if (tol.unit_atol.count(unit)) throw UsageError("--atol " + item + ": the unit '" + unit + "' is given twice");
    tol.unit_atol[unit] = non_negative("--atol " + item.substr(0, eq), item.substr(eq + 1));
  }
  for (const std::string& item : o.col_tol) {
    const size_t eq = item.find('=');
    if (eq == std::string::npos || eq == 0)
      throw UsageError("--col-tol needs NAME=RTOL or NAME=RTOL,ATOL, got '" + item + "'");
    const std::string name = item.substr(0, eq), value = item.substr(eq + 1);
    const size_t comma = value.find(',');
    tol.column_rtol[name] = non_negative("--col-tol " + name, value.substr(0, comma));
    if (comma != std::string::npos) tol.column_atol[name] = non_negative("--col-tol " + name, value.substr(comma + 1));
  }
  tol.skip.insert(o.skip.begin(), o.skip.end());
  tol.partial = o.partial;
  plot::Table a, b;
  try {
    a = plot::read_timeseries_csv(o.a);
    b = plot::read_timeseries_csv(o.b);
  } catch (const std::exception& e) {
    throw Unreadable(e.what());
  }
  // a unit no compared column has (a typo, "nm" for N·m) would leave every tolerance as it was, silently
  std::set<std::string> units;
  for (const std::string& name : a.names)
    if (!tol.skip.count(name)) units.insert(header_unit(name));
  for (const auto& [unit, value] : tol.unit_atol)
    if (!units.count(unit)) {
      std::string have;
      for (const std::string& u : units) have += (have.empty() ? "" : ", ") + (u.empty() ? std::string("1") : u);
      const std::string shown = unit.empty() ? "1" : unit;  // the dimensionless, as typed
      throw UsageError("--atol " + shown + "=...: no column of " + o.a + (tol.skip.empty() ? "" : " left in") +
                       " has the unit '" + shown + "' (its units: " + have + ")");
    }
  plot::CsvComparison c;
  try {
    c = plot::compare_csv(a, b, tol);
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  } catch (const std::exception& e) {
    throw Unreadable(e.what());
  }
  if (!c.note.empty()) std::fprintf(stderr, "beltsim compare: %s\n", c.note.c_str());
  std::printf("%s: %s\n", c.match ? "match" : "differ", c.reason.c_str());
  if (o.failing)
    for (const std::string& line : plot::failing_lines(c)) std::printf("%s\n", line.c_str());
  return c.match ? 0 : 1;
}

}  // namespace

int cmd_compare(const CompareOptions& o) {
  try {
    const bool pa = is_png(o.a), pb = is_png(o.b);
    if (pa != pb)
      throw UsageError("cannot compare a PNG with a file that is not one: " + (pa ? o.a : o.b) + " is a PNG, " +
                       (pa ? o.b : o.a) + " is not");
    return pa ? compare_pngs(o) : compare_csvs(o);
  } catch (const UsageError& e) {
    std::fprintf(stderr, "beltsim: %s\nRun 'beltsim compare --help' for the usage.\n", e.what());
    return 2;
  } catch (const Unreadable& e) {
    std::fprintf(stderr, "beltsim compare: %s\n", e.what());
    return 2;
  }
}

}  // namespace beltsim::app
