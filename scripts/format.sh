#!/usr/bin/env bash
# Formats the C++ sources with clang-format and the repository's .clang-format.
#   bash scripts/format.sh           rewrite every tracked C++ file in place
#   bash scripts/format.sh --check   change nothing; exit 1 and name each file that would change
set -euo pipefail
cd "$(dirname "$0")/.."
command -v clang-format >/dev/null || { echo "format.sh: clang-format not found (bash scripts/setup.sh)" >&2; exit 2; }
mapfile -t files < <(git ls-files '*.cpp' '*.hpp' '*.inc' '*.h' '*.hpp.in')
if [[ "${1:-}" == "--check" ]]; then
  clang-format --dry-run --Werror "${files[@]}"
  echo "format: ${#files[@]} files as clang-format writes them"
else
  clang-format -i "${files[@]}"
fi
