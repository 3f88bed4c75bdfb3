#!/usr/bin/env bash
# The diffusive tau at twice the study's pixels, where it resolves slowest: for every medium of the
# study at PHIS with a pore path (media.csv), the geometric T and the diffusive tau at 1000 pixels
# across (32 a smallest radius), each checked against 2000, with no flow solve and no droplets.
# Writes fine.csv, then runs analyse.py, which takes both values from there for those media (the
# flow T, converged at 500 (convergence.sh), and the droplet's <T> stay the study's). About 15 to 40
# s a medium on one core, two at a time: about 35 minutes at the default; a medium already solved
# (fine/, one JSON a medium) is kept, so it resumes.
#     bash results/tortuosities/fine.sh            (PHIS="0.45 0.5 0.55 0.6")
set -euo pipefail
cd "$(dirname "$0")"
here=$PWD
PHIS=${PHIS:-"0.45 0.5 0.55 0.6"}
SRC=${SOFTDROP:-$here/../../build/softdrop}
BIN=$(mktemp /tmp/softdrop_fine.XXXXXX)  # a copy: a rebuild meanwhile changes nothing here
trap 'rm -f "$BIN"' EXIT
cp "$SRC" "$BIN"
chmod +x "$BIN"
mkdir -p fine
jobs=()
for p in $PHIS; do
  # The study's media with a pore path (media.csv): target porosity and medium seed.
  for seed in $(awk -F, -v p="$p" 'NR > 1 && $1 + 0 == p + 0 { print $2 }' media.csv); do
    [[ -s fine/$p-$seed.json ]] || jobs+=("$p $seed")
  done
done
echo "fine: ${#jobs[@]} media to solve" >&2
if ((${#jobs[@]})); then
  printf '%s\n' "${jobs[@]}" | xargs -P 2 -L 1 bash -c '
    p=$0 seed=$1
    if "'"$BIN"'" tortuosity --porosity "$p" --medium-seed "$seed" --pixels 1000 --starts 0 --no-flow \
         --threads 1 --quiet --format json > "fine/$p-$seed.tmp" 2> "fine/$p-$seed.log"; then
      mv "fine/$p-$seed.tmp" "fine/$p-$seed.json"
      rm -f "fine/$p-$seed.log"
      echo "fine: $p $seed" >&2
    else
      cat "fine/$p-$seed.log" >&2
      exit 255  # stops xargs, and the script
    fi'
fi
# fine.csv: each medium's two values and the relative change from 1000 to 2000 pixels across.
PYTHON=${PYTHON:-/usr/bin/python3}  # Debian's, with numpy, pandas and matplotlib
"$PYTHON" - <<'PY'
import glob, json, os
import pandas as pd
rows = []
for path in sorted(glob.glob("fine/*.json")):
    target, seed = os.path.basename(path)[:-5].split("-")
    j = json.load(open(path))
    row = {"target_porosity": float(target), "medium_seed": int(seed)}
    for q in ("geometric", "diffusive"):
        v = j[q + "_tortuosity"]
        row.update({q + "_at_1000": v["values"][0], q + "_at_2000": v["values"][1],
                    q + "_change_1000_to_2000": v["change"]})
    rows.append(row)
pd.DataFrame(rows).to_csv("fine.csv", index=False)
print(f"fine: {len(rows)} media in fine.csv")
PY
"$PYTHON" "$here/analyse.py" "$here" "$BIN"
