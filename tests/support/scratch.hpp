// A test program's scratch folder: <tmp>/<prefix>_<pid>, made on first use and removed when the
// program ends, its tests passed or failed (BELTSIM_KEEP set in the environment keeps it, and its
// path is printed, to look into). A program that crashes or is killed leaves it.
#pragma once

#include <filesystem>
#include <string>

namespace beltsim::test {

// the folder for this process, created if missing; `prefix` names the test program
// (the first call's prefix holds for the whole process)
std::filesystem::path scratch_dir(const std::string& prefix);

}  // namespace beltsim::test
