// The fuzz target over checkpoint reading (issue 31, "Extend the fuzz harness to checkpoints"): the
// fuzzer's bytes are a checkpoint, resumed by Simulation::resume as beltsim.resume would. "@OUT@"
// in them stands for this process's output folder (the seeds, tests/fuzz/checkpoints/, are saved
// checkpoints with their folder written so), and the last line is made the checksum of the rest,
// so that mutations reach the reader's own checks rather than stopping at the checksum (and the
// fingerprints of a version 13 checkpoint's outputs those of the files written here). Every
// outcome but a refusal (std::runtime_error, or the vet's std::invalid_argument) or a resumed run
// is a finding: a crash, a sanitizer report, another exception, a hang or an allocation past
// libFuzzer's -rss_limit_mb.
//
// Built as beltsim_fuzz_checkpoint with BELTSIM_FUZZ (scripts/setup.sh test fuzzes with it), and
// as beltsim_fuzz_checkpoint_replay (the normal build) which runs the seeds through it as a ctest
// test with --each-accepted: every seed must resume and run (BeltsimFuzzRefusal says why not).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>

#include "io/checkpoint_text.hpp"
#include "io/csv_writer.hpp"
#include "sim/outputs.hpp"
#include "sim/simulation.hpp"

namespace {

namespace fs = std::filesystem;

struct Folder {
  fs::path dir, input, out;
  Folder() {
    dir = fs::temp_directory_path() / ("beltsim_fuzz_checkpoint_" + std::to_string(getpid()));
    fs::create_directories(dir);
    input = dir / "input.ckpt";
    out = dir / "out";
  }
  ~Folder() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
};

std::string g_refusal;  // why the last input was refused, "" when it resumed and ran

std::string sealed(std::string text) {
  if (text.size() >= 2 && text.back() == '\n') {
    const size_t last = text.rfind('\n', text.size() - 2);
    if (last != std::string::npos && text.compare(last + 1, 17, "checksum fnv1a64 ") == 0) text.erase(last + 1);
  }
  char sum[17];
  std::snprintf(sum, sizeof sum, "%016llx", static_cast<unsigned long long>(beltsim::fnv1a64(text)));
  return text + "checksum fnv1a64 " + sum + "\n";
}

// the value of the text's line `key` replaced (when it has one)
void set_value(std::string& text, const std::string& key, const std::string& value) {
  const size_t at = text.find("\n" + key + " ");
  if (at == std::string::npos) return;
  const size_t from = at + key.size() + 2, end = text.find('\n', from);
  text.replace(from, (end == std::string::npos ? text.size() : end) - from, value);
}

// A version 13 checkpoint's fingerprints of its outputs made those of the files written here
// (sim/state_io.cpp: csv_last_t, each file's FNV-1a 64 up to its size, parameters.csv's size 0:
// none written), as csv_bytes is made to fit them; a size past a file is left, and refused
void fit_fingerprints(std::string& text, const std::string& series, const std::string& rows) {
  const struct {
    const char *bytes, *hash;
    const std::string& content;
  } files[] = {{"csv_bytes", "csv_fnv1a64", series},
               {"events_bytes", "events_fnv1a64", rows},
               {"snapshots_bytes", "snapshots_fnv1a64", rows}};
  for (const auto& f : files) {
    const size_t at = text.find(std::string("\n") + f.bytes + " ");
    if (at == std::string::npos) continue;
    const long n = std::atol(text.c_str() + at + std::strlen(f.bytes) + 2);
    if (n < 0 || static_cast<size_t>(n) > f.content.size()) continue;
    char hex[17];
    std::snprintf(hex, sizeof hex, "%016llx",
                  static_cast<unsigned long long>(beltsim::fnv1a64(std::string_view(f.content).substr(0, n))));
    set_value(text, f.hash, hex);
  }
  // the last row's time: "0" (the rows below are zeros), unless there is none
  if (text.find("\ncsv_last_t none\n") == std::string::npos) set_value(text, "csv_last_t", "0");
  set_value(text, "parameters_bytes", "0");
}

}  // namespace

extern "C" const char* BeltsimFuzzRefusal() {
  return g_refusal.c_str();
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  static const Folder f;
  g_refusal.clear();
  std::string text(reinterpret_cast<const char*>(data), size);
  for (size_t at; (at = text.find("@OUT@")) != std::string::npos;) text.replace(at, 5, f.out.string());
  {
    std::ofstream in(f.input, std::ios::binary | std::ios::trunc);
    in << sealed(text);
  }
  // the outputs a resume continues: a header and a row each, for the positions to fall on.
  // timeseries.csv needs the header the checkpoint's run writes (resume checks it): its csv_bytes
  // is taken as counted from that header's end (the seeds' 4: "0\n" twice), the line rewritten
  // and the rows made to end there (a mutant's huge count is left as it is, and refused)
  fs::create_directories(f.out);
  const std::string small = "t\n0\n";
  for (const char* name : {"events.csv", "snapshots.csv"}) std::ofstream(f.out / name) << small;
  std::string series = "t\n0\n";
  try {
    const auto seen = beltsim::Simulation::open_checkpoint(f.input.string());
    const std::string header =
        beltsim::csv_header(beltsim::timeseries_columns(seen->scene(), seen->settings().probes.size())) + '\n';
    series = header + "0\n";
    const size_t at = text.find("\ncsv_bytes ");
    const long rows = at == std::string::npos ? -1 : std::atol(text.c_str() + at + 11);
    if (rows >= 1 && rows < (1L << 20)) {
      series = header + std::string(static_cast<size_t>(rows - 1), '0') + "\n";
      const size_t end = text.find('\n', at + 1);
      text.replace(at + 11, end - (at + 11), std::to_string(header.size() + static_cast<size_t>(rows)));
      std::ofstream in(f.input, std::ios::binary | std::ios::trunc);
      in << sealed(text);
    }
  } catch (const std::exception&) {
    // refused already: resume refuses it the same way below
  }
  std::ofstream(f.out / "timeseries.csv") << series;
  if (const std::string before = text; fit_fingerprints(text, series, small), text != before) {
    std::ofstream in(f.input, std::ios::binary | std::ios::trunc);
    in << sealed(text);
  }
  // outputs elsewhere are refused, as the sandbox refuses a script's
  const auto vet = [&](const beltsim::RunSettings& rs) {
    if (fs::path(rs.out_dir) != f.out) throw std::invalid_argument("outputs outside the fuzz folder");
  };
  try {
    auto sim = beltsim::Simulation::resume(f.input.string(), {}, nullptr, vet);
    try {
      sim->run_to(sim->now() + 1e-4);
    } catch (const beltsim::DivergenceError& e) {
      g_refusal = std::string("resumed, then diverged: ") + e.what();
    }
  } catch (const std::runtime_error& e) {
    g_refusal = e.what();
  } catch (const std::invalid_argument& e) {
    g_refusal = e.what();
  }
  std::error_code ec;
  fs::remove_all(f.out, ec);
  return 0;
}
