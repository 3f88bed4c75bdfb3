#!/usr/bin/env bash
# Sets up, builds and runs everything CI checks (.ci/run calls this):
#  0. that every C++ file is as clang-format writes it (scripts/format.sh --check), and passes the
#     checks of .clang-tidy (scripts/tidy.sh);
#  1. the Release build (warnings are errors under CI) and the whole test suite (ctest);
#  2. the same suite built with clang, AddressSanitizer and UndefinedBehaviorSanitizer;
#  3. the tests that run threads, built with ThreadSanitizer;
#  4. every fuzz target for FUZZ_SECONDS (default 60) on its committed corpus.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh -DSOFTDROP_TEST_HOOKS=ON ${CI:+-DSOFTDROP_WERROR=ON}
bash scripts/format.sh --check
bash scripts/tidy.sh
(cd build && ctest --output-on-failure -j "$(nproc)" --timeout 900)
bash scripts/sanitize.sh
bash scripts/tsan.sh
bash scripts/fuzz.sh "${FUZZ_SECONDS:-60}"
