#include "io/checkpoint_text.hpp"

#include <algorithm>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdio>

#include "io/number_text.hpp"

namespace beltsim {

namespace {

constexpr std::string_view kChecksumKey = "checksum fnv1a64 ";

// a piece of a line for a message: printable, at most 40 characters
std::string shown(std::string_view s) {
  std::string out;
  for (char c : s.substr(0, 40)) out += (c >= ' ' && c < 127) ? c : '?';
  return s.size() > 40 ? out + "..." : out;
}

std::string hex64(std::uint64_t h) {
  char b[17];
  std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(h));
  return b;
}

}  // namespace

// ---- writing -------------------------------------------------------------------------------

CheckpointWriter::CheckpointWriter() {
  text_ = kCheckpointMagic;
  text_ += ' ' + std::to_string(kCheckpointVersion) + '\n';
}

void CheckpointWriter::key(std::string_view k) { text_.append(k); }
void CheckpointWriter::num(double x) { text_ += ' ', append_number(text_, x); }
void CheckpointWriter::str(const std::string& s) {
  text_ += " \"";
  for (char c : s) {
    if (c == '"' || c == '\\') text_ += '\\', text_ += c;
    else if (c == '\n') text_ += "\\n";
    else text_ += c;
  }
  text_ += '"';
}

void CheckpointWriter::line(std::string_view k, double x) { key(k), num(x), text_ += '\n'; }
void CheckpointWriter::line(std::string_view k, long i) { key(k), text_ += ' ' + std::to_string(i) + '\n'; }
void CheckpointWriter::line(std::string_view k, bool b) { word(k, b ? "true" : "false"); }
void CheckpointWriter::line(std::string_view k, const std::string& s) { key(k), str(s), text_ += '\n'; }
void CheckpointWriter::word(std::string_view k, std::string_view w) {
  key(k), text_ += ' ', text_.append(w), text_ += '\n';
}
void CheckpointWriter::fixed(std::string_view k, std::initializer_list<double> x) {
  key(k);
  for (double v : x) num(v);
  text_ += '\n';
}
void CheckpointWriter::optional(std::string_view k, std::optional<double> x) {
  if (x) line(k, *x);
  else word(k, "none");
}
void CheckpointWriter::line(std::string_view k, const double* x, size_t n) {
  key(k), text_ += ' ' + std::to_string(n);
  for (size_t i = 0; i < n; ++i) num(x[i]);
  text_ += '\n';
}
void CheckpointWriter::line(std::string_view k, const std::vector<int>& v) {
  key(k), text_ += ' ' + std::to_string(v.size());
  for (int i : v) text_ += ' ' + std::to_string(i);
  text_ += '\n';
}
void CheckpointWriter::line(std::string_view k, const std::vector<long>& v) {
  key(k), text_ += ' ' + std::to_string(v.size());
  for (long i : v) text_ += ' ' + std::to_string(i);
  text_ += '\n';
}
void CheckpointWriter::line(std::string_view k, const std::vector<std::string>& v) {
  key(k), text_ += ' ' + std::to_string(v.size());
  for (const std::string& s : v) str(s);
  text_ += '\n';
}
void CheckpointWriter::line(std::string_view k, const std::map<std::string, double>& m) {
  key(k), text_ += ' ' + std::to_string(m.size());
  for (const auto& [s, x] : m) str(s), num(x);
  text_ += '\n';
}

void CheckpointWriter::pairs(std::string_view k, const std::vector<double>& x, const std::vector<double>& y) {
  key(k), text_ += ' ' + std::to_string(x.size());
  for (size_t i = 0; i < x.size(); ++i) num(x[i]), num(y[i]);
  text_ += '\n';
}

void CheckpointWriter::hash(std::string_view k, std::uint64_t h) {
  word(k, hex64(h));
}

std::string CheckpointWriter::finish() {
  const std::uint64_t h = fnv1a64(text_);
  text_.append(kChecksumKey);
  text_ += hex64(h) + '\n';
  return std::move(text_);
}

// ---- reading -------------------------------------------------------------------------------

CheckpointReader::CheckpointReader(std::string text) : text_(std::move(text)) {
  // line 1: what it is and its version
  const size_t eol = text_.find('\n');
  const std::string_view first = std::string_view(text_).substr(0, eol == std::string::npos ? text_.size() : eol);
  line_no_ = 1;
  const std::string_view magic = kCheckpointMagic;
  const size_t sp = first.find(' ');
  long version = -1;
  if (sp != std::string_view::npos) {
    const std::string_view v = first.substr(sp + 1);
    if (std::from_chars(v.data(), v.data() + v.size(), version).ptr != v.data() + v.size()) version = -1;
  }
  if (first.substr(0, sp) != magic || version < 0)
    throw CheckpointError("line 1: not a beltsim checkpoint (it begins '" + shown(first) + "')");
  if (version < kCheckpointOldest || version > kCheckpointVersion)
    throw CheckpointError("line 1: a version " + std::to_string(version) + " checkpoint; this beltsim reads " +
                          (kCheckpointOldest == kCheckpointVersion
                               ? "version " + std::to_string(kCheckpointVersion)
                               : "versions " + std::to_string(kCheckpointOldest) +
                                     (kCheckpointOldest + 1 == kCheckpointVersion ? " and " : " to ") +
                                     std::to_string(kCheckpointVersion)) +
                          " only: resume it with the beltsim that wrote it, or run the scene again from its script");
  version_ = static_cast<int>(version);
  next_ = eol + 1;
  // the last line: the checksum of everything before it
  const long total = static_cast<long>(std::count(text_.begin(), text_.end(), '\n'));
  if (text_.back() != '\n')
    throw CheckpointError("line " + std::to_string(total + 1) +
                          ": the file ends inside a line, without its checksum line: it was cut short");
  body_end_ = text_.rfind('\n', text_.size() - 2) + 1;
  const std::string_view last = std::string_view(text_).substr(body_end_, text_.size() - 1 - body_end_);
  if (body_end_ <= next_ || last.substr(0, kChecksumKey.size()) != kChecksumKey ||
      last.size() != kChecksumKey.size() + 16)
    throw CheckpointError("line " + std::to_string(total) + ": '" + shown(last) +
                          "' where the checksum line should end the file: it was cut short or damaged");
  intact_ = last.substr(kChecksumKey.size()) == hex64(fnv1a64(std::string_view(text_).substr(0, body_end_)));
  lines_ = static_cast<int>(total - 1);
}

void CheckpointReader::fail(const std::string& what) const { fail_at(line_no_, key_, what); }

std::string CheckpointReader::with_note(std::string m) const {
  if (!intact_)
    m += " (and the file does not match its checksum, line " + std::to_string(lines_ + 1) +
         ": it was damaged or changed after it was written)";
  return m;
}

void CheckpointReader::fail_at(int line, std::string_view key, const std::string& what) const {
  throw CheckpointError(with_note("line " + std::to_string(line) + ": " +
                                  (key.empty() ? "" : "'" + std::string(key) + "': ") + what));
}

void CheckpointReader::fail_lines(int from, int to, const std::string& what) const {
  throw CheckpointError(with_note("lines " + std::to_string(from) + " to " + std::to_string(to) + ": " + what));
}

void CheckpointReader::open(std::string_view key) {
  key_.clear();
  if (next_ >= body_end_) {
    line_no_ = lines_ + 1;
    fail("expected '" + std::string(key) + "', got the checksum line: the file ends early");
  }
  const size_t eol = text_.find('\n', next_);
  line_ = std::string_view(text_).substr(next_, eol - next_);
  next_ = eol + 1;
  ++line_no_;
  pos_ = std::min(line_.find(' '), line_.size());
  const std::string_view got = line_.substr(0, pos_);
  if (got != key) fail("expected '" + std::string(key) + "', got '" + shown(got) + "'");
  key_ = key;
  if (const auto at = lines_of_.find(key); at != lines_of_.end()) at->second = line_no_;
  else lines_of_.emplace(key, line_no_);
}

int CheckpointReader::line_of(std::string_view key) const {
  const auto at = lines_of_.find(key);
  return at == lines_of_.end() ? 0 : at->second;
}

bool CheckpointReader::next_is(std::string_view key) const {
  if (next_ >= body_end_) return false;
  const std::string_view rest = std::string_view(text_).substr(next_);
  return rest.substr(0, key.size()) == key && rest.size() > key.size() &&
         (rest[key.size()] == ' ' || rest[key.size()] == '\n');
}

void CheckpointReader::close() {
  if (pos_ < line_.size()) fail("unexpected '" + shown(line_.substr(pos_)) + "' after the values");
}

std::string_view CheckpointReader::token() {
  if (pos_ >= line_.size()) return {};
  if (line_[pos_] != ' ') fail("expected a space after the value, got '" + shown(line_.substr(pos_)) + "'");
  const size_t b = ++pos_;
  pos_ = std::min(line_.find(' ', b), line_.size());
  if (pos_ == b) fail("an empty value (two spaces in a row, or a space at the end of the line)");
  return line_.substr(b, pos_ - b);
}

size_t CheckpointReader::tokens_left() const {
  return static_cast<size_t>(std::count(line_.begin() + static_cast<std::ptrdiff_t>(pos_), line_.end(), ' '));
}

double CheckpointReader::num() {
  const double x = num_or_infinity();
  if (std::isinf(x)) fail("expected a finite number, got " + number_text(x));
  return x;
}

double CheckpointReader::num_or_infinity() {
  const std::string_view t = token();
  if (t.empty()) fail("expected a number, got the end of the line");
  const std::optional<double> x = parse_number(t);
  if (!x) fail("expected a number, got '" + shown(t) + "'");
  if (std::isnan(*x) || *x == -INFINITY) fail("expected a finite number, got " + number_text(*x));
  return *x;
}

double CheckpointReader::num_or_nan() {
  const size_t at = pos_;
  if (token() == "nan") return std::nan("");
  pos_ = at;
  return num();
}

std::optional<double> CheckpointReader::optional_num() {
  const size_t at = pos_;
  if (token() == "none") return std::nullopt;
  pos_ = at;
  return num();
}

long CheckpointReader::integer(long lo, long hi) {
  const std::string_view t = token();
  if (t.empty()) fail("expected an integer, got the end of the line");
  long i = 0;
  const auto r = std::from_chars(t.data(), t.data() + t.size(), i);
  if (r.ec != std::errc() || r.ptr != t.data() + t.size()) fail("expected an integer, got '" + shown(t) + "'");
  if (i < lo || i > hi)
    fail(std::string(t) + " is out of range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return i;
}

bool CheckpointReader::boolean() {
  const std::string_view t = token();
  if (t != "true" && t != "false") fail("expected true or false, got '" + shown(t) + "'");
  return t == "true";
}

std::string CheckpointReader::str() {
  if (pos_ >= line_.size()) fail("expected a quoted string, got the end of the line");
  if (line_[pos_] != ' ' || pos_ + 1 >= line_.size() || line_[pos_ + 1] != '"')
    fail("expected a quoted string, got '" + shown(line_.substr(pos_)) + "'");
  std::string s;
  for (pos_ += 2; pos_ < line_.size(); ++pos_) {
    char c = line_[pos_];
    if (c == '"') {
      ++pos_;
      return s;
    }
    if (c == '\\') {
      if (++pos_ >= line_.size()) break;
      c = line_[pos_];
      if (c == 'n') c = '\n';
      else if (c != '"' && c != '\\') fail(std::string("an unknown escape '\\") + shown(std::string_view(&c, 1)) + "'");
    }
    s += c;
  }
  fail("a string without its closing quote");
}

std::string CheckpointReader::word() {
  const std::string_view t = token();
  if (t.empty()) fail("expected a word, got the end of the line");
  return std::string(t);
}

size_t CheckpointReader::count(size_t per_value, size_t most) {
  const long n = integer(0, LONG_MAX);
  const size_t left = tokens_left();
  if (static_cast<size_t>(n) > left / per_value)
    fail(std::to_string(n) + " values announced, the line holds " + std::to_string(left / per_value));
  if (static_cast<size_t>(n) > most)
    fail(std::to_string(n) + " values, more than the " + std::to_string(most) + " this checkpoint's scene has room for");
  return static_cast<size_t>(n);
}

size_t CheckpointReader::group_count(size_t lines_each, size_t most) {
  const long n = integer(0, LONG_MAX);
  const size_t left = static_cast<size_t>(lines_ - line_no_);
  if (static_cast<size_t>(n) > left / lines_each)
    fail(std::to_string(n) + " entries of " + std::to_string(lines_each) + " lines announced, the file has " +
         std::to_string(left) + " lines left");
  if (static_cast<size_t>(n) > most)
    fail(std::to_string(n) + " entries, more than the " + std::to_string(most) + " this checkpoint's scene has");
  return static_cast<size_t>(n);
}

int CheckpointReader::line_choice(std::string_view k, const std::vector<std::string>& words) {
  open(k);
  const std::string w = word();
  for (size_t i = 0; i < words.size(); ++i)
    if (w == words[i]) return close(), static_cast<int>(i);
  std::string list;
  for (const std::string& s : words) list += (list.empty() ? "" : " or ") + s;
  fail("expected " + list + ", got '" + shown(w) + "'");
}

std::vector<double> CheckpointReader::line_fixed(std::string_view k, size_t n) {
  open(k);
  std::vector<double> v;
  for (size_t i = 0; i < n; ++i) v.push_back(num());
  return end_with(std::move(v));
}

std::vector<double> CheckpointReader::line_doubles(std::string_view k, size_t most) {
  open(k);
  std::vector<double> v(count(1, most));
  for (double& x : v) x = num();
  return end_with(std::move(v));
}

std::vector<double> CheckpointReader::line_doubles_or_nan(std::string_view k, size_t most) {
  open(k);
  std::vector<double> v(count(1, most));
  for (double& x : v) x = num_or_nan();
  return end_with(std::move(v));
}

std::vector<int> CheckpointReader::line_ints(std::string_view k, long lo, long hi, size_t most) {
  open(k);
  std::vector<int> v(count(1, most));
  for (int& x : v) x = static_cast<int>(integer(std::max<long>(lo, INT_MIN), std::min<long>(hi, INT_MAX)));
  return end_with(std::move(v));
}

std::vector<long> CheckpointReader::line_longs(std::string_view k, long lo, long hi, size_t most) {
  open(k);
  std::vector<long> v(count(1, most));
  for (long& x : v) x = integer(lo, hi);
  return end_with(std::move(v));
}

std::vector<std::string> CheckpointReader::line_strs(std::string_view k, size_t most) {
  open(k);
  std::vector<std::string> v(count(1, most));
  for (std::string& s : v) s = str();
  return end_with(std::move(v));
}

std::map<std::string, double> CheckpointReader::line_map(std::string_view k, size_t most) {
  open(k);
  std::map<std::string, double> m;
  for (size_t i = 0, n = count(2, most); i < n; ++i) {
    std::string s = str();
    if (m.count(s)) fail("'" + shown(s) + "' twice");
    m[s] = num();
  }
  return end_with(std::move(m));
}

std::uint64_t CheckpointReader::line_hash(std::string_view k) {
  open(k);
  const std::string w = word();
  std::uint64_t h = 0;
  if (w.size() != 16 || std::from_chars(w.data(), w.data() + w.size(), h, 16).ptr != w.data() + w.size())
    fail("expected 16 hexadecimal digits, got '" + shown(w) + "'");
  return end_with(h);
}

void CheckpointReader::finish() {
  key_.clear();
  if (next_ < body_end_) {
    const size_t eol = text_.find('\n', next_);
    ++line_no_;
    fail("unexpected '" + shown(std::string_view(text_).substr(next_, eol - next_)) +
         "' where the checksum line should come");
  }
  line_no_ = lines_ + 1;
  if (!intact_) {
    intact_ = true;  // (the message says it once)
    fail("the checksum does not match the text before it: the file was damaged or changed after it was written");
  }
}

}  // namespace beltsim
