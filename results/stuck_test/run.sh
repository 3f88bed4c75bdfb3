#!/usr/bin/env bash
# Which stuck test is safe: the same droplets (same media, same starts) run with the reference test
# and with shorter windows, and every verdict and tortuosity compared. Writes runs.csv (one row a
# droplet and setting) and summary.csv (one row a setting: verdicts changed against the reference,
# steps spent). Usage: bash results/stuck_test/run.sh [THREADS [SETTING...]]   (needs ./build/softdrop)
set -euo pipefail
cd "$(dirname "$0")/../.."
# Measured with the balloon (results/calibration/balloon.toml), whose search default the rest test is.
S="${SOFTDROP:-./build/softdrop} --config results/calibration/balloon.toml"
THREADS=${1:-0}
OUT=results/stuck_test
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
# setting name and its exit options; the first is the reference: the stuck test alone, as softdrop
# had it (0.5 time units, 5 length units). The w... settings shorten the stuck test; the r...
# settings keep it and add a rest test (window in time units, distance in length units).
SETTINGS=("reference|--stuck-window 0.5 --stuck-distance 5 --rest-window 0"
          "w0.2|--stuck-window 0.2 --stuck-distance 2 --rest-window 0"
          "w0.1|--stuck-window 0.1 --stuck-distance 1 --rest-window 0"
          "w0.05|--stuck-window 0.05 --stuck-distance 0.5 --rest-window 0"
          "r0.1/0.5|--stuck-window 0.5 --stuck-distance 5 --rest-window 0.1 --rest-distance 0.5"
          "r0.05/0.25|--stuck-window 0.5 --stuck-distance 5 --rest-window 0.05 --rest-distance 0.25"
          "r0.05/0.1|--stuck-window 0.5 --stuck-distance 5 --rest-window 0.05 --rest-distance 0.1"
          "r0.02/0.05|--stuck-window 0.5 --stuck-distance 5 --rest-window 0.02 --rest-distance 0.05")
# Settings to run: all, or those named after THREADS (their rows of runs.csv are replaced).
ONLY=("${@:2}")
selected() { ((${#ONLY[@]} == 0)) || printf '%s\n' "${ONLY[@]}" | grep -qxF "$1"; }
# scenes: name, extra options (the sweep's 500 x 500 boxes at five porosities, both kinds, and the
# search's default problem: 300 x 300, non-overlapping, phi about 0.735)
SCENES=()
for phi in 0.6 0.7 0.75 0.8 0.9; do
  for kind in overlapping non-overlapping; do SCENES+=("$kind-$phi|--kind $kind --porosity $phi"); done
done
SCENES+=("search-problem|--kind non-overlapping --porosity 0.735 --width 300 --height 300")
if ((${#ONLY[@]})) && [[ -f $OUT/runs.csv ]]; then
  for name in "${ONLY[@]}"; do grep -v "^$name," "$OUT/runs.csv" > "$TMP/keep.csv" || true; cp "$TMP/keep.csv" "$OUT/runs.csv"; done
else
  echo "setting,scene,medium_seed,droplet,start_x,outcome,tortuosity,steps" > "$OUT/runs.csv"
fi
n=0; for setting in "${SETTINGS[@]}"; do selected "${setting%%|*}" && n=$((n + 1)); done
total=$(( n * ${#SCENES[@]} * 10 )); done_=0; t0=$(date +%s)
for setting in "${SETTINGS[@]}"; do
  name=${setting%%|*}; exit_options=${setting#*|}
  selected "$name" || continue
  for scene in "${SCENES[@]}"; do
    label=${scene%%|*}; options=${scene#*|}
    for seed in 1 2 3 4 5 6 7 8 9 10; do
      # shellcheck disable=SC2086
      $S simulate $options --medium-seed "$seed" --seed "$seed" --droplets 50 --threads "$THREADS" \
        $exit_options --runs "$TMP/r.csv" > /dev/null 2>&1
      tail -n +2 "$TMP/r.csv" | cut -d, -f1-5 | sed "s|^|$name,$label,$seed,|" >> "$OUT/runs.csv"
      done_=$((done_ + 1)); el=$(( $(date +%s) - t0 ))
      printf '\rstuck test: %d/%d runs of 50 droplets, ETA %d s ' "$done_" "$total" $(( el * (total - done_) / done_ )) >&2
    done
  done
done
echo >&2
sqlite3 :memory: <<SQL > "$OUT/summary.csv"
.mode csv
.import $OUT/runs.csv runs
.headers on
WITH d AS (SELECT * FROM runs WHERE setting = 'reference')
SELECT r.setting,
       count(*) AS droplets,
       sum(r.outcome = 'passed') AS passed,
       sum(r.outcome = 'stuck') AS stuck,
       sum(r.outcome != d.outcome) AS verdicts_changed,
       sum(d.outcome = 'passed' AND r.outcome != 'passed') AS passed_now_stuck,
       sum(d.outcome = 'passed' AND r.outcome = 'passed' AND r.tortuosity != d.tortuosity) AS t_changed,
       sum(CAST(r.steps AS INTEGER)) AS steps,
       round(1.0 * sum(CAST(r.steps AS INTEGER)) / (SELECT sum(CAST(steps AS INTEGER)) FROM d), 4) AS steps_vs_reference
FROM runs r JOIN d USING (scene, medium_seed, droplet)
GROUP BY r.setting ORDER BY steps DESC;
SQL
cat "$OUT/summary.csv"
