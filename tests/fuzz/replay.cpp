// Runs inputs through the fuzz target without libFuzzer (the normal gcc build, and under ASan in
// scripts/setup.sh test): each file named, or each file in a folder named, in name order. A
// finding crashes or aborts this program, so the ctest test fails. With --each-accepted first
// (the seeds of a harness that may refuse an input: a checkpoint, a sweep), an input the harness
// refused fails it too, naming the input and the refusal: a seed is there to reach past the
// refusals, and one that no longer does would leave the fuzzer checking the refusals alone.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);
// why the harness refused its last input ("" when it took it): every harness says
extern "C" const char* BeltsimFuzzRefusal();

int main(int argc, char** argv) {
  namespace fs = std::filesystem;
  std::vector<fs::path> files;
  const bool each_accepted = argc > 1 && std::string(argv[1]) == "--each-accepted";
  for (int k = each_accepted ? 2 : 1; k < argc; ++k) {
    if (fs::is_directory(argv[k])) {
      for (const auto& e : fs::directory_iterator(argv[k]))
        if (e.is_regular_file()) files.push_back(fs::absolute(e.path()));
    } else {
      files.push_back(fs::absolute(argv[k]));
    }
  }
  std::sort(files.begin(), files.end());
  if (files.empty()) {
    std::fprintf(stderr, "beltsim_fuzz_replay: no input files\n");
    return 2;
  }
  for (const fs::path& p : files) {
    std::ifstream in(p, std::ios::binary);
    if (!in) {
      std::fprintf(stderr, "beltsim_fuzz_replay: cannot read %s\n", p.c_str());
      return 2;
    }
    const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::fprintf(stderr, "replaying %s (%zu bytes)\n", p.c_str(), bytes.size());
    LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size());
    if (each_accepted && *BeltsimFuzzRefusal()) {
      std::fprintf(stderr, "beltsim_fuzz_replay: %s was refused: %s\n", p.c_str(), BeltsimFuzzRefusal());
      return 1;
    }
  }
  std::fprintf(stderr, "beltsim_fuzz_replay: %zu inputs, no finding\n", files.size());
  return 0;
}
