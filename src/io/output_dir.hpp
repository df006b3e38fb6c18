// Every file beltsim creates is opened here, so that it never follows a symbolic link and never
// lands outside the folder it was meant for (a scenario package that ships `events.csv ->
// ~/.bashrc` must not get the user's file rewritten):
// - a folder is opened once (O_DIRECTORY | O_NOFOLLOW) and every file in it by openat() on that
//   descriptor with O_NOFOLLOW | O_CLOEXEC, one path component at a time (io/beneath.hpp, the
//   routine a script's own files are opened with too), so a link planted in the folder, or
//   swapped in while the run goes on, is refused rather than followed;
// - a file written in place must be a regular file with no other hard link (a FIFO, a device or a
//   second name of some other file is refused before anything is truncated);
// - a file written whole (parameters.csv, a checkpoint, session.lua, a PNG) is written unnamed
//   in the folder (O_TMPFILE, else NAME.part) and renamed over NAME when complete.
// The paths a user or a script names are checked by the sandbox (script/sandbox.hpp) before;
// this is what makes the files beltsim itself names inside them safe.
//
// Every output that cannot be written throws std::runtime_error "cannot write PATH: reason" and
// is recorded (output_failures()): a failure that surfaces where nobody can throw (a destructor,
// the end of the interpreter) still makes the program's exit status non-zero (app/main.cpp).
#pragma once

#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace beltsim {

// an output that could not be written: "cannot write PATH: REASON" (output_error)
struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// throws OutputError "cannot write PATH: REASON" after recording it
[[noreturn]] void output_error(const std::string& path, const std::string& reason);
// records a failure that is reported another way (its own message)
void note_output_failure(const std::string& message);
// the message of every output that could not be written so far in this process, in order
std::vector<std::string> output_failures();
// those not yet shown to the user (mark_output_failure_shown)
std::vector<std::string> unshown_output_failures();
// the failures with this message (an error's what()) have been shown; others are untouched
void mark_output_failure_shown(const std::string& message);

class OutputDir {
 public:
  // the folder PATH ("" is ".", whose files file() names by their bare names, as a path without a
  // folder gives them), made with its missing parents unless !make; refused when its last
  // component is a symbolic link or not a folder (output_error)
  explicit OutputDir(const std::string& path, bool make = true);
  // the same for the file `shown` (its errors name it)
  OutputDir(const std::string& path, bool make, const std::string* shown);
  // the subfolder NAME of parent (one component), made when missing, never through a link
  OutputDir(const OutputDir& parent, const std::string& name);
  OutputDir(OutputDir&& o) noexcept;
  OutputDir& operator=(OutputDir&& o) noexcept;
  OutputDir(const OutputDir&) = delete;
  OutputDir& operator=(const OutputDir&) = delete;
  ~OutputDir();

  const std::string& path() const { return path_; }
  int fd() const { return fd_; }
  // PATH/NAME, for messages (NAME alone in the folder "")
  std::string file(std::string_view name) const;

  // a descriptor (O_WRONLY | O_CLOEXEC, the caller closes it) writing NAME, created when missing:
  // emptied, or (append) continued at its end. Refused (output_error) when NAME is a link, not a
  // regular file, or has another hard link.
  int open_file(const std::string& name, bool append) const;
  // NAME cut to its first `bytes` bytes (a resumed run); refused as open_file, and when NAME is
  // missing or shorter. `room` more bytes past the cut are taken from the file system, as
  // WholeFile::reserve takes them (none where it cannot)
  void truncate(const std::string& name, long bytes, long room = 0) const;
  // the size of NAME (not through a link), -1 when there is none
  long size(const std::string& name) const;
  // whether NAME exists in the folder (a file, a folder or a link, never followed)
  bool has(const std::string& name) const;
  // NAME removed (a link itself, never its target); no error when there is none
  void remove(const std::string& name) const;

  // claims the folder for one writer: an exclusive lock on DIR/.beltsim.lock (opened as any
  // output; an open file description's lock, fcntl F_OFD_SETLK, which another one of this
  // process is refused too), held until this object is destroyed (or the process ends), which
  // removes the file (a process killed leaves it, holding no lock, for the next claim). Throws
  // std::runtime_error naming the folder when another simulation, of this process or another,
  // holds it.
  void lock();
  // the same claim, the holder said rather than thrown: "" when this object holds the folder
  // now, else who does ("another beltsim (process N)", "another simulation of this beltsim");
  // throws as an output for any other failure
  std::string try_lock();

 private:
  void unlock();  // the lock file removed and the lock released, when this object holds it
  OutputDir() = default;
  int open_own(const std::string& name, int flags, bool empty) const;
  std::string path_;
  bool bare_ = false;  // given as "": the working folder of a path without a folder (file())
  int fd_ = -1;
  int lock_fd_ = -1;
};

// who holds the folder open as `dir` (any descriptor of it, O_PATH too) when another process does:
// "another beltsim (process N)" ("" when nobody does, or this process). Only asked (F_OFD_GETLK),
// never claimed: a scenario script's writes into a folder another beltsim writes are refused with
// it (script/sandbox_files.cpp)
std::string folder_holder(int dir);

// A fresh run's numbered files (frame_00012.png, state_00003.ckpt, a mode's mode_01_26.8Hz.png)
// replace an earlier run's in the same folder: those it would not write over (a longer earlier
// run's last frames, the modes of another time or another count) are removed too, so that the
// folder holds one run's, as it holds one run's timeseries.csv (a golden test compared a frame the
// run no longer drew, left by the run before). Removes the regular files of `dir` (never a link:
// a link is refused when written) whose names `numbered` accepts, and nothing else.
void remove_numbered(const OutputDir& dir, const std::function<bool(const std::string&)>& numbered);
// the names of the regular files (never a link) in the folder `path` that `keep` accepts, sorted
std::vector<std::string> regular_files(const std::string& path, const std::function<bool(const std::string&)>& keep);

// The folder and the name of a path a caller gave: OutputDir(parent), made with its missing
// parents as every output's folder is (docs/outputs.md), and the last component; errors name the
// path. Every writer of a file named by its path goes through here.
struct OutputPlace {
  OutputDir dir;
  std::string name;
};
OutputPlace output_place(const std::string& path);

// A file written whole: its bytes go to an unnamed file in the folder (O_TMPFILE; NAME.part where
// the file system has none), and commit() gives it the name NAME, replacing the old file in one
// rename. Until then (an error, a kill) NAME keeps its old content and no half file is left
// (a NAME.part only where O_TMPFILE is missing and the process is killed).
class WholeFile {
 public:
  // refused (output_error) when NAME is a symbolic link or a folder
  WholeFile(const OutputDir& dir, std::string name);
  ~WholeFile();
  WholeFile(const WholeFile&) = delete;
  WholeFile& operator=(const WholeFile&) = delete;
  int fd() const { return fd_; }
  std::string path() const { return dir_.file(name_); }
  // all of text (output_error on a failed write)
  void write(std::string_view text);
  // room for `bytes` more past what is written, taken from the file system now (fallocate,
  // FALLOC_FL_KEEP_SIZE: the file's size and bytes unchanged), so that rows appended later find it
  // on a disk that has filled meanwhile (parameters.csv's end rows); nothing where the file system
  // cannot
  void reserve(long bytes);
  // closes the file and names it NAME, or `as` (another name in the folder) when given
  // (output_error on failure: then nothing is left)
  void commit(const std::string& as = "");
  // gives up the file: nothing is left of it, NAME keeps its old content
  void discard();

 private:
  const OutputDir& dir_;
  std::string name_;
  int fd_ = -1;
  bool unnamed_ = true;  // O_TMPFILE; else NAME.part exists
  bool done_ = false;
};

// text written whole to DIR/NAME (WholeFile)
void write_file_whole(const OutputDir& dir, const std::string& name, std::string_view text);
// the same for a path (output_place: its missing folders made)
void write_file_whole(const std::string& path, std::string_view text);

// "" when a picture's path names a PNG file (.png, any case), the only kind beltsim draws, else
// why not (a user's x.jpg got PNG bytes under that name)
std::string png_name_problem(const std::string& path);
// the same for a video's path: "" when it names an MP4 file (.mp4, any case), the only kind
// beltsim writes (a user's clip.avi, or --video clip.png, got MP4 bytes under that name)
std::string video_name_problem(const std::string& path);

}  // namespace beltsim
