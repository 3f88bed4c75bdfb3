#!/usr/bin/env bash
# The objectives compared on what a user means: the held-out value of each search's best.
#   bash results/search/objectives.sh ["SEEDS"] ["OBJECTIVE:GENERATIONS[:STRATEGY[:LAMBDA]] ..."]
# For each seed and run, a search of the program's default problem with that objective and
# strategy (default es; seed = medium seed), whose best gets its held-out value at the end (200 random
# starts, seed 1, at dt and dt/2), and its starting medium the same (at dt): a random medium of
# the problem. Then results/search/objectives/runs.csv and summary.csv. A search already in
# objectives/db/ is not run again.
set -euo pipefail
cd "$(dirname "$0")/../.."
S=${SOFTDROP:-./build/softdrop}
# The droplet calibrated for the exponential viscosity step (the defaults' <T>(phi) within 0.02),
# which these searches ran: pinned, so that they resume and reproduce to the bit.
DROPLET=(--config results/calibration/exponential.toml)
SEEDS=${1:-"1 2 3 4 5"}
RUNS=${2:-"mean:200 single:200 single:3600 mean:600"}
OUT=results/search/objectives
mkdir -p "$OUT/db"
for run in $RUNS; do
  IFS=: read -r objective generations strategy lambda <<< "$run"
  strategy=${strategy:-es}
  lambda=${lambda:-8}
  for seed in $SEEDS; do
    name="$OUT/db/default-$objective-$generations-$seed"
    [[ $strategy == es ]] || name+="-$strategy"
    [[ $lambda == 8 ]] || name+="$lambda"
    [[ -f $name.json ]] && continue
    echo "objectives: $objective, $generations generations, $strategy, seed $seed" >&2
    rm -f "$name.db" "$name.db-wal" "$name.db-shm"
    "$S" "${DROPLET[@]}" optimize --db "$name.db" --objective "$objective" --strategy "$strategy" --lambda "$lambda" --seed "$seed" \
      --medium-seed "$seed" --generations "$generations" --quiet --json "$name.json" > /dev/null
  done
done
for db in "$OUT"/db/*.db; do  # the starting media, held out as the bests are
  [[ -f ${db%.db}-start.json ]] || "$S" validate --db "$db" --run 1 --generation 0 --same-dt-only --quiet \
    --format json > "${db%.db}-start.json"
done
python3 - "$OUT" <<'PY'
import csv, glob, json, os, statistics, sys
out = sys.argv[1]
rows = []
for path in sorted(p for p in glob.glob(f"{out}/db/*.json") if not p.endswith("-start.json")):
    j = json.load(open(path))
    start = json.load(open(path[:-5] + "-start.json"))["at_dt"]
    _, objective, generations, seed = os.path.basename(path)[:-5].split("-")[:4]
    h = j["held_out"] or {}
    lam = round((j["evaluations"] - 1) / int(generations))  # generation 0 is one evaluation
    rows.append(dict(problem="default", objective=objective, strategy=j["strategy"], **{"lambda": lam},
                     generations=int(generations),
                     seed=int(seed), droplets=j["droplets"], start_held_out_t=start.get("mean_tortuosity", start.get("mean_t")),
                     start_held_out_passed=start["passed"], in_search_tortuosity=j["best_tortuosity"],
                     best_generation=j["best_generation"], held_out_tortuosity=h.get("mean_tortuosity", h.get("mean_t")),
                     held_out_standard_error=h.get("standard_error"), held_out_passed=h.get("passed"),
                     held_out_objective=h.get("objective_value"), half_dt_t=h.get("half_dt_mean_tortuosity", h.get("half_dt_mean_t")),
                     wall_seconds=round(j["wall_seconds"], 1)))
with open(f"{out}/runs.csv", "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0]))
    w.writeheader()
    w.writerows(rows)
groups = {}
for r in rows:
    groups.setdefault((r["objective"], r["generations"], r["strategy"], r["lambda"]), []).append(r)
with open(f"{out}/summary.csv", "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["objective", "generations", "strategy", "lambda", "seeds", "droplets", "median_start_held_out_t", "median_in_search_t",
                "median_held_out_t", "min_held_out_t", "max_held_out_t", "median_held_out_passed", "median_gap",
                "max_gap_in_se", "median_wall_seconds"])
    for (objective, generations, strategy, lam), rs in sorted(groups.items()):
        held = [r["held_out_tortuosity"] for r in rs]
        # The in-search value against its held-out counterpart: the objective over the held-out
        # starts (a robust objective), or the held-out <T> (single).
        ref = [r["held_out_objective"] if r["held_out_objective"] is not None else r["held_out_tortuosity"] for r in rs]
        gaps = [r["in_search_tortuosity"] - x for r, x in zip(rs, ref)]
        w.writerow([objective, generations, strategy, lam, len(rs), statistics.median(r["droplets"] for r in rs),
                    round(statistics.median(r["start_held_out_t"] for r in rs), 4),
                    round(statistics.median(r["in_search_tortuosity"] for r in rs), 4), round(statistics.median(held), 4),
                    round(min(held), 4), round(max(held), 4), statistics.median(r["held_out_passed"] for r in rs),
                    round(statistics.median(gaps), 4),
                    round(max(abs(g) / r["held_out_standard_error"] for g, r in zip(gaps, rs)), 1),
                    statistics.median(r["wall_seconds"] for r in rs)])
print(open(f"{out}/summary.csv").read(), end="")
PY
