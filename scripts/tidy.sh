#!/usr/bin/env bash
# Runs the checks of .clang-tidy on the library's, the program's and the Python module's sources,
# with the compile commands of a configured build (default build/, as scripts/build.sh makes it).
#   bash scripts/tidy.sh [BUILD_DIR]    exit 1 on any finding, each named with its file and line
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
command -v clang-tidy >/dev/null || { echo "tidy.sh: clang-tidy not found (bash scripts/setup.sh)" >&2; exit 2; }
[[ -f $build/compile_commands.json ]] || { echo "tidy.sh: $build/compile_commands.json missing (bash scripts/build.sh)" >&2; exit 2; }
mapfile -t files < <(git ls-files '*.cpp' | grep -E '^(src|optimizer|python)/')
# The build's GCC flags that clang does not know are not findings.
printf '%s\0' "${files[@]}" |
  xargs -0 -P "$(nproc)" -n 4 clang-tidy -p "$build" --quiet --extra-arg=-Wno-unknown-warning-option \
    --extra-arg=-Wno-ignored-optimization-argument 2>/dev/null
echo "tidy: ${#files[@]} files pass .clang-tidy"
