#!/usr/bin/env bash
# passage.toml (a droplet of radius 5 among grains of radii 26 to 50) against the defaults, as the
# calibration measures a setting but on 200 media a porosity (6 porosities x 200 overlapping media
# x 20 droplets, area traces through 4 non-overlapping media at phi = 0.79, the resting test), with
# two seeds of media and starts; then passage.toml through the robustness droplets of
# tension_robustness.sh (its non-overlapping media at phi = 0.5 with gaps of 0.08: at the default
# 0.13 its grains jam).
# Writes passage.csv (one row per droplet and seed), passage_points.csv (one row per droplet, seed
# and porosity), passage.png and passage_robustness.csv. About 15 minutes on 2 cores.
#     bash results/calibration/passage.sh
#     bash results/calibration/passage.sh paper   # and the paper-size sweep of passage.toml, 24 minutes more
# The paper-size sweep writes passage_paper_points.csv and passage_paper_fit.json; its store,
# passage_paper.db (not committed), continues where it stopped. SOFTDROP=path runs another build.
set -euo pipefail
cd "$(dirname "$0")"
BIN=${SOFTDROP:-../../build/softdrop}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for seed in 1 2; do
  echo "passage.sh: the defaults and passage.toml, seed $seed" >&2
  "$BIN" calibrate --format csv --quiet --seed "$seed" --media 200 --trace-media 4 --setting "defaults:" \
    --csv "$tmp/defaults_$seed.csv" --points "$tmp/defaults_${seed}_points.csv" > /dev/null
  "$BIN" calibrate --format csv --quiet --config passage.toml --seed "$seed" --media 200 --trace-media 4 \
    --setting "passage.toml:" --csv "$tmp/passage_$seed.csv" --points "$tmp/passage_${seed}_points.csv" > /dev/null
done
/usr/bin/python3 - "$tmp" <<'PY'
import sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import pandas as pd

tmp = sys.argv[1]
rows, points = [], []
for droplet in ("defaults", "passage"):
    for seed in (1, 2):
        for frame, name in ((rows, f"{droplet}_{seed}.csv"), (points, f"{droplet}_{seed}_points.csv")):
            part = pd.read_csv(f"{tmp}/{name}")
            part.insert(0, "seed", seed)
            part.insert(0, "droplet", "defaults" if droplet == "defaults" else "passage.toml")
            frame.append(part)
rows, points = pd.concat(rows), pd.concat(points)
points["passed_fraction"] = points.passed / points.droplets
rows.to_csv("passage.csv", index=False)
points.to_csv("passage_points.csv", index=False)

fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
phi = np.linspace(0.45, 1, 200)
left.plot(phi, 1.58 - 0.58 * phi**3.87, "k-", label="paper: 1.58 - 0.58 φ^3.87")
for (droplet, seed), group in points.groupby(["droplet", "seed"]):
    label = f"{droplet}, seed {seed}"
    left.errorbar(group.porosity, group.mean_tortuosity, yerr=group.media_standard_error, marker="o", ms=3,
                  capsize=2, label=label)
    right.plot(group.target_porosity, group.passed_fraction, "o-", ms=3, label=label)
left.set_xlabel("porosity φ")
left.set_ylabel("⟨T⟩ of the droplets that pass (error over media)")
left.legend(fontsize=7)
right.axhline(0.25, color="gray", lw=0.8, ls="--", label="a quarter")
right.set_xlabel("target porosity φ (200 media x 20 droplets)")
right.set_ylabel("fraction of droplets that pass")
right.legend(fontsize=7)
fig.tight_layout()
fig.savefig("passage.png", dpi=110)
PY
SOFTDROP=$BIN NON_OVERLAPPING="0.5:0.08 0.6 0.7 0.8 0.9 0.95" bash tension_robustness.sh passage.toml passage_robustness.csv
if [[ ${1:-} == paper ]]; then
  # The calibration stream's seed 1: the media the paper-size study of the defaults had before
  # sweeps drew held-out media, so the two droplets are compared on the same seeds.
  "$BIN" sweep --preset paper --config passage.toml --media-stream calibration --db passage_paper.db > /dev/null
  "$BIN" sweep-report --db passage_paper.db --format csv > passage_paper_points.csv
  "$BIN" fit --db passage_paper.db --json passage_paper_fit.json > /dev/null
fi
