#!/usr/bin/env bash
# Tortuosity against porosity at the paper's size: 10 porosities (0.45 to 0.9) x 200 overlapping
# media x 200 droplets, 400 000 droplets, on the defaults and on media no calibration saw (the
# sweep's held-out stream); then the paper's fit (weighed by the media's standard errors, again by
# the droplets', and of the per-medium means), its two averagings in groups of 100 media, and the
# figure of both means against the paper's f with their residuals. About 30 minutes on 2 cores
# (Intel Xeon; 16 on an AMD EPYC of family 26).
# An interrupted run continues where it stopped: the store, paper.db (not committed), keeps every
# finished medium. SOFTDROP=path runs another build.
#     bash results/paper_size/run.sh
set -euo pipefail
cd "$(dirname "$0")"
BIN=${SOFTDROP:-../../build/softdrop}
"$BIN" sweep --preset paper --db paper.db > summary.txt
"$BIN" sweep-report --db paper.db --format csv > points.csv
"$BIN" sweep-report --db paper.db --media --format csv > media.csv
"$BIN" fit --db paper.db --plot fit.png --json fit.json > fit.txt
"$BIN" fit --db paper.db --errors droplets --json fit_droplets.json > fit_droplets.txt
"$BIN" fit --db paper.db --mean per-medium --json fit_per_medium.json > fit_per_medium.txt
"$BIN" averagings --db paper.db --group 100 --csv averagings.csv --plot averagings.png > /dev/null
/usr/bin/python3 figure.py
