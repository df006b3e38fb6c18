// Outputs' state for a pause and a resume (declared in outputs.hpp): what a checkpoint records of
// the files written so far (rows, sizes, hashes), the checks that a folder still holds them when a
// run resumes, and the files cut back to that state.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>

#include "io/csv_writer.hpp"
#include "io/output_dir.hpp"
#include "io/row_file.hpp"
#include "io/suggest.hpp"
#include "sim/outputs.hpp"

namespace beltsim {

Outputs::State Outputs::get_state() const {
  State s = last_;
  s.rows = rows_, s.frames = frames_written();
  if (dir_)
    s.csv_bytes = bytes("timeseries.csv"), s.events_bytes = bytes("events.csv"),
    s.snapshots_bytes = has_snapshots() ? bytes("snapshots.csv") : 0;
  if (csv_) s.csv_hash = csv_->file().hash();
  if (events_) s.events_hash = events_->hash();
  if (snapshots_) s.snapshots_hash = snapshots_->hash();
  return s;
}

namespace {

// an output of the claimed folder read for a resume's checks: a regular file, never through a link
class ReadOutput {
 public:
  explicit ReadOutput(const std::string& path) : path_(path) {
    fd_ = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOFOLLOW | O_CLOEXEC);
    if (fd_ < 0) throw std::runtime_error("the run's output " + path + " cannot be read: " + std::strerror(errno));
    struct stat st {};
    if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode))
      throw std::runtime_error("the run's output " + path + " is not a regular file");
    size_ = st.st_size;
  }
  ~ReadOutput() { ::close(fd_); }
  ReadOutput(const ReadOutput&) = delete;
  ReadOutput& operator=(const ReadOutput&) = delete;
  const std::string& path() const { return path_; }
  long size() const { return size_; }
  // up to n bytes from `at` (fewer at the end of the file)
  std::string read(long at, long n) const {
    std::string b(static_cast<size_t>(n), '\0');
    long got = 0;
    while (got < n) {
      const ssize_t k = ::pread(fd_, b.data() + got, static_cast<size_t>(n - got), at + got);
      if (k < 0 && errno == EINTR) continue;
      if (k < 0) throw std::runtime_error("the run's output " + path_ + " cannot be read: " + std::strerror(errno));
      if (k == 0) break;
      got += k;
    }
    b.resize(static_cast<size_t>(got));
    return b;
  }
  // the end of its first line (the byte after its '\n') when it ends before `bytes`, else -1
  long header_end(long bytes) const {
    for (long at = 0; at < bytes;) {
      const std::string b = read(at, std::min(4096L, bytes - at));
      if (b.empty()) break;
      if (const size_t nl = b.find('\n'); nl != std::string::npos) return at + static_cast<long>(nl) + 1;
      at += static_cast<long>(b.size());
    }
    return -1;
  }
  // FNV-1a 64 of its first `bytes` bytes (io/fnv1a64.hpp)
  std::uint64_t hash(long bytes) const {
    std::uint64_t h = kFnv1a64Empty;
    for (long at = 0; at < bytes;) {
      const std::string b = read(at, std::min(1L << 20, bytes - at));
      if (b.empty()) break;
      h = fnv1a64(b, h);
      at += static_cast<long>(b.size());
    }
    return h;
  }
  // the first cell of the row that ends at `bytes` (its time, in timeseries.csv), as written
  std::string first_cell_before(long bytes) const {
    long start = 0;  // where the row begins: after the '\n' before its own
    for (long end = bytes - 1; end > 0;) {
      const long from = std::max(0L, end - 4096);
      const std::string b = read(from, end - from);
      if (const size_t nl = b.rfind('\n'); nl != std::string::npos) {
        start = from + static_cast<long>(nl) + 1;
        break;
      }
      end = from;
    }
    const std::string row = read(start, std::min(bytes - 1 - start, 64L));
    return row.substr(0, row.find(','));
  }

 private:
  std::string path_;
  int fd_ = -1;
  long size_ = 0;
};

// An output cut back to `bytes`: the position must lie past its header line, on the end of a row,
// within the file as it is now; with `header`, its header line must be that one (the run's own:
// another scene's run into the folder since the save writes another, and its rows would go on
// under ours, or be cut at a row end by chance).
void check_cut(const ReadOutput& f, long bytes, const std::string* want = nullptr) {
  const std::string& path = f.path();
  if (f.size() < bytes)
    throw std::runtime_error("the run's output " + path + " (" + std::to_string(f.size()) +
                             " bytes) is shorter than when the checkpoint was taken (" + std::to_string(bytes) + ")");
  const long header = f.header_end(bytes);
  if (header < 0 || bytes < header)
    throw std::runtime_error("the checkpoint continues " + path + " from byte " + std::to_string(bytes) +
                             ", inside its header line: cutting it there would lose the header");
  if (want && (header - 1 != static_cast<long>(want->size()) || f.read(0, header - 1) != *want))
    throw std::runtime_error("the run's output " + path +
                             " is not this run's: its header is not the one this simulation writes (another run "
                             "has written the folder since the checkpoint was saved)");
  if (f.read(bytes - 1, 1) != "\n")
    throw std::runtime_error("the checkpoint continues " + path + " from byte " + std::to_string(bytes) +
                             ", which is not the end of a row");
}

// what differs between the file and the state's fingerprint of it, "" when nothing does (a
// time last_t NaN: no row to compare)
std::string fingerprint_difference(const ReadOutput& f, long bytes, std::uint64_t hash, double last_t) {
  if (!std::isnan(last_t)) {
    const std::string cell = f.first_cell_before(bytes);
    if (parse_number(cell) != last_t)
      return "its row ending at byte " + std::to_string(bytes) + " is at t = " + cell +
             " s, where the checkpoint's run had written its last at t = " + value_text(last_t) + " s";
  }
  if (f.hash(bytes) != hash)
    return "its first " + std::to_string(bytes) + " bytes" +
           (std::isnan(last_t) ? std::string() : ", to t = " + value_text(last_t) + " s,") +
           " are not the ones the checkpoint's run wrote";
  return "";
}

}  // namespace

// the files a state cuts, with their sizes and hashes in it
std::vector<Outputs::Cut> Outputs::cuts(const State& s) const {
  std::vector<Cut> c{{"timeseries.csv", s.csv_bytes, s.csv_hash}, {"events.csv", s.events_bytes, s.events_hash}};
  if (has_snapshots()) c.push_back({"snapshots.csv", s.snapshots_bytes, s.snapshots_hash});
  return c;
}

void Outputs::check_state(const State& s) const {
  if (sink_ && s.frames != frames_written())
    throw std::runtime_error("the run has drawn " + std::to_string(frames_written()) + " frames, the state " +
                             std::to_string(s.frames) + ": frames drawn cannot be taken back");
  if (dir_) check_files(s, dir_->path());
}

void Outputs::check_files(const State& s, const std::string& from) const {
  const auto path = [&from](const char* name) { return output_path(from, name); };
  const std::string series = csv_header(timeseries_columns(scene_, rs_.probes.size()));
  for (const Cut& c : cuts(s))
    check_cut(ReadOutput(path(c.name)), c.bytes, std::string(c.name) == "timeseries.csv" ? &series : nullptr);
  if (!s.fingerprinted) return;
  // the files up to the state's sizes are the ones its run wrote, byte for byte: a later run of
  // the same scene into the folder writes the same header, and a row end at the same byte is a
  // matter of chance (a user's resume spliced two runs of different pretensions so)
  std::vector<std::string> differ;
  if (s.parameters_bytes > 0) {  // (0: none was there when a version 12 checkpoint was resumed)
    const ReadOutput f(path("parameters.csv"));
    if (f.size() < s.parameters_bytes || f.hash(s.parameters_bytes) != s.parameters_hash)
      differ.push_back("parameters.csv (its first " + std::to_string(s.parameters_bytes) +
                       " bytes, the parameters the checkpoint's run wrote at its start, differ)");
  }
  for (const Cut& c : cuts(s)) {
    const bool series_file = std::string(c.name) == "timeseries.csv";
    const std::string d =
        fingerprint_difference(ReadOutput(path(c.name)), c.bytes, c.hash, series_file ? s.csv_last_t : NAN);
    if (!d.empty()) differ.push_back(std::string(c.name) + " (" + d + ")");
  }
  if (!differ.empty())
    throw std::runtime_error(
        "the outputs in " + from + " are not the ones this checkpoint's run wrote: " + and_list(differ) +
        ". Another run has written the folder since the checkpoint was saved, and continuing would join this "
        "checkpoint's run to that run's rows. Nothing was changed: resume a checkpoint the later run saved, or run "
        "the script that saved this one again (each run its own folder: --out or out = ...)");
}

Outputs::State Outputs::branch(const State& s, const std::string& from) {
  const OutputDir& dir = claim();
  // the rows up to the state copied in whole rows, a MB at a time (a long run's timeseries.csv
  // need not fit in memory): each file as its run wrote it, so its hash goes on from the state's
  for (const Cut& c : cuts(s)) {
    const ReadOutput in(output_path(from, c.name));
    RowFile copy(dir, c.name, false);
    std::string rest;
    for (long at = 0; at < c.bytes;) {
      const std::string b = in.read(at, std::min(1L << 20, c.bytes - at));
      if (b.empty()) throw std::runtime_error("the run's output " + in.path() + " ended while it was copied");
      at += static_cast<long>(b.size());
      rest += b;
      const size_t end = rest.rfind('\n') + 1;  // (0 when no row ends in it yet)
      if (end > 0) copy.write(std::string_view(rest).substr(0, end)), rest.erase(0, end);
    }
  }
  // parameters.csv the branch's own: its start as its run wrote it, but for run.out
  start_parameters();
  State b = s;
  b.parameters_bytes = last_.parameters_bytes, b.parameters_hash = last_.parameters_hash;
  return b;
}

Outputs::State Outputs::with_fingerprints(const State& s) const {
  State f = s;
  f.fingerprinted = true;
  if (!dir_) return f;
  for (const Cut& c : cuts(s)) {
    const ReadOutput r(path(c.name));
    const std::uint64_t h = r.hash(c.bytes);
    if (std::string(c.name) == "timeseries.csv") {
      f.csv_hash = h;
      if (s.rows > 0) f.csv_last_t = parse_number(r.first_cell_before(c.bytes)).value_or(NAN);
    } else {
      (std::string(c.name) == "events.csv" ? f.events_hash : f.snapshots_hash) = h;
    }
  }
  // parameters.csv whole as it is now, with the fallbacks its run appended at close (a later run
  // rewrites the file, so its start still tells the runs apart); none when it is not there (a
  // version 12 resume needed none)
  f.parameters_bytes = 0, f.parameters_hash = kFnv1a64Empty;
  if (dir_->size("parameters.csv") >= 0) {
    const ReadOutput p(path("parameters.csv"));
    f.parameters_bytes = p.size();
    f.parameters_hash = p.hash(p.size());
  }
  return f;
}

std::string Outputs::later_results(const State& s) const {
  if (!dir_) return {};
  std::ifstream in(path("timeseries.csv"), std::ios::binary);
  if (!in || !in.seekg(s.csv_bytes)) return {};
  long rows = 0;
  std::string line, last;
  while (std::getline(in, line))
    if (!line.empty()) ++rows, last = line;
  if (rows == 0) return {};
  const std::string t = last.substr(0, last.find(','));
  return std::to_string(rows) + (rows == 1 ? " row" : " rows") + " of " + path("timeseries.csv") +
         " after it, to t = " + t + " s";
}

void Outputs::set_state(const State& s) {
  last_ = s.fingerprinted ? s : with_fingerprints(s);  // (before the files are cut: their hashes go on from it)
  if (dir_) {
    for (const Cut& c : cuts(s)) dir_->truncate(c.name, c.bytes);
    // parameters.csv back to the rows its run wrote at its start: the end rows a run that closed
    // appended (warning.*, check.*, end.*) are the continuation's to write, once (a resume into
    // the stopped run's folder left end.status interrupted and, after it, ok). Its room for them
    // taken again. (A version 12 checkpoint knows no start: its file is kept whole.)
    if (last_.parameters_bytes > 0 && dir_->size("parameters.csv") > last_.parameters_bytes)
      dir_->truncate("parameters.csv", last_.parameters_bytes, kParametersTail);
    if (csv_) open_rows(true);  // written on at their new ends (a file opened to be emptied writes at its own offset)
  }
  rows_ = s.rows;
  if (samples_.size() > static_cast<size_t>(s.rows)) samples_.resize(static_cast<size_t>(s.rows));
  frames_before_ = s.frames - (sink_ ? sink_->frames_written() : 0);
}

}  // namespace beltsim
