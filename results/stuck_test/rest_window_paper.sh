#!/usr/bin/env bash
# The rest window at the paper's size: the paper-size sweep (10 porosities x 200 media x 200
# droplets) under the default rest test and again under windows of 0.01 and 0.005 time units,
# every droplet compared; the droplets the shortest window loses run again alone under windows
# between; and the first 6 media of every porosity, with those where droplets paused 0.02 time
# units or longer before passing, run again with no rest test. Uses the default study's store ../paper_size/paper.db (made by ../paper_size/run.sh if it
# is missing, about 35 minutes) and makes rest_window_paper_W.db (not committed), about 30 minutes
# each on 2 cores; the reruns take about 10 minutes. Writes rest_window_paper*.csv.
#     bash results/stuck_test/rest_window_paper.sh
set -euo pipefail
cd "$(dirname "$0")"
BIN=${SOFTDROP:-../../build/softdrop}
[[ -f ../paper_size/paper.db ]] || SOFTDROP="$(realpath "$BIN")" bash ../paper_size/run.sh
for w in 0.01 0.005; do
  "$BIN" sweep --preset paper --rest-window "$w" --db "rest_window_paper_$w.db" --quiet > /dev/null
done
PYTHONPATH="$(dirname "$BIN")/python${PYTHONPATH:+:$PYTHONPATH}" OPENBLAS_NUM_THREADS=1 \
  /usr/bin/python3 rest_window_paper.py | tee rest_window_paper.txt
