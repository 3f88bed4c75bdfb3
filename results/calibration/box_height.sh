#!/usr/bin/env bash
# The explicit droplet (explicit.toml, the defaults' <T> and passage) in boxes of other heights: the
# calibration's 6 porosities x 10 overlapping media x 20 droplets in boxes 500 wide and 200 to 500
# high (no area traces). Shows what the box's depth does to the passage at low porosity and to <T>.
# Writes box_height.csv (one row per height), box_height_points.csv (one row per height and
# porosity) and box_height.png. Under a minute on 2 cores. SOFTDROP=path runs another build.
#     bash results/calibration/box_height.sh
set -euo pipefail
cd "$(dirname "$0")"
BIN=${SOFTDROP:-../../build/softdrop}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for h in 200 250 300 350 400 450 500; do
  echo "box_height.sh: height $h" >&2
  "$BIN" calibrate --format csv --quiet --config explicit.toml --setting "height $h:" --height "$h" --trace-media 0 \
    --csv "$tmp/$h.csv" --points "$tmp/${h}_points.csv" > /dev/null
done
/usr/bin/python3 - "$tmp" <<'PY'
import sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

tmp = sys.argv[1]
heights = [200, 250, 300, 350, 400, 450, 500]
rows, points = [], []
for h in heights:
    rows.append(pd.read_csv(f"{tmp}/{h}.csv").assign(height=h))
    points.append(pd.read_csv(f"{tmp}/{h}_points.csv").assign(height=h))
rows, points = pd.concat(rows), pd.concat(points)
rows.insert(0, "height", rows.pop("height"))
points.insert(0, "height", points.pop("height"))
rows.to_csv("box_height.csv", index=False)
points.to_csv("box_height_points.csv", index=False)

fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
phi = np.linspace(0.45, 1, 200)
left.plot(phi, 1.58 - 0.58 * phi**3.87, "k-", label="paper: 1.58 - 0.58 φ^3.87")
for h, group in points.groupby("height"):
    left.errorbar(group.porosity, group.mean_tortuosity, yerr=group.standard_error, marker="o", ms=3,
                  capsize=2, label=f"H = {h}")
left.set_xlabel("porosity φ")
left.set_ylabel("⟨T⟩ of the droplets that pass")
left.legend(fontsize=7)
low = points[points.target_porosity == 0.5]
right.plot(low.height, low.passed / low.droplets, "o-", label="passed at φ = 0.5")
right.plot(rows.height, rows.rms_distance, "s-", label="rms distance from the paper's f(φ)")
right.axhline(0.25, color="gray", lw=0.8, ls="--", label="a quarter")
right.set_xlabel("box height H (box 500 wide; droplet radius 8, grains 16 to 48)")
right.legend(fontsize=8)
fig.tight_layout()
fig.savefig("box_height.png", dpi=110)
PY
