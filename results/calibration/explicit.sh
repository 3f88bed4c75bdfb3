#!/usr/bin/env bash
# explicit.toml (the defaults' droplet with the explicit viscosity step at dt = 3.5e-6, nu = 1.37e5)
# measured as defaults.sh measures the defaults: the calibration's 6 porosities x 10 overlapping
# media x 20 droplets, the area traces at phi = 0.79, the resting test, and then the 10 080
# droplets of tension_robustness.sh. Writes explicit.csv, explicit_points.csv and
# explicit_robustness.csv. About 3 minutes on 2 cores. SOFTDROP=path runs another build.
#     bash results/calibration/explicit.sh
set -euo pipefail
cd "$(dirname "$0")"
BIN=${SOFTDROP:-../../build/softdrop}
"$BIN" calibrate --format csv --quiet --config explicit.toml --setting "explicit:" --csv explicit.csv \
  --points explicit_points.csv > /dev/null
SOFTDROP=$BIN bash tension_robustness.sh explicit.toml explicit_robustness.csv
