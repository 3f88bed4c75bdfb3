#!/usr/bin/env bash
# Builds the test suite and the fuzz targets a second time with clang, AddressSanitizer and
# UndefinedBehaviorSanitizer into ./build-asan, and runs the tests there. Any sanitizer report
# aborts the test that caused it, so it fails the run. Extra arguments go to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export CCACHE_DIR="${CCACHE_DIR:-$PWD/.ccache}"
cmake --preset asan  # CMakePresets.json
cmake --build build-asan -j "$(nproc)"
source scripts/sanitizer_env.sh
cd build-asan
ctest --output-on-failure -j "$(nproc)" --timeout 1800 "$@"
