#!/usr/bin/env bash
# The scan behind passage.toml: a smaller droplet (R = 3.5 to 6, nRT for about 9 % spring strain at
# rest) with stiffer contacts and more internal viscosity, among grains of radii 28 to 48 (media
# seed 2), 26 to 50, 28 to 52, 30 to 52 and the defaults' 16 to 48 (seed 1); each setting as the
# calibration measures it, on 200 overlapping media a porosity (6 porosities x 200 media x 20
# droplets, area traces through 4 non-overlapping media at phi = 0.79).
# Writes passage_scan.csv (one row per setting and grain range) and passage_scan_points.csv (one
# row per setting, grain range and porosity). About 35 minutes on 2 cores. SOFTDROP=path runs
# another build.
#     bash results/calibration/passage_scan.sh
set -euo pipefail
cd "$(dirname "$0")"
BIN=${SOFTDROP:-../../build/softdrop}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
stage=0
# run SEED R_MIN R_MAX CALIBRATE_OPTIONS...: one calibrate command over one grain range
run() {
  local seed=$1 lo=$2 hi=$3
  shift 3
  stage=$((stage + 1))
  echo "passage_scan.sh: stage $stage, grains $lo-$hi, seed $seed" >&2
  "$BIN" calibrate --format csv --quiet --seed "$seed" --media 200 --trace-media 4 --r-min "$lo" --r-max "$hi" \
    "$@" --csv "$tmp/$stage.csv" --points "$tmp/${stage}_points.csv" > /dev/null
  echo "$seed,$lo,$hi" > "$tmp/$stage.range"
}
run 2 28 48 --setting "radius=6 kc=3e8" --setting "radius=5 nrt=1.59e9 kc=3e8" \
  --setting "radius=5 nrt=1.59e9 kc=2e8" --setting "radius=5.5 nrt=1.92e9 kc=3e8" \
  --setting "radius=5 nrt=1.24e9 kc=3e8" --setting "radius=5 nrt=1.59e9 kc=1.5e8" \
  --setting "radius=5.5 nrt=1.92e9 kc=2e8 viscosity=1.4e5"
run 2 28 48 --scan radius=5 --scan nrt=1.59e9 --scan kc=2e8 --scan viscosity=3e4,7e4,1.4e5,4e5,6e5,1e6
run 2 28 48 --scan radius=5 --scan nrt=1.59e9 --scan kc=3e8 --scan viscosity=4e5,6e5,1e6
run 1 28 48 --scan radius=5 --scan nrt=1.59e9 --scan kc=2.5e8,3e8 --scan viscosity=1e6,2e6
for range in "26 50" "28 52" "30 52"; do
  run 1 $range --scan radius=5 --scan nrt=1.59e9 --scan kc=2.5e8,3e8 --scan viscosity=1e6
done
run 1 16 48 --setting "radius=3.5 nrt=0.779e9 kc=2.5e8 viscosity=1e6" \
  --setting "radius=4.5 nrt=1.288e9 kc=2.5e8 viscosity=1e6" --setting "radius=5 nrt=1.59e9 kc=2.5e8 viscosity=1e6"
run 1 16 48 --scan radius=4 --scan nrt=1.018e9 --scan kc=2e8,2.5e8,3e8 --scan viscosity=1e6
run 1 16 48 --setting "radius=4 nrt=1.018e9 kc=2.5e8 viscosity=3e6"
/usr/bin/python3 - "$tmp" "$stage" <<'PY'
import sys
import pandas as pd

tmp, stages = sys.argv[1], int(sys.argv[2])
rows, points = [], []
for stage in range(1, stages + 1):
    seed, lo, hi = open(f"{tmp}/{stage}.range").read().split(",")
    for frame, name in ((rows, f"{stage}.csv"), (points, f"{stage}_points.csv")):
        part = pd.read_csv(f"{tmp}/{name}")
        part.insert(0, "r_max", float(hi))
        part.insert(0, "r_min", float(lo))
        part.insert(0, "seed", int(seed))
        part.insert(0, "stage", stage)
        frame.append(part)
rows, points = pd.concat(rows), pd.concat(points)
points["passed_fraction"] = points.passed / points.droplets
rows.sort_values(["stage", "setting"]).to_csv("passage_scan.csv", index=False)
points.to_csv("passage_scan_points.csv", index=False)
PY
