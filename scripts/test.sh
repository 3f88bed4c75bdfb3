#!/usr/bin/env bash
# Sets up, builds and runs the whole test suite (ctest). Used by CI (.ci/run).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh ${CI:+-DSOFTDROP_WERROR=ON}
cd build
ctest --output-on-failure -j "$(nproc)" --timeout 900
