#!/usr/bin/env bash
# Sets up, builds and runs the main job on defaults: a maximum-tortuosity search (200 generations
# of 8 candidates, the evolution strategy with relocation, on all cores) logged to the SQLite
# history results/run/history.db, then the best-T curve and the best configuration exported next
# to it. Extra arguments go to `softdrop optimize` (e.g. --generations 1000, --time-limit 600,
# --resume 1).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh > build.log 2>&1 || { cat build.log; exit 1; }
mkdir -p results/run
./build/softdrop optimize --db results/run/history.db --generations 200 \
  --json results/run/summary.json "$@"
run=$(sed -n 's/^ *"run": \([0-9]*\),$/\1/p' results/run/summary.json)
./build/softdrop history --db results/run/history.db --run "$run" --best --format csv > results/run/best_curve.csv
./build/softdrop export --db results/run/history.db --run "$run" -o results/run/best_medium.json \
  --simulate-config results/run/best_simulate.toml
echo "history: results/run/history.db (run $run); best-T curve: results/run/best_curve.csv;" \
     "best medium: results/run/best_medium.json (softdrop simulate --config results/run/best_simulate.toml)"
