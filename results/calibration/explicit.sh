#!/usr/bin/env bash
# fast.toml (the defaults' droplet with the exponential viscosity step at dt = 6e-6 and nu = 2.8e5)
# measured as defaults.sh measures the defaults: the calibration's 6 porosities x 10 overlapping
# media x 20 droplets, the area traces at phi = 0.79, the resting test, and then the 10 080
# droplets of tension_robustness.sh. Writes fast.csv, fast_points.csv and fast_robustness.csv.
# About 7 minutes on 2 cores. SOFTDROP=path runs another build.
#     bash results/calibration/fast.sh
set -euo pipefail
cd "$(dirname "$0")"
BIN=${SOFTDROP:-../../build/softdrop}
"$BIN" calibrate --format csv --quiet --config fast.toml --setting "fast:" --csv fast.csv --points fast_points.csv \
  > /dev/null
SOFTDROP=$BIN bash tension_robustness.sh fast.toml fast_robustness.csv
