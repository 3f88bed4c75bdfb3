#!/usr/bin/env bash
# Runs every command of the README's tour (the lines between <!-- tour --> and <!-- /tour -->) in a
# scratch folder, with build/softdrop replaced by the program under test, and checks that each ends
# well: exit status 0, no warning on stderr, and every single droplet it reports passed.
#   bash tests/readme_tour.sh SOFTDROP_BINARY SOURCE_DIR
set -euo pipefail
bin=$(realpath "$1"); src=$(realpath "$2")
work=$(mktemp -d); trap 'rm -rf "$work"' EXIT
ln -s "$src/examples" "$work/examples"
mapfile -t commands < <(sed -n '/^<!-- tour -->$/,/^<!-- \/tour -->$/p' "$src/README.md" |
                        sed -n 's/^    \(build\/softdrop .*\)$/\1/p')
((${#commands[@]} >= 10)) || { echo "readme_tour: found ${#commands[@]} commands in the README's tour"; exit 1; }
cd "$work"
failed=0
for c in "${commands[@]}"; do
  read -r -a words <<< "${c#build/softdrop }"
  if ! "$bin" "${words[@]}" > out.txt 2> err.txt; then
    echo "FAIL (exit status): $c"; cat err.txt; failed=1; continue
  fi
  if grep -qi "warning" err.txt; then echo "FAIL (warning): $c"; cat err.txt; failed=1; continue; fi
  if grep -E '^outcome ' out.txt | grep -vq 'passed'; then
    echo "FAIL (droplet did not pass): $c"; cat out.txt; failed=1; continue
  fi
  echo "ok: $c"
done
exit $failed
