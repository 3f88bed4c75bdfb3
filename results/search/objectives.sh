#!/usr/bin/env bash
# The objectives compared on what a user means: the held-out value of each search's best.
#   [PROBLEM=forty] bash results/search/objectives.sh ["SEEDS"] ["OBJECTIVE:GENERATIONS[:STRATEGY[:LAMBDA]] ..."]
# For each seed and run, a search of the problem with that objective and strategy (default es;
# seed = medium seed), whose best gets its held-out value at the end (200 random starts, seed 1,
# at dt and dt/2), and its starting medium the same (at dt): a random medium of the problem. Then
# results/search/objectives/runs.csv, summary.csv and paired.csv (each search against the default
# search of its seed), held_out.png (objectives_plot.py), and
# pictures of the bests with 50 droplets' paths (PROBLEM-OBJECTIVE-best-paths.png). A search already in objectives/db/ is not run again;
# the rows of runs.csv whose database is not there are kept.
# The problems:
#   default: the program's default problem (20 non-overlapping grains of radii 16-48 in the 500 x
#            500 periodic box) with the droplet calibrated for the exponential viscosity step,
#            pinned so that these searches resume and reproduce to the bit;
#   forty:   40 grains of radii 12-32 in the same box, with the program's default droplet.
set -euo pipefail
shopt -s nullglob
cd "$(dirname "$0")/../.."
S=${SOFTDROP:-./build/softdrop}
PROBLEM=${PROBLEM:-default}
case $PROBLEM in
  default) SETUP=(--config results/calibration/exponential.toml); MEDIUM=() ;;
  forty) SETUP=(); MEDIUM=(--grains 40 --r-min 12 --r-max 32) ;;
  *) echo "objectives.sh: PROBLEM = $PROBLEM: must be default or forty" >&2; exit 2 ;;
esac
SEEDS=${1:-"1 2 3 4 5"}
RUNS=${2:-"mean:200 single:200 single:3600 mean:600"}
OUT=results/search/objectives
mkdir -p "$OUT/db"
for run in $RUNS; do
  IFS=: read -r objective generations strategy lambda <<< "$run"
  strategy=${strategy:-es}
  lambda=${lambda:-8}
  for seed in $SEEDS; do
    name="$OUT/db/$PROBLEM-$objective-$generations-$seed"
    [[ $strategy == es ]] || name+="-$strategy"
    [[ $lambda == 8 ]] || name+="$lambda"
    [[ -f $name.json ]] && continue
    echo "objectives: $PROBLEM, $objective, $generations generations, $strategy, seed $seed" >&2
    rm -f "$name.db" "$name.db-wal" "$name.db-shm"
    "$S" "${SETUP[@]}" optimize --db "$name.db" --objective "$objective" --strategy "$strategy" --lambda "$lambda" \
      --seed "$seed" --medium-seed "$seed" "${MEDIUM[@]}" --generations "$generations" --quiet --json "$name.json" > /dev/null
  done
done
for db in "$OUT"/db/*.db; do  # the starting media, held out as the bests are
  [[ -f ${db%.db}-start.json ]] || "$S" validate --db "$db" --run 1 --generation 0 --same-dt-only --quiet \
    --format json > "${db%.db}-start.json"
done
python3 - "$OUT" <<'PY'
import csv, glob, json, os, re, statistics, sys
out = sys.argv[1]
rows = []
for path in sorted(p for p in glob.glob(f"{out}/db/*.json") if not p.endswith("-start.json")):
    j = json.load(open(path))
    start = json.load(open(path[:-5] + "-start.json"))["at_dt"]
    problem, objective, generations, seed = re.match(r"([a-z0-9]+)-([a-z-]+)-(\d+)-(\d+)", os.path.basename(path)).groups()
    h = j["held_out"] or {}
    assert objective == "single" or j["starts"] == 16, f"{path}: K = {j['starts']}; the error of the gap below takes K = 16"
    lam = round((j["evaluations"] - 1) / int(generations))  # generation 0 is one evaluation
    rows.append(dict(problem=problem, objective=objective, strategy=j["strategy"], **{"lambda": lam},
                     generations=int(generations),
                     seed=int(seed), droplets=j["droplets"], start_held_out_t=start.get("mean_tortuosity", start.get("mean_t")),
                     start_held_out_passed=start["passed"], in_search_tortuosity=j["best_tortuosity"],
                     best_generation=j["best_generation"], held_out_tortuosity=h.get("mean_tortuosity", h.get("mean_t")),
                     held_out_standard_error=h.get("standard_error"), held_out_passed=h.get("passed"),
                     held_out_objective=h.get("objective_value"), half_dt_t=h.get("half_dt_mean_tortuosity", h.get("half_dt_mean_t")),
                     wall_seconds=round(j["wall_seconds"], 1)))
# A search whose database is not in db/ keeps its committed row.
key = lambda r: tuple(str(r[k]) for k in ("problem", "objective", "strategy", "lambda", "generations", "seed"))
ran = {key(r) for r in rows}
if os.path.exists(f"{out}/runs.csv"):
    for r in csv.DictReader(open(f"{out}/runs.csv")):
        if key(r) not in ran:
            rows.append({k: (None if v == "" else v) for k, v in r.items() if k not in ("start_stuck_as_1", "held_out_stuck_as_1", "in_search_reruns",
                                                                     "gap_in_se_of_difference")})
num = lambda v: None if v is None else float(v)
for r in rows:
    for k in ("lambda", "generations", "seed", "droplets", "start_held_out_passed", "best_generation", "held_out_passed"):
        r[k] = None if r[k] is None else int(float(r[k]))
    for k in ("start_held_out_t", "in_search_tortuosity", "held_out_tortuosity", "held_out_standard_error",
              "held_out_objective", "half_dt_t", "wall_seconds"):
        r[k] = num(r[k])
# The default objective's value of the starting medium and of each best over the held-out starts,
# whatever the search's objective: <T> with a droplet that did not pass counted as T = 1.
STARTS = 200
stuck_as_1 = lambda t, passed: None if passed is None else ((t or 0) * passed + (STARTS - passed)) / STARTS
for r in rows:
    r["start_stuck_as_1"] = stuck_as_1(r["start_held_out_t"], r["start_held_out_passed"])
    r["held_out_stuck_as_1"] = stuck_as_1(r["held_out_tortuosity"], r["held_out_passed"])
# How far the in-search value may stray from the held-out one by chance alone: the standard error
# of their difference, from the held-out droplets' spread (the spread of one droplet's value: T of
# a passed droplet, with T = 1 for one that did not pass under the mean objective).
#  - single: the in-search value is one droplet's T.
#  - mean: a robust search runs its best again on each later generation's fresh starts, and its
#    in-search value is then the mean of those re-runs (the value it won with is dropped): K
#    droplets a re-run. A best kept in the last generation has no re-run: its value is the one it
#    won with among the candidates, which chance favours (the winner's curse).
#  - quantile and lower-bound: no simple standard error; left empty.
# A search's K starts are stratified over the box's width; the held-out starts are not. Treating
# both as independent droplets overstates the in-search error a little, if anything.
K = 16  # every search here runs the default --starts
for r in rows:
    r["in_search_reruns"] = r["generations"] - r["best_generation"] if r["objective"] != "single" else None
    r["gap_in_se_of_difference"] = None
    n, se, t = r["held_out_passed"], r["held_out_standard_error"], r["held_out_tortuosity"]
    if None in (n, se, t) or n < 2 or r["objective"] not in ("mean", "single"):
        continue
    spread_t = se * se * n  # the variance of a passed droplet's T
    if r["objective"] == "single":
        one, ref, droplets_in = spread_t, t, 1
    else:
        p = n / STARTS
        one = p * spread_t + p * (1 - p) * (t - 1) ** 2
        ref, droplets_in = r["held_out_objective"], K * max(1, r["in_search_reruns"])
    held_var = spread_t / n if r["objective"] == "single" else one / STARTS
    r["gap_in_se_of_difference"] = round((r["in_search_tortuosity"] - ref) / (one / droplets_in + held_var) ** 0.5, 2)
rows.sort(key=lambda r: (r["problem"], r["objective"], r["strategy"], r["lambda"], r["generations"], r["seed"]))
with open(f"{out}/runs.csv", "w", newline="") as f:
    w = csv.DictWriter(f, fieldnames=list(rows[0]))
    w.writeheader()
    w.writerows(rows)
groups = {}
def max_abs(values):
    known = [abs(v) for v in values if v is not None]
    return round(max(known), 1) if len(known) == len(values) else None
for r in rows:
    groups.setdefault((r["problem"], r["objective"], r["generations"], r["strategy"], r["lambda"]), []).append(r)
with open(f"{out}/summary.csv", "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["problem", "objective", "generations", "strategy", "lambda", "seeds", "droplets", "median_start_held_out_t", "median_in_search_t",
                "median_held_out_t", "min_held_out_t", "max_held_out_t", "median_held_out_passed",
                "median_start_stuck_as_1", "median_held_out_stuck_as_1", "min_held_out_stuck_as_1",
                "max_held_out_stuck_as_1", "median_gap",
                "max_gap_in_se", "max_gap_in_se_of_difference", "kept_in_last_generation", "median_wall_seconds"])
    for (problem, objective, generations, strategy, lam), rs in sorted(groups.items()):
        held = [r["held_out_tortuosity"] for r in rs]
        # The in-search value against its held-out counterpart: the objective over the held-out
        # starts (a robust objective), or the held-out <T> (single).
        ref = [r["held_out_objective"] if r["held_out_objective"] is not None else r["held_out_tortuosity"] for r in rs]
        gaps = [r["in_search_tortuosity"] - x for r, x in zip(rs, ref)]
        w.writerow([problem, objective, generations, strategy, lam, len(rs), statistics.median(r["droplets"] for r in rs),
                    round(statistics.median(r["start_held_out_t"] for r in rs), 4),
                    round(statistics.median(r["in_search_tortuosity"] for r in rs), 4), round(statistics.median(held), 4),
                    round(min(held), 4), round(max(held), 4), statistics.median(r["held_out_passed"] for r in rs),
                    round(statistics.median(r["start_stuck_as_1"] for r in rs), 4),
                    round(statistics.median(r["held_out_stuck_as_1"] for r in rs), 4),
                    round(min(r["held_out_stuck_as_1"] for r in rs), 4), round(max(r["held_out_stuck_as_1"] for r in rs), 4),
                    round(statistics.median(gaps), 4),
                    round(max(abs(g) / r["held_out_standard_error"] for g, r in zip(gaps, rs)), 1),
                    max_abs([r["gap_in_se_of_difference"] for r in rs]),
                    sum(r["in_search_reruns"] == 0 for r in rs),
                    statistics.median(r["wall_seconds"] for r in rs)])
print(open(f"{out}/summary.csv").read(), end="")
# Each search against the default search (mean, es, lambda 8, 200 generations) of the same problem
# and seed, which starts from the same medium: the held-out value with stuck droplets as T = 1.
default = {(r["problem"], r["seed"]): r["held_out_stuck_as_1"] for r in rows
           if (r["objective"], r["strategy"], r["lambda"], r["generations"]) == ("mean", "es", 8, 200)}
with open(f"{out}/paired.csv", "w", newline="") as f:
    w = csv.writer(f)
    w.writerow(["problem", "objective", "generations", "strategy", "lambda", "seeds", "mean_difference",
                "standard_error", "seeds_higher"])
    for (problem, objective, generations, strategy, lam), rs in sorted(groups.items()):
        d = [r["held_out_stuck_as_1"] - default[(problem, r["seed"])] for r in rs
             if (problem, r["seed"]) in default and r["held_out_stuck_as_1"] is not None]
        if len(d) < 2 or (objective, strategy, lam, generations) == ("mean", "es", 8, 200):
            continue
        w.writerow([problem, objective, generations, strategy, lam, len(d), round(statistics.mean(d), 4),
                    round(statistics.stdev(d) / len(d) ** 0.5, 4), sum(x > 0 for x in d)])
print(open(f"{out}/paired.csv").read(), end="")
PY
/usr/bin/python3 results/search/objectives_plot.py "$OUT/runs.csv" "$OUT/held_out.png"
# The problem's best arrangement of the default objective (the seed with the highest held-out value)
# and of the paper's (the highest in-search T, as that objective ranks them), each with the paths
# of 50 droplets from random starts (seed 2: not the held-out starts), the droplet the search ran.
for objective in mean single; do
  best=$(python3 - "$OUT" "$PROBLEM" "$objective" <<'PY'
import glob, json, sys
out, problem, objective = sys.argv[1:]
runs = [(p, json.load(open(p))) for p in glob.glob(f"{out}/db/{problem}-{objective}-200-*.json")
        if not p.endswith("-start.json") and p.count("-") == out.count("-") + 3]
key = (lambda j: (j["held_out"] or {}).get("objective_value") or 0) if objective == "mean" else (lambda j: j["best_tortuosity"])
print(max(runs, key=lambda r: key(r[1]))[0][:-5] if runs else "")
PY
)
  [[ -n $best ]] || continue
  picture="$OUT/$PROBLEM-$objective-best-paths.png"
  [[ -f $picture ]] && continue
  tmp=$(mktemp -d)
  "$S" export --db "$best.db" --run 1 -o "$tmp/best.json" --simulate-config "$tmp/best.toml" 2> /dev/null
  grep -v -E '^(x0|droplets|seed) =' "$tmp/best.toml" > "$tmp/paths.toml"
  "$S" --config "$tmp/paths.toml" render paths --droplets 50 --seed 2 --quiet -o "$picture"
  echo "objectives: $picture: $(basename "$best")" >&2
  rm -r "$tmp"
done
