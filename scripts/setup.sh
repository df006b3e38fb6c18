#!/usr/bin/env bash
# One-command set-up for a Debian 12 machine (run as root, or with sudo available):
#   bash scripts/setup.sh run    install what the program needs (scripts/debian-packages.txt),
#                                build the program alone, run the paper's dry scenario
#   bash scripts/setup.sh test   install that and what the tests add (debian-packages-test.txt),
#                                run every test once but clean_machine's (below): the quick tests
#                                in one clang-14 build with ASan + UBSan and libFuzzer's
#                                instrumentation in build-san/, and beside them 60 s of fuzzing
#                                (three targets in turn), then all but the quick tests in build/
#                                (built without the quick tests' programs and the benchmarks)
#   bash scripts/setup.sh build  install both lists and build everything, running nothing
#   bash scripts/setup.sh clean-machine-test
#                                install both lists, build the program, make its Debian package
#                                and install it with apt in a minimal Debian made by debootstrap,
#                                running an example there (ctest -L clean_machine; root, the
#                                network, 3.5-6 min: not part of test)
# Idempotent: packages already present are not touched, and apt is not consulted at all when
# nothing is missing; the build is incremental (ccache when available).
set -euo pipefail

mode=${1:-build}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$here"
build_dir=${BELTSIM_BUILD_DIR:-build}

case "$mode" in
  run|test|build|clean-machine-test) ;;
  *) echo "usage: bash scripts/setup.sh run|test|build|clean-machine-test" >&2; exit 2 ;;
esac

# --- packages -------------------------------------------------------------------------------
lists=(scripts/debian-packages.txt)
if [ "$mode" != run ]; then lists+=(scripts/debian-packages-test.txt); fi
mapfile -t wanted < <(sed -e 's/#.*//' -e 's/[[:space:]]//g' "${lists[@]}" | grep -v '^$')
missing=()
for p in "${wanted[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed'; then
    missing+=("$p")
  fi
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  sudo=""
  if [ "$(id -u)" -ne 0 ]; then sudo="sudo"; fi
  export DEBIAN_FRONTEND=noninteractive
  $sudo apt-get update -q
  $sudo apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# --- build ----------------------------------------------------------------------------------
jobs=$(nproc 2>/dev/null || echo 2)
# each stage's wall time, printed when it ends
stage_start=$SECONDS
stage_done() { echo "setup: $1 in $((SECONDS - stage_start)) s"; stage_start=$SECONDS; }
# Ninja for a new build folder; a folder configured before keeps its generator (CMake refuses to
# change it)
generator() { [ -f "$1/CMakeCache.txt" ] || echo "-GNinja"; }
if [ "$mode" = run ]; then
  # the program alone: no tests, no benchmarks
  cmake $(generator "$build_dir") -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DBELTSIM_BUILD_TESTS=OFF -DBELTSIM_BUILD_BENCH=OFF >/dev/null
  cmake --build "$build_dir" -j "$jobs" --target beltsim
else
  cmake $(generator "$build_dir") -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release -DBELTSIM_BUILD_TESTS=ON -DBELTSIM_BUILD_BENCH=ON >/dev/null
  if [ "$mode" = clean-machine-test ]; then
    # the package holds the program alone
    cmake --build "$build_dir" -j "$jobs" --target beltsim
  elif [ "$mode" = test ] && [ "${BELTSIM_SANITIZE:-1}" != 0 ]; then
    # every test runs once: the quick ones under the sanitizers below, so here everything but
    # their programs (tests/CMakeLists.txt, BELTSIM_QUICK_PROGRAMS), the benchmarks included
    # (bench_runs starts them)
    cmake --build "$build_dir" -j "$jobs" --target beltsim_all_but_quick
  else
    cmake --build "$build_dir" -j "$jobs"
  fi
fi
stage_done "built $build_dir/"

# --- run ------------------------------------------------------------------------------------
case "$mode" in
  run)
    "$build_dir/beltsim" run scripts/paper_dry.lua
    ;;
  clean-machine-test)
    # -V: its stages and their times as they end (the output of apt and of the runs is shown on a
    # failure only)
    ctest --test-dir "$build_dir" -L clean_machine -V
    stage_done "the package installed and run on a clean machine"
    ;;
  test)
    # the quick tests and the fuzzer, in one build with clang-14, AddressSanitizer +
    # UndefinedBehaviorSanitizer and libFuzzer's coverage instrumentation (build-san/: only what
    # they run). The first finding stops a test. BELTSIM_SANITIZE=0 skips the quick tests there,
    # BELTSIM_FUZZ_SECONDS=0 the fuzzing, both together the build.
    fuzz_seconds=${BELTSIM_FUZZ_SECONDS:-60}
    if [ "${BELTSIM_SANITIZE:-1}" != 0 ] || [ "$fuzz_seconds" != 0 ]; then
      san_dir=${BELTSIM_SAN_BUILD_DIR:-build-san}
      # intercept_tls_get_addr=0: clang-14's LeakSanitizer reads glibc 2.36's dynamic TLS vector
      # wrongly (a bogus "DTLS" range once Mesa's and LLVM's libraries are loaded) and its tracer
      # crashes at exit ("Tracer caught signal 11"), depending on the heap's layout; without the
      # interception it scans the threads' stacks and static TLS only
      export ASAN_OPTIONS=halt_on_error=1:print_stacktrace=1:intercept_tls_get_addr=0
      export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
      export LSAN_OPTIONS=suppressions=$here/tests/lsan.supp:print_suppressions=0
      CXX=clang++-14 cmake $(generator "$san_dir") -S . -B "$san_dir" -DCMAKE_BUILD_TYPE=Release -DBELTSIM_FUZZ=ON \
        -DBELTSIM_BUILD_TESTS=ON -DBELTSIM_BUILD_BENCH=OFF >/dev/null
      targets=(beltsim_fuzz beltsim_fuzz_checkpoint beltsim_fuzz_sweep)
      if [ "${BELTSIM_SANITIZE:-1}" != 0 ]; then
        targets+=(beltsim_quick_programs)
      fi
      cmake --build "$san_dir" -j "$jobs" --target "${targets[@]}"
      stage_done "built $san_dir/"
    fi
    # what runs beside the sanitizer tests (the fuzzing, then build/'s tests) does not outlive
    # this script (a failed test, Ctrl-C); build/'s tests run in a session of their own, ended with
    # them
    fuzz_pid="" lane_pids=()
    beside_end() {
      [ -z "$fuzz_pid" ] || kill "$fuzz_pid" 2>/dev/null
      for p in "${lane_pids[@]}"; do kill -- -"$p" 2>/dev/null || true; done
      true
    }
    trap beside_end EXIT
    if [ "${BELTSIM_SANITIZE:-1}" = 0 ]; then
      # every test in build/ (but clean_machine's), on both cores, before the fuzzing
      ctest --test-dir "$build_dir" -LE clean_machine --output-on-failure -j "$jobs"
      stage_done "tests in $build_dir/ passed"
    fi
    # fuzzing, for BELTSIM_FUZZ_SECONDS in all (default 60; 0 skips), three targets in turn on one
    # core beside the sanitizer tests, which cannot keep both cores busy to the end: the scene API
    # fed random scripts (tests/fuzz/fuzz_script.cpp, half the time, seeded with scripts/*.lua and
    # the kept findings), checkpoints resumed (fuzz_checkpoint.cpp, a quarter, seeded with saved
    # ones) and a sweep's values through its files (fuzz_sweep.cpp, the rest). A crash, sanitizer
    # report, uncaught exception or hang (-timeout) fails the run: its input is printed and kept in
    # build-san/fuzz/<target>/findings/ (fix it, then add it to the target's seeds).
    if [ "$fuzz_seconds" != 0 ]; then
      script_s=$((fuzz_seconds / 2)); checkpoint_s=$((fuzz_seconds / 4))
      ((script_s > 0)) || script_s=1; ((checkpoint_s > 0)) || checkpoint_s=1
      sweep_s=$((fuzz_seconds - script_s - checkpoint_s)); ((sweep_s > 0)) || sweep_s=1
      # fuzz NAME SECONDS BINARY SEEDS...: one target, its corpus, seeds, findings and log in
      # build-san/fuzz/NAME/ (-close_fd_mask=1: the scripts' print() output is not wanted; the
      # reports go to stderr)
      fuzz() {
        local name=$1 seconds=$2 binary=$3 dir=$san_dir/fuzz/$1
        shift 3
        mkdir -p "$dir/corpus" "$dir/seeds" "$dir/findings"
        rm -f "$dir"/findings/*
        cp "$@" "$dir/seeds/" 2>/dev/null || true
        local dict=()
        if [ "$name" = script ]; then dict=(-dict=tests/fuzz/lua.dict); fi
        "$san_dir/tests/$binary" -max_total_time="$seconds" -timeout=30 -rss_limit_mb=4096 "${dict[@]}" \
            -close_fd_mask=1 -artifact_prefix="$dir/findings/" "$dir/corpus" "$dir/seeds" 2>"$dir/fuzz.log" &
        fuzzer=$!
        wait "$fuzzer"  # (a TERM to the subshell below ends it at once, and its trap ends the fuzzer)
      }
      (fuzzer=""
       trap 'kill "$fuzzer" 2>/dev/null; exit 1' TERM
       fuzz script "$script_s" beltsim_fuzz scripts/*.lua tests/fuzz/regressions/* &&
         fuzz checkpoint "$checkpoint_s" beltsim_fuzz_checkpoint tests/fuzz/checkpoints/* &&
         fuzz sweep "$sweep_s" beltsim_fuzz_sweep tests/fuzz/sweeps/*) &
      fuzz_pid=$!
    fi
    # build/'s tests, beside the sanitizer tests, one at a time in two lanes, each starting when a
    # core comes free: the physics, golden, browser and install tests once the fuzzing is done (at
    # once without it), the app tests (the program's workflows through Python, tens of seconds
    # each) once the sanitizer tests are; and the Slurm test, which mostly waits, at once. Their
    # output goes to build/ctest.log, build/ctest-slurm.log and build/ctest-app.log, shown when
    # they end. (A poll for the fuzzing's end: this shell reaps its job as it ends.)
    lane_logs=()
    if [ "${BELTSIM_SANITIZE:-1}" != 0 ]; then
      # (the Slurm test waits on its daemons and its jobs for most of its 13 s: 1.5 s of CPU)
      setsid ctest --test-dir "$build_dir" -L slurm --output-on-failure -j 1 >"$build_dir/ctest-slurm.log" 2>&1 &
      lane_pids+=($!) lane_logs+=("$build_dir/ctest-slurm.log")
      setsid bash -c 'while kill -0 "$1" 2>/dev/null; do sleep 1; done
                      exec ctest --test-dir "$2" -LE "quick|app|slurm|clean_machine" --output-on-failure -j 1' _ "$fuzz_pid" "$build_dir" \
        >"$build_dir/ctest.log" 2>&1 &
      lane_pids+=($!) lane_logs+=("$build_dir/ctest.log")
    fi
    tests_ok=1
    if [ "${BELTSIM_SANITIZE:-1}" != 0 ]; then
      if ctest --test-dir "$san_dir" -L quick --output-on-failure -j "$jobs"; then
        stage_done "tests in $san_dir/ passed"
      else
        tests_ok=0
      fi
      setsid ctest --test-dir "$build_dir" -L app --output-on-failure -j 1 >"$build_dir/ctest-app.log" 2>&1 &
      lane_pids+=($!) lane_logs+=("$build_dir/ctest-app.log")
    fi
    release_ok=1
    for i in "${!lane_pids[@]}"; do
      wait "${lane_pids[$i]}" || release_ok=0
      echo "setup: tests in $build_dir/ (${lane_logs[$i]}):"
      cat "${lane_logs[$i]}"
    done
    lanes=${#lane_pids[@]} lane_pids=()  # (ended: nothing for beside_end to stop)
    if ((lanes)); then
      if ((release_ok)); then
        stage_done "tests in $build_dir/ passed; waited for them"
      else
        echo "setup: tests failed in $build_dir/ (above)" >&2
        exit 1
      fi
    fi
    if [ -n "$fuzz_pid" ]; then
      if ! wait "$fuzz_pid"; then
        for name in script checkpoint sweep; do
          found=0
          for f in "$san_dir/fuzz/$name"/findings/*; do
            [ -f "$f" ] || continue
            found=1
            echo "setup: the $name fuzzer's finding $f (bytes as text, cat -v):" >&2
            cat -v "$f" >&2
            echo >&2
          done
          if ((found)) || ! grep -qE '^Done|DONE' "$san_dir/fuzz/$name/fuzz.log" 2>/dev/null; then
            [ -f "$san_dir/fuzz/$name/fuzz.log" ] && tail -n 60 "$san_dir/fuzz/$name/fuzz.log" >&2
            echo "setup: the $name fuzzer found a crash, a sanitizer report or a hang (the log:" \
                 "$san_dir/fuzz/$name/fuzz.log)" >&2
            break
          fi
        done
        exit 1
      fi
      fuzz_pid=""
      for name in script checkpoint sweep; do
        echo "$name: $(grep -E '^Done|^#[0-9]+.*DONE' "$san_dir/fuzz/$name/fuzz.log" | tail -n 1)"
      done
      stage_done "fuzzing (${script_s} + ${checkpoint_s} + ${sweep_s} s from the tests' start) found nothing; waited for it"
    fi
    if [ "$tests_ok" = 0 ]; then
      echo "setup: tests failed in $san_dir/ (above)" >&2
      exit 1
    fi
    ;;
esac
