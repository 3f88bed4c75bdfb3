#!/usr/bin/env bash
# Regenerates results/: the tortuosity-porosity sweep, the two fits, the two averagings, the sweep
# with the other constraint order and the area trace (about a minute on 2 cores). Each
# study's README.md repeats its commands.
# An interrupted run continues where it stopped: the sweep store keeps every finished medium.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh > build.log 2>&1 || { cat build.log; exit 1; }
S=${SOFTDROP:-./build/softdrop}  # SOFTDROP=path runs another build
mkdir -p results/sweep results/fit results/averagings results/area_trace results/constraint_order
PHI=0.5,0.55,0.6,0.65,0.7,0.75,0.8,0.85,0.9,0.95

# 1. Sweep: 10 porosities x 20 overlapping media x 20 droplets from random starts (500 x 500 boxes).
$S sweep --db results/sweep/sweep.db --porosities "$PHI" --media 20 --droplets 20 \
  > results/sweep/summary.txt
$S sweep-report --db results/sweep/sweep.db --format csv > results/sweep/points.csv
$S sweep-report --db results/sweep/sweep.db --media --format csv > results/sweep/media.csv

# 2. Fits of <T>(phi): a - c phi^b (the paper's) and 1 - p ln phi (hydrodynamic), weighted by the SEs.
$S fit --db results/sweep/sweep.db --plot results/fit/fit.png --json results/fit/fit.json > results/fit/fit.txt

# 3. The two averagings of the per-medium points, groups of 10 media.
$S averagings --db results/sweep/sweep.db --group 10 --csv results/averagings/averagings.csv \
  --plot results/averagings/averagings.png > /dev/null

# 4. The sweep again with the red-black constraint order, compared droplet by droplet with step 1's.
$S sweep --db results/constraint_order/sweep.db --porosities "$PHI" --media 20 \
  --droplets 20 --constraint-order red-black > results/constraint_order/summary.txt
$S sweep-report --db results/constraint_order/sweep.db --format csv > results/constraint_order/points.csv
sqlite3 results/sweep/sweep.db < results/constraint_order/compare.sql > results/constraint_order/pairs.csv

# 5. Area trace: one droplet through a phi = 0.79 medium of non-overlapping, slightly separated grains.
$S render trace --kind non-overlapping --porosity 0.79 --medium-seed 4 --csv results/area_trace/trace.csv \
  -o results/area_trace/trace.png 2> results/area_trace/summary.txt
cat results/area_trace/summary.txt
