// The files a simulation writes into its output folder, and the observer that writes them: the
// simulation notifies it of each sample, event, snapshot and frame as they fall due.
//   parameters.csv  the scene's and the run's values (at open), the fallbacks taken (at close)
//   timeseries.csv  a row per sample (columns: timeseries_columns)
//   events.csv      a row per change (t, what, value)
//   snapshots.csv   a row per element per snapshot, when snapshots are asked for
//   frames          PNG files and/or a video, through the renderer's FrameSink
//   states/         with keep_states, a checkpoint at each frame time (state_NNNNN.ckpt)
// Every row reaches its file whole when written (io/row_file.hpp). The folder is held by this
// simulation alone from open() to close() (io/output_dir.hpp).
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "integrate/warnings.hpp"
#include "io/fnv1a64.hpp"
#include "model/drive.hpp"
#include "model/observables.hpp"
#include "sim/run_settings.hpp"

namespace beltsim {

// the room parameters.csv keeps for the rows appended at close (WholeFile::reserve): the fallbacks'
// rows take 1.4 KB, a checked run's check.* rows 1.5 KB and the end rows' note up to a message
inline constexpr long kParametersTail = 16 * 1024;

class CsvWriter;
class OutputDir;
class RowFile;
struct Scene;

// the column names of timeseries.csv for a scene with that many probes (documented in docs/outputs.md)
std::vector<std::string> timeseries_columns(const Scene& scene, size_t probes = 1);
// route span k's name in the columns: span_<a>_<b>, the pulleys it runs from and to
std::string span_name(const Scene& sc, size_t k);
// the default name of a picture of `kind` ("show", "plot": sim:show's, sim:plot's) drawn at t:
// KIND_<t>.png (t to 6 decimals), the k-th at one time (k >= 2) KIND_<t>_k.png
std::string picture_name(const std::string& kind, double t, int k = 1);
// whether a file's name is one of those
bool is_picture_name(const std::string& name);

class Outputs {
 public:
  // scene and settings are the simulation's own (frames paths resolved), read as they are when
  // open() is called; nothing is written before then
  Outputs(const Scene& scene, const RunSettings& settings);
  ~Outputs();
  Outputs(const Outputs&) = delete;
  Outputs& operator=(const Outputs&) = delete;

  // the output folder, made when missing (unless !make: then refused) and claimed (a second
  // simulation on it is refused before it writes anything; never through a link); a resumed run
  // cuts its files through it
  const OutputDir& claim(bool make = true);
  // the renderer first (it opens the video and the PNG folder, so a bad frames path stops the run
  // before any CSV is written), then parameters.csv (unless append), timeseries.csv, events.csv
  // and snapshots.csv; append continues the files of a resumed run
  void open(bool append);
  // the outputs an earlier run left in the claimed folder that this one does not write:
  // snapshots.csv, every video (NAME.mp4, whatever its name, but this run's own), the pictures of
  // sim:show and sim:plot by their default names (is_picture_name; past four, three and "N more
  // pictures"), every PNG folder (frames/, and any other holding frame_NNNNN.png, but this run's
  // own) and states/, then the checkpoints in it and in its subfolders (NAME.ckpt, SUB/NAME.ckpt;
  // not in a subfolder that is a run's output folder itself), which cannot be resumed once this
  // run has written the folder
  // (a folder holds one run's outputs; the simulation warns of them as it starts)
  std::vector<std::string> earlier_outputs() const;
  // finishes the video, appends the fallbacks (warning.<name>.count, .first_t) and `rows` (whole
  // rows: a checked run's check.*) to parameters.csv and releases the folder; each output closed
  // whatever happened to the one before, the first failure thrown at the end
  void close(const Warnings& warnings, const std::string& rows = "");

  // ---- notifications (each a whole row or rows, in the file when it returns) ----------------
  void sample(std::vector<double> row);
  void event(double t, const std::string& what, const std::string& text);
  // one row per element: t, element, s (where it started along the belt), x, y, tension, normal,
  // friction, slip, mu, pulley (name, empty when free), state (free, stick, slip)
  void snapshot(double t, const Observation& obs);
  void frame(double t, const Eigen::VectorXd& y, const Drive& drive, const Observation& obs);
  // states/NAME, written whole (keep_states)
  void keep_state(const std::string& name, const std::string& checkpoint);

  bool has_frames() const { return sink_ != nullptr; }
  bool has_snapshots() const;
  std::string path(const char* name) const;  // OUT_DIR/NAME
  long bytes(const char* name) const;        // the size of NAME in the claimed folder, 0 when none
  // the bytes the outputs hold in the claimed folder (timeseries.csv, snapshots.csv, the states
  // this simulation kept), and those free on its file system for this process (-1: unknown)
  double written_bytes() const;
  double free_bytes() const;
  long rows() const { return rows_; }        // samples written
  double last_row_t() const { return last_.csv_last_t; }  // the time of timeseries.csv's last row (NaN: none)
  long frames_written() const;
  const std::vector<std::vector<double>>& samples() const { return samples_; }  // keep_samples

  // Where the outputs stand (a run's state, sim/sim_state.hpp): the counts so far and the sizes of
  // the files (as measured in the claimed folder; before it is claimed and after close, the last
  // set or measured).
  struct State {
    long rows = 0;                                              // samples written
    long frames = 0;                                            // frames drawn
    long csv_bytes = 0, events_bytes = 0, snapshots_bytes = 0;  // 0 for a file that is not there
    // what the files held, to know them again (a folder another run has written since is not
    // this run's, whatever its sizes): the time of timeseries.csv's last row (NaN: no row yet),
    // parameters.csv's size as the run wrote it at its start (its fallbacks are appended at
    // close), and FNV-1a 64 of each file's bytes up to its size (io/fnv1a64.hpp)
    double csv_last_t = std::numeric_limits<double>::quiet_NaN();
    long parameters_bytes = 0;
    std::uint64_t csv_hash = kFnv1a64Empty, events_hash = kFnv1a64Empty, snapshots_hash = kFnv1a64Empty,
                  parameters_hash = kFnv1a64Empty;
    // false for a state read from a version 12 checkpoint, which holds none of these
    // (with_fingerprints takes them from the files)
    bool fingerprinted = true;
  };
  State get_state() const;
  // std::runtime_error naming the file when the claimed folder's files cannot be cut back to the
  // state's sizes (shorter, not a regular file, a size inside the header or not at a row's end),
  // when they are not the files the state's run wrote (another run has written the folder since:
  // parameters.csv's start, the last row's time or the bytes up to each size differ), or when
  // frames drawn since would have to be taken back from a video; nothing is touched
  void check_state(const State& s) const;
  // the same checks of the files a state's run wrote into another folder `from` (a branch's
  // source, which is read, never claimed nor written: its run may still be going on in it)
  void check_files(const State& s, const std::string& from) const;
  // a branch (beltsim.resume's out): the folder claimed (made when missing) to hold the state's
  // outputs up to it, copied from `from` (check_files first) up to the state's sizes, and a parameters.csv of its
  // own (run.out names this folder); the state returned names that parameters.csv. open(true) then
  // continues them
  State branch(const State& s, const std::string& from);
  // a state without fingerprints (fingerprinted false) with those of the claimed folder's files
  // as they are up to its sizes (check_state first), so that a later save holds them
  State with_fingerprints(const State& s) const;
  // what cutting the claimed folder's files back to the state would drop ("61 rows of
  // timeseries.csv after it, to t = 0.1 s"); empty when they end where the state left them
  std::string later_results(const State& s) const;
  // the counts set, the claimed folder's files cut to the state's sizes (check_state first)
  void set_state(const State& s);

 private:
  const Scene& scene_;
  const RunSettings& rs_;
  std::unique_ptr<OutputDir> dir_;  // out_dir, locked from claim() to close()
  std::unique_ptr<FrameSink> sink_;
  std::unique_ptr<OutputDir> states_;  // OUT_DIR/states, with keep_states
  std::unique_ptr<CsvWriter> csv_;
  std::unique_ptr<RowFile> events_;
  std::unique_ptr<RowFile> snapshots_;
  std::vector<std::vector<double>> samples_;
  long rows_ = 0;
  long frames_before_ = 0;  // frames written before a resume
  double kept_bytes_ = 0;   // the bytes of the states kept by this simulation
  State last_;              // the sizes set or measured last (get_state without the folder)
  struct Cut {
    const char* name;
    long bytes;
    std::uint64_t hash;
  };
  std::vector<Cut> cuts(const State& s) const;
  void open_rows(bool append);  // timeseries.csv, events.csv, snapshots.csv
  void start_parameters();      // parameters.csv as the run writes it at its start (last_ its size and hash)
};

}  // namespace beltsim
