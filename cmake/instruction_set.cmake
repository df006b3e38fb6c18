# x86-64-v3 (AVX2 and FMA: Intel since Haswell, 2013; every AMD Zen) where the compiler takes it
# and the machine that builds runs it (the program is built where it runs: scripts/setup.sh). On
# this project's 2-core machine, run alone, the serpentine drive at speed took 8-9 % less CPU time
# with it and the paper's 60-element drive 0-5 % (docs/performance.md); AVX-512 (-march=native
# there) took 16 % more. A machine without it builds for the x86-64 baseline, whose results differ
# in the last bits. A program built with it stops with a word on a CPU that lacks it
# (src/app/isa_check.cpp): build the Debian package for older cluster nodes with
# -DBELTSIM_X86_64_V3=OFF.
option(BELTSIM_X86_64_V3 "Build for x86-64-v3 (AVX2, FMA) when the compiler and the building machine have it" ON)
set(BELTSIM_ISA_FLAG "")
if(BELTSIM_X86_64_V3 AND NOT CMAKE_CROSSCOMPILING)
  include(CheckCXXSourceRuns)
  set(CMAKE_REQUIRED_FLAGS -march=x86-64-v3)
  check_cxx_source_runs("int main() { __builtin_cpu_init(); return __builtin_cpu_supports(\"avx2\") && __builtin_cpu_supports(\"fma\") && __builtin_cpu_supports(\"bmi2\") ? 0 : 1; }"
                        BELTSIM_HAVE_X86_64_V3)
  unset(CMAKE_REQUIRED_FLAGS)
  if(BELTSIM_HAVE_X86_64_V3)
    set(BELTSIM_ISA_FLAG -march=x86-64-v3)
    add_compile_options(${BELTSIM_ISA_FLAG})
  endif()
endif()
