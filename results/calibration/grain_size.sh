#!/usr/bin/env bash
# The default droplet on grains of other sizes: the calibration's 6 porosities x 30 overlapping media
# x 20 droplets in the 500 x 500 box, for uniform grain radii from r_min in {16, 20, 24, 28, 32} to
# r_max in {40, 48, 56, 72} (no area traces), and beside each the fraction of starts a point moved by
# gravity alone passes at porosity 0.5 (softdrop.rigid_descent, 200 media x 20 starts). Shows what the
# grains' sizes do to the passage at low porosity and to <T>. Writes grain_size.csv (one row per
# grain range), grain_size_points.csv (one row per range and porosity) and grain_size.png. About 4
# minutes on 2 cores; needs the Python module next to the binary (build/python). SOFTDROP=path runs
# another build.
#     bash results/calibration/grain_size.sh
set -euo pipefail
cd "$(dirname "$0")"
BIN=${SOFTDROP:-../../build/softdrop}
export PYTHONPATH="$(dirname "$BIN")/python${PYTHONPATH:+:$PYTHONPATH}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
ranges=()
for lo in 16 20 24 28 32; do
  for hi in 40 48 56 72; do ranges+=("$lo-$hi"); done
done
for i in "${!ranges[@]}"; do
  range=${ranges[$i]}
  echo "grain_size.sh: grains $range ($((i + 1)) of ${#ranges[@]})" >&2
  "$BIN" calibrate --format csv --quiet --setting "grains $range:" --r-min "${range%-*}" --r-max "${range#*-}" \
    --media 30 --trace-media 0 --csv "$tmp/$range.csv" --points "$tmp/${range}_points.csv" > /dev/null
done
/usr/bin/python3 - "$tmp" "${ranges[@]}" <<'PY'
import sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import pandas as pd
import softdrop

tmp, ranges = sys.argv[1], sys.argv[2:]
rows, points = [], []
for i, name in enumerate(ranges):
    lo, hi = (float(v) for v in name.split("-"))
    print(f"grain_size.sh: a point's passage, grains {name} ({i + 1} of {len(ranges)})", file=sys.stderr)
    rng = np.random.default_rng(20261204)
    media = [softdrop.Medium.generate("overlapping", porosity=0.5, r_min=lo, r_max=hi, seed=seed)
             for seed in range(1, 201)]
    per_medium = np.array([(softdrop.rigid_descent(m, rng.uniform(0, m.width, 20)).outcome == "passed").mean()
                           for m in media])
    row = pd.read_csv(f"{tmp}/{name}.csv")
    row.insert(0, "r_max", hi)
    row.insert(0, "r_min", lo)
    row["point_passed_05"] = per_medium.mean()
    row["point_passed_05_standard_error"] = per_medium.std(ddof=1) / np.sqrt(len(per_medium))
    rows.append(row)
    point = pd.read_csv(f"{tmp}/{name}_points.csv")
    point.insert(0, "r_max", hi)
    point.insert(0, "r_min", lo)
    points.append(point)
rows, points = pd.concat(rows), pd.concat(points)
low = points[points.target_porosity == 0.5].set_index(["r_min", "r_max"])
rows = rows.set_index(["r_min", "r_max"])
rows["passed_05"] = low.passed / low.droplets
rows = rows.reset_index()
rows.to_csv("grain_size.csv", index=False)
points.to_csv("grain_size_points.csv", index=False)

fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.3))
for hi, group in rows.groupby("r_max"):
    left.plot(group.passed_05, group.rms_distance, "o-", label=f"r_max = {hi:g} (r_min 16 to 32)")
    for _, r in group.iterrows():
        left.annotate(f"{r.r_min:g}", (r.passed_05, r.rms_distance), fontsize=6,
                      xytext=(3, 2), textcoords="offset points")
left.axvline(0.25, color="gray", lw=0.8, ls="--")
left.axhline(0.03, color="gray", lw=0.8, ls=":")
left.set_xlabel("fraction of the 600 droplets that pass at φ = 0.5")
left.set_ylabel("rms of ⟨T⟩ − f(φ) over the 6 porosities")
left.legend(fontsize=7)
for lo, hi in [(16, 48), (24, 40), (28, 48), (24, 72), (16, 72)]:
    group = points[(points.r_min == lo) & (points.r_max == hi)]
    right.errorbar(group.porosity, group.mean_tortuosity - group.paper_tortuosity, yerr=group.media_standard_error,
                   marker="o", ms=3, capsize=2, label=f"grains {lo} to {hi}")
right.axhline(0, color="k", lw=0.8)
right.set_xlabel("porosity φ")
right.set_ylabel("⟨T⟩ − f(φ), error over media")
right.legend(fontsize=7)
fig.tight_layout()
fig.savefig("grain_size.png", dpi=110)
PY
