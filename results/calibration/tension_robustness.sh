#!/usr/bin/env bash
# The calibrated tension-carrying droplet of tension.sh (tension_droplet.toml: S = 8 400, grains
# 16 S to 48 S, c_c = 0, nu = 1 500) through 10 080 droplets: porosities 0.5 to 0.95, overlapping
# and non-overlapping media, 10 media of each, 84 droplets from random starts in each, none of them
# the calibration's.
# Writes tension_robustness.csv, one row per porosity, kind and medium: droplets passed, stuck,
# timed out and diverged, and their mean T. About 10 minutes on 2 cores. SOFTDROP=path runs
# another build.
#   bash tension_robustness.sh [CONFIG OUT]: another droplet (a config file, or "defaults" for the
#   program's defaults) through the same droplets, written to OUT. NON_OVERLAPPING="0.6 0.7 ..."
#   leaves out the non-overlapping porosities that a config's grains cannot reach; an entry
#   "0.5:0.08" makes that porosity's media with surface gaps of 0.08 (the kind column then says
#   "non-overlapping gap 0.08").
set -euo pipefail
cd "$(dirname "$0")"
BIN=${SOFTDROP:-../../build/softdrop}
CONFIG=${1:-tension_droplet.toml}
OUT=${2:-tension_robustness.csv}
DROPLET=()
[[ $CONFIG == defaults ]] || DROPLET=(--config "$CONFIG")
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "porosity_target,kind,medium_seed,droplets,passed,stuck,timeout,diverged,mean_tortuosity" > "$tmp/out.csv"
POROSITIES="0.5 0.6 0.7 0.8 0.9 0.95"
for kind in overlapping non-overlapping; do
  porosities=$POROSITIES
  [[ $kind == overlapping ]] || porosities=${NON_OVERLAPPING:-$POROSITIES}
  for entry in $porosities; do
    phi=${entry%%:*}
    GAP=() label=$kind
    if [[ $entry == *:* ]]; then GAP=(--gap "${entry#*:}") label="$kind gap ${entry#*:}"; fi
    echo "tension_robustness.sh: $CONFIG, $label, phi = $phi" >&2
    for medium in 1 2 3 4 5 6 7 8 9 10; do
      "$BIN" simulate --quiet "${DROPLET[@]}" --kind "$kind" "${GAP[@]}" --porosity "$phi" --medium-seed $((1000 + medium)) \
        --seed $((2000 + medium)) --droplets 84 --runs "$tmp/runs.csv" > /dev/null
      /usr/bin/python3 - "$tmp/runs.csv" "$phi" "$label" $((1000 + medium)) >> "$tmp/out.csv" <<'PY'
import sys
import pandas as pd
runs = pd.read_csv(sys.argv[1])
count = runs.outcome.value_counts()
passed = runs[runs.outcome == "passed"]
mean_tortuosity = f"{passed.tortuosity.mean():.6f}" if len(passed) else ""
print(",".join([sys.argv[2], sys.argv[3], sys.argv[4], str(len(runs))] +
               [str(int(count.get(k, 0))) for k in ("passed", "stuck", "timeout", "diverged")] + [mean_tortuosity]))
PY
    done
  done
done
mv "$tmp/out.csv" "$OUT"
