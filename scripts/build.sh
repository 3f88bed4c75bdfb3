#!/usr/bin/env bash
# Installs the dependencies (Debian 12 packages) and builds softdrop, its tests and benchmarks
# into ./build (Release, ccache when available). Extra arguments go to cmake's configure step.
# SOFTDROP_TARGETS="softdrop ..." builds only those targets (scripts/run.sh builds the program alone).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export CCACHE_DIR="${CCACHE_DIR:-$PWD/.ccache}"
cmake --preset release "$@"  # CMakePresets.json
# shellcheck disable=SC2086  # the targets' names, split at spaces
cmake --build build -j "$(nproc)" ${SOFTDROP_TARGETS:+--target $SOFTDROP_TARGETS}
