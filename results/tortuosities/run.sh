#!/usr/bin/env bash
# The four tortuosities of the same media against porosity: the droplet's <T> (100 random starts),
# and the pore space's geometric T, diffusive tau and flow (hydrodynamic) T with the permeability,
# each at 250 and 500 pixels across the 500 x 500 box (8 and 16 pixels a smallest radius). MEDIA
# overlapping media a porosity (default 50) at porosities 0.45 to 0.95, medium seeds from 5000
# (no calibration or search ever used them). One `softdrop tortuosity` a medium, two at a time;
# a medium already measured is kept, so the study resumes. About 45 minutes on 2 cores at the
# default. Writes json/ (one file a medium), media.csv, points.csv, fits.csv, correlations.csv and
# tortuosities.png, then prints points.csv. fine.sh then solves the geometric T and the diffusive tau
# at φ ≤ 0.6 at twice the pixels, where 500 is not enough for the diffusive tau.
set -euo pipefail
cd "$(dirname "$0")"
here=$PWD
MEDIA=${MEDIA:-50}
SRC=${SOFTDROP:-$here/../../build/softdrop}
BIN=$(mktemp /tmp/softdrop_tortuosities.XXXXXX)  # a copy: a rebuild meanwhile changes nothing here
trap 'rm -f "$BIN"' EXIT
cp "$SRC" "$BIN"
chmod +x "$BIN"
PYTHON=${PYTHON:-/usr/bin/python3}  # Debian's, with numpy, pandas and matplotlib
mkdir -p json
jobs=()
for p in 0.45 0.5 0.55 0.6 0.65 0.7 0.75 0.8 0.85 0.9 0.95; do
  index=$("$PYTHON" -c "print(round(($p - 0.45) / 0.05))")
  for ((m = 0; m < MEDIA; ++m)); do
    seed=$((5000 + 100 * index + m))
    [[ -s json/$p-$seed.json || -s json/$p-$seed.err ]] || jobs+=("$p $seed")
  done
done
echo "tortuosities: ${#jobs[@]} media to measure" >&2
if ((${#jobs[@]})); then
  printf '%s\n' "${jobs[@]}" | xargs -P 2 -L 1 bash -c '
    p=$0 seed=$1
    if "'"$BIN"'" tortuosity --porosity "$p" --medium-seed "$seed" --pixels 250 --starts 100 --seed "$seed" \
         --threads 1 --quiet --format json > "json/$p-$seed.tmp" 2> "json/$p-$seed.log"; then
      mv "json/$p-$seed.tmp" "json/$p-$seed.json"
    elif grep -q "every tortuosity is undefined" "json/$p-$seed.log"; then
      mv "json/$p-$seed.log" "json/$p-$seed.err"  # no pore path from the top to the bottom
    else
      cat "json/$p-$seed.log" >&2
      exit 255  # stops xargs, and the script
    fi
    rm -f "json/$p-$seed.tmp" "json/$p-$seed.log"
    echo "tortuosities: $p $seed" >&2'
fi
"$PYTHON" "$here/analyse.py" "$here" "$BIN"
cat points.csv
