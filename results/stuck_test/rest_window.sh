#!/usr/bin/env bash
# How short can the rest window be for the default droplet? The same 4 000 droplets (porosities
# 0.5, 0.6, 0.7 and 0.8, overlapping, 10 held-out media of seed 777001 each, 100 droplets a medium)
# under the default rest test (0.1 within 0.05 time units) and under shorter windows with the same
# distance; every droplet's verdict, T and steps compared with the default's. Writes
# rest_window.csv (one row per window and porosity). About 1.5 minutes on 2 cores.
#     bash results/stuck_test/rest_window.sh
set -euo pipefail
cd "$(dirname "$0")"
BIN=${SOFTDROP:-../../build/softdrop}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
for w in 0.05 0.03 0.02 0.01 0.005; do
  "$BIN" sweep --porosities 0.5,0.6,0.7,0.8 --media 10 --droplets 100 --seed 777001 --rest-window "$w" \
    --db "$tmp/w$w.db" --quiet > /dev/null
done
/usr/bin/python3 - "$tmp" <<'PY'
import sqlite3, sys
import pandas as pd
tmp = sys.argv[1]
def droplets(w):
    with sqlite3.connect(f"{tmp}/w{w}.db") as db:
        return pd.read_sql("SELECT porosity_index, medium_index, droplet, outcome, tortuosity, steps "
                           "FROM sweep_droplets_view", db)
porosities = [0.5, 0.6, 0.7, 0.8]
ref, rows = droplets("0.05"), []
for w in ["0.05", "0.03", "0.02", "0.01", "0.005"]:
    d = ref.merge(droplets(w), on=["porosity_index", "medium_index", "droplet"], suffixes=("", "_w"))
    for i, g in d.groupby("porosity_index"):
        passed = g["outcome"] == "passed"
        rows.append({"rest_window": float(w), "target_porosity": porosities[i], "droplets": len(g),
                     "passed": int((g["outcome_w"] == "passed").sum()),
                     "stuck": int((g["outcome_w"] == "stuck").sum()),
                     "verdicts_changed": int((g["outcome"] != g["outcome_w"]).sum()),
                     "tortuosity_changed": int((g["tortuosity"][passed] != g["tortuosity_w"][passed]).sum()),
                     "steps": int(g["steps_w"].sum()),
                     "steps_ratio": round(g["steps_w"].sum() / g["steps"].sum(), 3)})
out = pd.DataFrame(rows)
out.to_csv("rest_window.csv", index=False)
print(out.to_string(index=False))
PY
