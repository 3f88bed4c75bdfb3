#!/usr/bin/env bash
# Is the study's resolution converged? The pore-space values of media.csv are at 500 pixels across
# (checked there against 250). Here the first MEDIA media of the study at PHIS are solved at 500 and
# at 1000 pixels across (32 a smallest radius), and convergence_500.csv gives, per porosity and
# value, the median and largest relative change from 500 to 1000 beside the same media's change from
# 250 to 500. About 30 minutes on one core at the defaults; a medium already solved is kept.
#     bash results/tortuosities/convergence.sh            (MEDIA=6 PHIS="0.45 0.55 0.65 0.75")
set -euo pipefail
cd "$(dirname "$0")"
MEDIA=${MEDIA:-6}
PHIS=${PHIS:-"0.45 0.55 0.65 0.75"}
BIN=${SOFTDROP:-../../build/softdrop}
PYTHON=${PYTHON:-/usr/bin/python3}
mkdir -p convergence
for p in $PHIS; do
  index=$("$PYTHON" -c "print(round(($p - 0.45) / 0.05))")
  for ((m = 0; m < MEDIA; ++m)); do
    seed=$((5000 + 100 * index + m))  # the study's medium seeds (run.sh)
    out=convergence/$p-$seed
    [[ -s $out.json || -s $out.err ]] && continue
    if "$BIN" tortuosity --porosity "$p" --medium-seed "$seed" --pixels 500 --starts 0 --threads 1 --quiet \
         --format json > "$out.tmp" 2> "$out.log"; then
      mv "$out.tmp" "$out.json"
    elif grep -q "every tortuosity is undefined" "$out.log"; then
      mv "$out.log" "$out.err"  # no pore path from the top to the bottom
    else
      cat "$out.log" >&2
      exit 1
    fi
    rm -f "$out.tmp" "$out.log"
    echo "convergence: $p $seed" >&2
  done
done
"$PYTHON" - <<'PY'
import glob, json, os
import pandas as pd
media = pd.read_csv("media.csv").set_index(["target_porosity", "medium_seed"])
QUANTITIES = {"geometric_tortuosity": "geometric", "hydrodynamic_tortuosity": "hydrodynamic",
              "diffusive_tortuosity": "diffusive", "permeability": "permeability"}
rows = []
for path in sorted(glob.glob("convergence/*.json")):
    target, seed = os.path.basename(path)[:-5].split("-")
    j = json.load(open(path))
    for q, short in QUANTITIES.items():
        rows.append({"target_porosity": float(target), "medium_seed": int(seed), "value": short,
                     "at_500": j[q]["values"][0], "at_1000": j[q]["values"][1], "change_500_to_1000": j[q]["change"],
                     "change_250_to_500": media.loc[(float(target), int(seed)), short + "_change"]})
frame = pd.DataFrame(rows)
summary = frame.assign(a=frame.change_500_to_1000.abs(), b=frame.change_250_to_500.abs()).groupby(
    ["value", "target_porosity"]).agg(media=("a", "size"), median_change_500_to_1000=("a", "median"),
                                      largest_change_500_to_1000=("a", "max"), median_change_250_to_500=("b", "median"),
                                      mean_change_500_to_1000=("change_500_to_1000", "mean"))
summary.round(5).to_csv("convergence_500.csv")
print(summary.round(4).to_string())
PY
