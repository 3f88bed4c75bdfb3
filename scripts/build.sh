#!/usr/bin/env bash
# Installs the dependencies (Debian 12 packages) and builds softdrop, its tests and benchmarks
# into ./build (Release, ccache when available). Extra arguments go to cmake's configure step.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
export CCACHE_DIR="${CCACHE_DIR:-$PWD/.ccache}"
cmake --preset release "$@"  # CMakePresets.json
cmake --build build -j "$(nproc)"
