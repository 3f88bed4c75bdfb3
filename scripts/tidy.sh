#!/usr/bin/env bash
# Runs the checks of .clang-tidy on the library's, the program's and the Python module's sources,
# with the compile commands of a configured build (default build/, as scripts/build.sh makes it).
# Targets built eight files to a unit (CMake's unity build) are checked a unit at a time, as the
# compiler sees them; every source must be in some compile command, or the script says which not.
#   bash scripts/tidy.sh [BUILD_DIR]    exit 1 on any finding, each named with its file and line
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
command -v clang-tidy >/dev/null || { echo "tidy.sh: clang-tidy not found (bash scripts/setup.sh)" >&2; exit 2; }
[[ -f $build/compile_commands.json ]] || { echo "tidy.sh: $build/compile_commands.json missing (bash scripts/build.sh)" >&2; exit 2; }
# The compile commands that compile a tracked source of src/, optimizer/ or python/, alone or in a unit.
units=$(python3 - "$build" <<'PY'
import json, os, re, subprocess, sys
build = sys.argv[1]
tracked = subprocess.run(["git", "ls-files", "*.cpp"], capture_output=True, text=True, check=True).stdout.split()
wanted = {f for f in tracked if re.match(r"(src|optimizer|python)/", f)}
units, covered = [], set()
for e in json.load(open(os.path.join(build, "compile_commands.json"))):
    path = os.path.join(e["directory"], e["file"])
    sources = [os.path.relpath(path)]
    if "/Unity/unity_" in path:
        sources = [os.path.relpath(i) for i in re.findall(r'#include "([^"]+)"', open(path).read())]
    if wanted.intersection(sources):
        units.append(path)
        covered.update(sources)
if wanted - covered:
    sys.exit(f"tidy.sh: no compile command of {build} compiles " + ", ".join(sorted(wanted - covered)))
print("\n".join(units))
PY
) || exit 2
mapfile -t files <<< "$units"
# The build's GCC flags that clang does not know are not findings.
printf '%s\0' "${files[@]}" |
  xargs -0 -P "$(nproc)" -n 1 clang-tidy -p "$build" --config-file=.clang-tidy --quiet --extra-arg=-Wno-unknown-warning-option \
    --extra-arg=-Wno-ignored-optimization-argument 2>/dev/null
echo "tidy: ${#files[@]} compile units pass .clang-tidy"
