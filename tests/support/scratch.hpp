// A test program's scratch folder: <tmp>/<prefix>_<pid>, made on first use and removed when the
// program ends with every test passed (kept after a failure, and its path printed, to look into).
#pragma once

#include <filesystem>
#include <string>

namespace beltsim::test {

// the folder for this process, created if missing; `prefix` names the test program
// (the first call's prefix holds for the whole process)
std::filesystem::path scratch_dir(const std::string& prefix);

}  // namespace beltsim::test
