#!/usr/bin/env bash
# One-command set-up for a Debian 12 machine (run as root, or with sudo available):
#   bash scripts/setup.sh run    install what is missing, build, run the paper's dry scenario
#   bash scripts/setup.sh test   install what is missing, build, run the test suite, then the quick
#                                tests again built with ASan + UBSan in build-asan/
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
        beltsim_tests_render beltsim_tests_plot
      ctest --test-dir "$asan_dir" -L quick --output-on-failure -j "$jobs"
    fi
    ;;
esac
