#!/usr/bin/env bash
# One-command set-up for a Debian 12 machine (run as root, or with sudo available):
#   bash scripts/setup.sh run    install what is missing, build, run the paper's dry scenario
#   bash scripts/setup.sh test   install what is missing, build, run the test suite, then the quick
#                                tests again built with ASan + UBSan in build-asan/, then 60 s of
#                                fuzzing with clang's libFuzzer in build-fuzz/
#   bash scripts/setup.sh build  install what is missing and build only
# Idempotent: packages already present are not touched, and apt is not consulted at all when
# nothing is missing; the build is incremental (ccache when available).
set -euo pipefail

mode=${1:-build}
here=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
cd "$here"
build_dir=${BELTSIM_BUILD_DIR:-build}

case "$mode" in
  run|test|build) ;;
  *) echo "usage: bash scripts/setup.sh run|test|build" >&2; exit 2 ;;
esac

# --- packages -------------------------------------------------------------------------------
mapfile -t wanted < <(sed -e 's/#.*//' -e 's/[[:space:]]//g' scripts/debian-packages.txt | grep -v '^$')
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
cmake -S . -B "$build_dir" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build_dir" -j "$jobs"

# --- run ------------------------------------------------------------------------------------
case "$mode" in
  run)
    "$build_dir/beltsim" run scripts/paper_dry.lua
    ;;
  test)
    ctest --test-dir "$build_dir" --output-on-failure -j "$jobs"
    # the quick tests again under AddressSanitizer + UndefinedBehaviorSanitizer (a second build
    # of only what they run); BELTSIM_SANITIZE=0 skips this. The first finding stops the test.
    if [ "${BELTSIM_SANITIZE:-1}" != 0 ]; then
      asan_dir=${BELTSIM_ASAN_BUILD_DIR:-build-asan}
      export ASAN_OPTIONS=halt_on_error=1:print_stacktrace=1
      export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
      export LSAN_OPTIONS=suppressions=$here/tests/lsan.supp:print_suppressions=0
      cmake -S . -B "$asan_dir" -DCMAKE_BUILD_TYPE=Release -DBELTSIM_SANITIZE=ON >/dev/null
      cmake --build "$asan_dir" -j "$jobs" --target beltsim beltsim_tests_quick beltsim_tests_script \
        beltsim_tests_render beltsim_tests_plot beltsim_fuzz_replay
      ctest --test-dir "$asan_dir" -L quick --output-on-failure -j "$jobs"
    fi
    # fuzzing: the scene API fed random scripts (tests/fuzz/fuzz_script.cpp) by libFuzzer, built
    # with clang-14 and ASan + UBSan in build-fuzz/, seeded with scripts/*.lua and the kept
    # findings; BELTSIM_FUZZ_SECONDS (default 60; 0 skips). A crash, sanitizer report, uncaught
    # exception or hang (-timeout) fails the run: its input is printed and kept in
    # build-fuzz/findings/ (fix it, then add it to tests/fuzz/regressions/).
    fuzz_seconds=${BELTSIM_FUZZ_SECONDS:-60}
    if [ "$fuzz_seconds" != 0 ]; then
      fuzz_dir=${BELTSIM_FUZZ_BUILD_DIR:-build-fuzz}
      CXX=clang++-14 cmake -S . -B "$fuzz_dir" -DCMAKE_BUILD_TYPE=Release -DBELTSIM_FUZZ=ON >/dev/null
      cmake --build "$fuzz_dir" -j "$jobs" --target beltsim_fuzz
      mkdir -p "$fuzz_dir/corpus" "$fuzz_dir/seeds" "$fuzz_dir/findings"
      rm -f "$fuzz_dir"/findings/*
      cp scripts/*.lua tests/fuzz/regressions/* "$fuzz_dir/seeds/" 2>/dev/null || true
      export ASAN_OPTIONS=halt_on_error=1:print_stacktrace=1
      export UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1
      export LSAN_OPTIONS=suppressions=$here/tests/lsan.supp:print_suppressions=0
      # -close_fd_mask=1: the scripts' print() output is not wanted; the reports go to stderr
      if ! "$fuzz_dir/tests/beltsim_fuzz" -max_total_time="$fuzz_seconds" -timeout=30 -rss_limit_mb=4096 \
          -dict=tests/fuzz/lua.dict -close_fd_mask=1 -artifact_prefix="$fuzz_dir/findings/" \
          "$fuzz_dir/corpus" "$fuzz_dir/seeds" 2>"$fuzz_dir/fuzz.log"; then
        tail -n 60 "$fuzz_dir/fuzz.log" >&2
        for f in "$fuzz_dir"/findings/*; do
          [ -f "$f" ] || continue
          echo "setup: the fuzzer's finding $f (bytes as text, cat -v):" >&2
          cat -v "$f" >&2
          echo >&2
        done
        echo "setup: the fuzzer found a crash, a sanitizer report or a hang (the log: $fuzz_dir/fuzz.log)" >&2
        exit 1
      fi
      grep -E '^Done|^#[0-9]+.*DONE' "$fuzz_dir/fuzz.log" | tail -n 1
    fi
    ;;
esac
