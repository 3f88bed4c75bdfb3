#!/usr/bin/env bash
# Sets up, builds and runs the main job on defaults: a maximum-tortuosity search (200 generations
# of 8 candidates, the evolution strategy with relocation, on all cores) logged to the SQLite
# history results/run/history.db; then, in results/run/run-N/ for the search's run N (a run again
# adds a run and a folder, and keeps the earlier ones): its summary, the best-T curve (CSV and
# picture), the best medium (JSON, with the simulate config that replays its value) and its picture
# with droplets' paths. Extra arguments go to `softdrop optimize` (e.g. --generations 1000,
# --time-limit 600, --resume 1). SOFTDROP=path runs another build (and skips building this one).
set -euo pipefail
cd "$(dirname "$0")/.."
if [[ -z ${SOFTDROP:-} ]]; then
  echo "run.sh: building softdrop (a few minutes the first time; the log is build.log)" >&2
  SOFTDROP_TARGETS=softdrop bash scripts/build.sh > build.log 2>&1 || { tail -n 30 build.log; echo "run.sh: the build failed; see build.log" >&2; exit 1; }
fi
S=${SOFTDROP:-./build/softdrop}
mkdir -p results/run
"$S" optimize --db results/run/history.db --generations 200 --json results/run/summary.json "$@"
run=$(sed -n 's/^ *"run": \([0-9]*\),$/\1/p' results/run/summary.json)
out=results/run/run-$run
mkdir -p "$out"
mv results/run/summary.json "$out/summary.json"
"$S" history --db results/run/history.db --run "$run" --best --format csv > "$out/best_curve.csv"
"$S" export --db results/run/history.db --run "$run" -o "$out/best_medium.json" \
  --simulate-config "$out/best_simulate.toml"
"$S" render search --db results/run/history.db --run "$run" -o "$out/best.png" --curve "$out/best_curve.png"
echo "history: results/run/history.db (run $run); in $out/: summary.json, best_curve.csv and best_curve.png," \
     "best_medium.json, best.png (the best medium with droplets' paths through it); its droplets again:" \
     "softdrop simulate --config $out/best_simulate.toml"
