#!/usr/bin/env bash
# Islands against one long search at the same total number of evaluations: K islands of E / K
# evaluations each (a migration every M generations) against one search of E, on the default
# problem (60 grains, 300 x 300), for each seed. The searches resume, so the comparison can be run
# in parts; databases under results/islands/db/ (not committed). Writes curves.csv (setup, seed,
# evaluations: all islands' together, best_tortuosity: the best of all islands), summary.csv (median,
# least and largest best T over the seeds at fixed budgets) and curves.png.
#   bash results/islands/run.sh [EVALUATIONS [SEEDS [K [M [STRATEGY]]]]]
#   e.g. bash results/islands/run.sh 6000 "1 2 3" 4 25 es+r3
#        bash results/islands/run.sh report
set -euo pipefail
cd "$(dirname "$0")/../.."
S=${SOFTDROP:-./build/softdrop}
EVALUATIONS=${1:-6000}
SEEDS=${2:-"1 2 3"}
K=${3:-4}
M=${4:-25}
STRATEGY=${5:-es+r3}
OUT=results/islands
mkdir -p "$OUT/db"
LAMBDA=8
name=${STRATEGY%%+*}
relocate=""
[[ $STRATEGY == *+r* ]] && relocate="--relocate-every ${STRATEGY##*+r}"
# The balloon (results/calibration/balloon.toml) on its default problem.
common="--config results/calibration/balloon.toml --grains 60 --width 300 --height 300 --strategy $name $relocate --lambda $LAMBDA --quiet"

if [[ $EVALUATIONS != report ]]; then
  for seed in $SEEDS; do
    # one search of E evaluations; K islands of E / K each (migrations count none)
    for setup in one islands; do
      db="$OUT/db/$setup-$STRATEGY-$seed.db"
      if [[ $setup == one ]]; then
        generations=$(( (EVALUATIONS + LAMBDA - 1) / LAMBDA )); extra=""
      else
        per=$(( (EVALUATIONS / K + LAMBDA - 1) / LAMBDA )); generations=$(( per + per / (M - 1) )); extra="--islands $K --migrate-every $M"
      fi
      echo "islands: $setup, seed $seed: $EVALUATIONS evaluations" >&2
      if [[ -f $db ]]; then
        $S optimize --db "$db" --resume 1 --generations "$generations" --quiet > /dev/null
      else
        # shellcheck disable=SC2086
        $S optimize --db "$db" $common $extra --seed "$seed" --medium-seed "$seed" --generations "$generations" > /dev/null
      fi
    done
  done
fi

PYTHONPATH=build/python /usr/bin/python3 - "$OUT" "$STRATEGY" "$K" "$M" <<'PY'
import glob, os, sys
import pandas as pd
import softdrop

out, strategy, k, m = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
rows = []
for path in sorted(glob.glob(f"{out}/db/*-{strategy}-*.db")):
    setup, seed = os.path.basename(path).split("-")[0], int(path.rsplit("-", 1)[1][:-3])
    h = softdrop.read_history(path, arrangements=False)
    g = h["generations"].merge(h["candidates"].groupby(["run", "generation"]).size().rename("n").reset_index())
    g["evaluations"] = g["n"].where(g["kind"] != "migrate", 0)
    # all islands together, generation by generation: evaluations summed, the best of the bests
    # (generation 0 is evaluated once and shared by the islands)
    per = g.groupby("generation").agg(evaluations=("evaluations", "sum"), best_tortuosity=("best_tortuosity", "max")).reset_index()
    per.loc[per.generation == 0, "evaluations"] = 1
    per["evaluations"] = per["evaluations"].cumsum()
    for r in per.itertuples():
        rows.append({"setup": f"{k} islands" if setup == "islands" else "one search", "seed": seed,
                     "evaluations": int(r.evaluations), "best_tortuosity": r.best_tortuosity})
curves = pd.DataFrame(rows)
curves.to_csv(f"{out}/curves.csv", index=False)
summary = []
for budget in (1500, 3000, 6000, 12000):
    for setup, c in curves.groupby("setup"):
        at = [s[s.evaluations <= budget].best_tortuosity.max() for _, s in c.groupby("seed") if s.evaluations.max() >= budget]
        if at:
            summary.append({"setup": setup, "evaluations": budget, "seeds": len(at), "median_best_t": pd.Series(at).median(),
                            "least": min(at), "largest": max(at)})
pd.DataFrame(summary).to_csv(f"{out}/summary.csv", index=False)
print(pd.DataFrame(summary).to_string(index=False))
try:
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4))
    for (setup, seed), c in curves.groupby(["setup", "seed"]):
        ax.step(c.evaluations, c.best_tortuosity, where="post", color="crimson" if setup != "one search" else "0.3",
                alpha=0.8, label=setup if seed == curves.seed.min() else None)
    ax.set_xlabel("evaluations (all islands together)"), ax.set_ylabel("best T")
    ax.set_title(f"{k} islands (migration every {m} generations) against one search, {strategy}, λ = 8")
    ax.legend()
    fig.tight_layout()
    fig.savefig(f"{out}/curves.png", dpi=120)
except ImportError:
    pass
PY
