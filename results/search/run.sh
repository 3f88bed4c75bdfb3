#!/usr/bin/env bash
# The strategies compared: best T against evaluations and wall seconds, for every strategy, over
# seeds, on several problems. Each search is one database under results/search/db/ (not committed);
# running the script again resumes every search to the budget given, so a long comparison can be
# run in parts. Writes curves.csv (problem, strategy, seed, generation, evaluations, seconds,
# best_tortuosity), summary.csv (per problem and strategy: the median, least and largest best T over the
# seeds after 750, 3 000, 5 000, 8 000 and 20 000 evaluations, for the seeds that got that far) and
# curves.png and curves_seconds.png (every search's best T against evaluations, and wall seconds).
#   bash results/search/run.sh [EVALUATIONS [SEEDS [PROBLEMS [STRATEGIES]]]]
#   e.g. bash results/search/run.sh 20000 "1 2 3 4 5" default "paper es lahc anneal es+r3"
#        bash results/search/run.sh 3000 "1 2 3" calibrated "paper es lahc anneal paper+r3 es+r3"
#        bash results/search/run.sh report   (no search: the tables and the plot from the databases)
# A strategy NAME+rN is NAME with --relocate-every N; NAME alone has --relocate-every 0. A further
# +oK makes it K restarts: K islands that never migrate, each from a starting medium of its own
# (--islands K --migrate-every 0 --island-starts own), sharing the evaluations.
set -euo pipefail
cd "$(dirname "$0")/../.."
S=${SOFTDROP:-./build/softdrop}
EVALUATIONS=${1:-2000}
SEEDS=${2:-"1 2 3"}
PROBLEMS=${3:-"default dense large"}
STRATEGIES=${4:-"paper es lahc anneal"}
OUT=results/search
mkdir -p "$OUT/db"

# Every problem but `calibrated` runs the balloon (results/calibration/balloon.toml) on grains of
# its size; `calibrated` is the program's default problem with the droplet calibrated for the
# exponential viscosity step (results/calibration/exponential.toml: the defaults' <T>(phi) within
# 0.02), which these searches ran, pinned so that they resume and reproduce to the bit.
BALLOON="--config results/calibration/balloon.toml"
problem_options() {
  case $1 in
    calibrated) echo "--config results/calibration/exponential.toml" ;;  # 20 grains of radii 16-48 in 500 x 500, phi ~ 0.72
    *) echo "$BALLOON $(balloon_problem_options "$1")" ;;
  esac
}
balloon_problem_options() {
  case $1 in
    default) echo "--grains 60 --width 300 --height 300" ;;            # phi ~ 0.735
    # more, smaller grains (radii 6-11; 100 of radii 8-16 leave phi ~ 0.56, where no start passes)
    dense) echo "--grains 100 --width 300 --height 300 --r-min 6 --r-max 11" ;;  # phi ~ 0.76
    large) echo "--grains 150 --width 500 --height 500" ;;             # phi ~ 0.72
    # grains of the droplet's radius: the ones it rolls along down shallow slopes (see README)
    fine) echo "--grains 100 --width 300 --height 300 --r-min 8 --r-max 8" ;;  # phi ~ 0.78
    # as fine, with fewer grains in the way of a ramp
    fine60) echo "--grains 60 --width 300 --height 300 --r-min 8 --r-max 8" ;;  # phi ~ 0.87
    # half the default box's height and width, grains about the droplet's size: a ramp down the
    # whole height needs about 20 grains here, against about 40 in the default box (see README)
    small) echo "--grains 20 --width 150 --height 150 --r-min 6 --r-max 10" ;;  # phi ~ 0.82
    *) echo "unknown problem '$1'" >&2; exit 2 ;;
  esac
}
# Candidates per generation: the paper's hill climb speculates ahead on every thread with 2; the
# others evaluate a whole generation at once, so they get enough candidates for every lane.
lambda_of() { case ${1%%+*} in paper) echo 2 ;; *) echo 8 ;; esac; }
restarts_of() { if [[ $1 =~ \+o([0-9]+) ]]; then echo "${BASH_REMATCH[1]}"; else echo 1; fi; }
strategy_options() {
  local name=${1%%+*} relocate=0  # said outright: optimize relocates every third generation by default
  [[ $1 =~ \+r([0-9]+) ]] && relocate=${BASH_REMATCH[1]}
  echo "--strategy $name --relocate-every $relocate"
  local k; k=$(restarts_of "$1")
  (( k > 1 )) && echo "--islands $k --migrate-every 0 --island-starts own"
  return 0
}

for problem in $PROBLEMS; do
  [[ $EVALUATIONS == report ]] && break  # only the tables and the plot, from the searches there are
  for strategy in $STRATEGIES; do
    for seed in $SEEDS; do
      db="$OUT/db/$problem-$strategy-$seed.db"
      lambda=$(lambda_of "$strategy")
      per=$(( lambda * $(restarts_of "$strategy") ))  # evaluations a generation, over the restarts
      generations=$(( (EVALUATIONS + per - 1) / per ))
      echo "search: $problem $strategy seed $seed: $EVALUATIONS evaluations" >&2
      if [[ -f $db ]]; then
        $S optimize --db "$db" --resume 1 --generations "$generations" --quiet > /dev/null
      else
        # shellcheck disable=SC2046
        $S optimize --db "$db" $(problem_options "$problem") $(strategy_options "$strategy") --lambda "$lambda" \
          --seed "$seed" --medium-seed "$seed" --generations "$generations" --quiet > /dev/null
      fi
    done
  done
done

# A search whose database is not here (the databases are not committed) keeps its rows of the
# committed curves.csv; a database here replaces its search's rows.
have=$(cd "$OUT/db" && for db in *.db; do [[ -f $db ]] && echo "${db%.db}"; done | tr '\n' ' ')
kept=$(mktemp)
trap 'rm -f "$kept"' EXIT
[[ -f $OUT/curves.csv ]] && awk -F, -v have="$have" '
  BEGIN { n = split(have, names, " "); for (i = 1; i <= n; i++) here[names[i]] = 1 }
  NR > 1 && !(($1 "-" $2 "-" $3) in here)' "$OUT/curves.csv" > "$kept"
echo "problem,strategy,seed,generation,evaluations,seconds,best_tortuosity" > "$OUT/curves.csv"
cat "$kept" >> "$OUT/curves.csv"
for db in "$OUT"/db/*.db; do
  [[ -f $db ]] || continue
  name=$(basename "$db" .db); IFS=- read -r problem strategy seed <<< "$name"
  # Restarts (islands, one run each) count the evaluations of them all and the best of them all;
  # they run side by side, so a generation's wall seconds are its slowest island's.
  sqlite3 -csv "$db" "SELECT '$problem', '$strategy', $seed, g.generation,
                             count(*) * (1 + g.generation * (SELECT lambda FROM runs WHERE id = 1)),
                             sum(max(g.seconds)) OVER (ORDER BY g.generation), max(g.best_t)
                      FROM generations g GROUP BY g.generation ORDER BY g.generation" >> "$OUT/curves.csv"
done

# Best T at fixed budgets, over the seeds whose search got that far (searches of several budgets
# can share the folder).
sqlite3 :memory: <<SQL > "$OUT/summary.csv"
.mode csv
.import $OUT/curves.csv curves
.headers on
WITH checkpoints(e) AS (VALUES (750), (3000), (5000), (8000), (20000)),
reached AS (SELECT problem, strategy, seed, max(CAST(evaluations AS INTEGER)) AS last FROM curves
            GROUP BY problem, strategy, seed),
at AS (  -- best T of each search once it had spent e evaluations
  SELECT c.problem, c.strategy, c.seed, k.e, max(CAST(c.best_tortuosity AS REAL)) AS t, max(CAST(c.seconds AS REAL)) AS s
  FROM curves c JOIN reached r ON r.problem = c.problem AND r.strategy = c.strategy AND r.seed = c.seed
  JOIN checkpoints k ON CAST(c.evaluations AS INTEGER) <= k.e AND r.last >= k.e
  GROUP BY c.problem, c.strategy, c.seed, k.e),
ranked AS (SELECT *, row_number() OVER (PARTITION BY problem, strategy, e ORDER BY t) AS r,
                  count(*) OVER (PARTITION BY problem, strategy, e) AS n FROM at)
SELECT problem, strategy, e AS evaluations, n AS seeds,
       round(avg(CASE WHEN r IN ((n + 1) / 2, (n + 2) / 2) THEN t END), 4) AS median_best_t,
       round(min(t), 4) AS least, round(max(t), 4) AS largest, round(avg(s), 1) AS mean_seconds
FROM ranked GROUP BY problem, strategy, e ORDER BY problem, e, median_best_t DESC;
SQL
cat "$OUT/summary.csv"
# shellcheck disable=SC2046
/usr/bin/python3 "$OUT/plot.py" "$OUT/curves.csv" "$OUT/curves.png"
