// The text of a checkpoint: one writer and one reader for every part of it (the run settings,
// the scene, the drive, the integrator's state), so that the whole file has one format and one
// version.
//
//   beltsim-checkpoint 13            <- what it is, and the format version
//   integrator "esdirk32"            <- a key, then its values, one field per line
//   rtol 1e-04
//   probe 2 0 75                     <- sequences: the count, then the values
//   pulley.centre 0 0                <- fixed pairs: no count
//   ...
//   checksum fnv1a64 8c1f0e6d2a3b4c5d  <- FNV-1a 64 of every byte before this line
//
// Numbers are the shortest decimals that read back as the same double (io/number_text.hpp);
// strings are quoted, with \" \\ \n escaped; words (inside, true) stand bare; values are
// separated by one space, lines end in '\n'. The reader is strict: every line must open with the
// key expected there, every value must be whole and well-formed (a number finite unless the
// field allows otherwise), a count is believed only as far as the text holding its values goes,
// and nothing may follow the values. Every error names the line: "line 12: 'rtol': expected a
// number, got '1e-4x'".
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "io/fnv1a64.hpp"

namespace beltsim {

// Raised whenever anything a checkpoint holds changes (the scene's fields, scene/scene_fields.hpp;
// the run's state, sim/state_io.cpp; the settings, sim/checkpoint.cpp): a reader refuses every
// version before kCheckpointOldest and after this one. Version 13 added the outputs' fingerprints
// (sim/state_io.cpp); a version 12 checkpoint is read without them. Version 14 added the arms' and
// the couplings' energy integrals (model.hpp, EnergyIndex); an older checkpoint of a run that
// tracked energy is read with them at zero (sim/state_io.cpp, read_state).
inline constexpr int kCheckpointVersion = 14;
inline constexpr int kCheckpointOldest = 12;
inline constexpr const char* kCheckpointMagic = "beltsim-checkpoint";

// A checkpoint that cannot be read: "line N: reason".
struct CheckpointError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

class CheckpointWriter {
 public:
  CheckpointWriter();  // the first line: magic and version

  void line(std::string_view key, double x);
  void line(std::string_view key, long i);
  void line(std::string_view key, int i) { line(key, static_cast<long>(i)); }
  void line(std::string_view key, bool b);
  void line(std::string_view key, const std::string& s);  // quoted
  void line(std::string_view key, const char* s) = delete;  // (would be taken for a bool)
  void word(std::string_view key, std::string_view w);     // bare
  void fixed(std::string_view key, std::initializer_list<double> x);  // no count
  void optional(std::string_view key, std::optional<double> x);      // the number or "none"
  void line(std::string_view key, const double* x, size_t n);
  void line(std::string_view key, const std::vector<double>& v) { line(key, v.data(), v.size()); }
  void line(std::string_view key, const std::vector<int>& v);
  void line(std::string_view key, const std::vector<long>& v);
  void line(std::string_view key, const std::vector<std::string>& v);
  void line(std::string_view key, const std::map<std::string, double>& m);  // count, then "name" value pairs
  // a table: the count of rows, then x y of each row (x and y of one size)
  void pairs(std::string_view key, const std::vector<double>& x, const std::vector<double>& y);
  // a 64-bit hash as 16 hexadecimal digits (io/fnv1a64.hpp)
  void hash(std::string_view key, std::uint64_t h);

  // appends the checksum line and hands over the text
  std::string finish();

 private:
  void key(std::string_view k);
  void num(double x);
  void str(const std::string& s);
  std::string text_;
};

class CheckpointReader {
 public:
  // the whole text of a checkpoint. Checks at once that it is one (its first line) of a version
  // read (kCheckpointOldest to kCheckpointVersion), and that it ends in a checksum line (a file cut
  // short does not).
  explicit CheckpointReader(std::string text);
  // its format version (what an older one lacks is read as absent)
  int version() const { return version_; }

  // the next line, which must open with `key`; its values follow through the calls below
  void open(std::string_view key);
  // whether the next line opens with `key` (a part a checkpoint holds only when the run has it)
  bool next_is(std::string_view key) const;
  void close();  // nothing but the end of the line may follow
  double num();              // finite
  double num_or_infinity();  // finite or +inf
  double num_or_nan();       // finite or NaN
  std::optional<double> optional_num();  // finite or "none"
  long integer(long lo, long hi);
  bool boolean();            // true or false
  std::string str();
  std::string word();
  // a count of values that follow on this line, `per_value` tokens each: at most what the line
  // holds, and at most `most`
  size_t count(size_t per_value = 1, size_t most = SIZE_MAX);
  // a count of groups of `lines_each` lines that follow: at most the lines left, and at most `most`
  size_t group_count(size_t lines_each, size_t most = SIZE_MAX);

  // whole lines
  double line_num(std::string_view key) { return open(key), end_with(num()); }
  long line_int(std::string_view key, long lo, long hi) { return open(key), end_with(integer(lo, hi)); }
  bool line_bool(std::string_view key) { return open(key), end_with(boolean()); }
  std::string line_str(std::string_view key) { return open(key), end_with(str()); }
  // one of `words`, as its index
  int line_choice(std::string_view key, const std::vector<std::string>& words);
  std::optional<double> line_optional(std::string_view key) { return open(key), end_with(optional_num()); }
  std::vector<double> line_fixed(std::string_view key, size_t n);
  std::vector<double> line_doubles(std::string_view key, size_t most = SIZE_MAX);
  std::vector<double> line_doubles_or_nan(std::string_view key, size_t most = SIZE_MAX);  // NaN allowed too
  std::vector<int> line_ints(std::string_view key, long lo, long hi, size_t most = SIZE_MAX);
  std::vector<long> line_longs(std::string_view key, long lo, long hi, size_t most = SIZE_MAX);
  std::vector<std::string> line_strs(std::string_view key, size_t most = SIZE_MAX);
  std::map<std::string, double> line_map(std::string_view key, size_t most = SIZE_MAX);
  // 16 hexadecimal digits (CheckpointWriter::hash)
  std::uint64_t line_hash(std::string_view key);

  // the checksum line is next, it matches the text before it, and nothing follows
  void finish();
  int line_number() const { return line_no_; }
  const std::string& key() const { return key_; }
  // the line that last opened with `key`, 0 when none did (a check made after a part is read
  // names the line of the value it refuses)
  int line_of(std::string_view key) const;
  // "line N: 'key': what" for the line being read (CheckpointError)
  [[noreturn]] void fail(const std::string& what) const;
  [[noreturn]] void fail_at(int line, std::string_view key, const std::string& what) const;
  // "lines FROM to N: what" for a whole part read so far (a scene the validation refuses)
  [[noreturn]] void fail_lines(int from, const std::string& what) const { fail_lines(from, line_no_, what); }
  // "lines FROM to TO: what" for a part read before (run settings refused once the scene is read)
  [[noreturn]] void fail_lines(int from, int to, const std::string& what) const;

 private:
  template <class T>
  T end_with(T value) {
    close();
    return value;
  }
  std::string_view token();
  std::string with_note(std::string m) const;  // + the checksum's verdict when it failed
  size_t tokens_left() const;

  std::string text_;
  int version_ = 0;
  size_t next_ = 0;          // where the next line starts
  size_t body_end_ = 0;      // where the checksum line starts
  int lines_ = 0;            // lines of the body, the checksum line excluded
  int line_no_ = 0;          // the line being read (1-based)
  std::string_view line_;    // its text, without the '\n'
  size_t pos_ = 0;           // in line_
  std::string key_;
  bool intact_ = false;  // the text matches its checksum (read on, to name a damaged line if not)
  std::map<std::string, int, std::less<>> lines_of_;  // line_of
};

}  // namespace beltsim
