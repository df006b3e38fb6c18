// A program built for x86-64-v3 (cmake/instruction_set.cmake, BELTSIM_X86_64_V3) stops with a
// word, instead of "Illegal instruction", on a CPU without AVX2, FMA or BMI2 (a Debian package
// built on a newer machine and installed on older cluster nodes). This file is built for the
// x86-64 baseline, and its constructor runs before every C++ static initialiser of the program
// (priority 101), any of which the compiler may have written with those instructions.
#include <unistd.h>

#include <cstring>

namespace {

__attribute__((constructor(101))) void check_instruction_set() {
  __builtin_cpu_init();
  if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") && __builtin_cpu_supports("bmi2")) return;
  const char* msg =
      "beltsim: this program was built for x86-64-v3 (AVX2, FMA, BMI2), which this CPU lacks; build it on this "
      "machine (bash scripts/setup.sh run), or configure with -DBELTSIM_X86_64_V3=OFF (docs/install.md)\n";
  [[maybe_unused]] const ssize_t n = write(2, msg, std::strlen(msg));
  _exit(2);
}

}  // namespace
