#!/usr/bin/env bash
# The explicit droplet (explicit.toml, the defaults' <T> and passage) with a smaller droplet, over
# the paper's number of media: the calibration's six porosities x 200 media x 20 droplets (no area
# traces) for droplet radii 4 to 8 in the same grains (radii 16 to 48) and box (500 x 500), on
# overlapping media and on non-overlapping ones (surface gaps of 13 % of the larger radius). nRT
# scales with R^2, so the springs rest at the same 5 % strain; every other parameter is
# explicit.toml's. Shows what the droplet's size and the kind of medium do to the passage at low
# porosity and to <T>. Writes radius.csv (one row per radius), radius_points.csv (one row per radius
# and porosity), the same for non-overlapping media (radius_non_overlapping.csv,
# radius_non_overlapping_points.csv) and radius.png. About 16 minutes on 2 cores. SOFTDROP=path runs
# another build.
#     bash results/calibration/radius.sh
set -euo pipefail
cd "$(dirname "$0")"
BIN=${SOFTDROP:-../../build/softdrop}
settings=()
for r in 4 5 6 7 8; do
  nrt=$(awk -v r="$r" 'BEGIN { printf "%.17g", 2.29e9 * r * r / 64 }')
  settings+=(--setting "radius $r: radius=$r nrt=$nrt")
done
"$BIN" calibrate --format csv --config explicit.toml --media 200 --droplets 20 --trace-media 0 "${settings[@]}" \
  --csv radius.csv --points radius_points.csv > /dev/null
"$BIN" calibrate --format csv --config explicit.toml --kind non-overlapping --media 200 --droplets 20 --trace-media 0 "${settings[@]}" \
  --csv radius_non_overlapping.csv --points radius_non_overlapping_points.csv > /dev/null
/usr/bin/python3 - <<'PY'
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import pandas as pd

fig, axes = plt.subplots(2, 2, figsize=(10, 7.5), sharex=True)
for (left, right), name, kind in zip(axes, ["radius", "radius_non_overlapping"],
                                     ["overlapping", "non-overlapping"]):
    rows, points = pd.read_csv(f"{name}.csv"), pd.read_csv(f"{name}_points.csv")
    points = points.merge(rows[["setting", "radius"]], on="setting")
    for r, group in points.groupby("radius"):
        measured = group[group.passed >= 2]
        left.errorbar(measured.porosity, measured.mean_tortuosity - measured.paper_tortuosity,
                      yerr=measured.media_standard_error, marker="o", ms=3, capsize=2, label=f"R = {r:g}")
        right.plot(group.porosity, group.passed / group.droplets, "o-", ms=3, label=f"R = {r:g}")
    left.axhspan(-0.03, 0.03, color="0.9", label="within 0.03")
    left.axhline(0, color="k", lw=0.8)
    left.set_ylabel("⟨T⟩ − paper's f(φ)  (bars: SE over media)")
    left.set_title(f"{kind} media", fontsize=9)
    left.legend(fontsize=7)
    right.axhline(0.25, color="gray", lw=0.8, ls="--", label="a quarter")
    right.set_ylabel("fraction of droplets that pass")
    right.set_title(f"{kind} media", fontsize=9)
    right.legend(fontsize=7)
for ax in axes[1]:
    ax.set_xlabel("porosity φ")
fig.suptitle("droplet radius R in grains of radii 16 to 48, 200 media × 20 droplets a porosity", fontsize=9)
fig.tight_layout()
fig.savefig("radius.png", dpi=110)
PY
