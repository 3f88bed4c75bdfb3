#!/usr/bin/env bash
# The defaults measured as the calibration measures every setting (6 porosities x 10 overlapping
# media x 20 droplets, the area traces at phi = 0.79, the resting test), against the paper's
# <T>(phi), and then through the 10 080 droplets of tension_robustness.sh. Writes defaults.csv,
# defaults_points.csv, defaults.png and defaults_robustness.csv. About 2 minutes on 2 cores.
# SOFTDROP=path runs another build.
#     bash results/calibration/defaults.sh
set -euo pipefail
cd "$(dirname "$0")"
BIN=${SOFTDROP:-../../build/softdrop}
"$BIN" calibrate --format csv --quiet --setting defaults --csv defaults.csv --points defaults_points.csv \
  --plot defaults.png > /dev/null
SOFTDROP=$BIN bash tension_robustness.sh defaults defaults_robustness.csv
