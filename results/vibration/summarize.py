"""Tables of the vibration study (run.sh): each shaken sweep's droplets paired one by one with the
same droplets unshaken (the same media, starts and bits until the shaking begins).

    summarize.py grid|confirm DIR   one row per setting and porosity, from DIR/<kind>_<A>_<f>_<axis>.db
    summarize.py gentlest grid.csv PHI  the amplitude and frequency of the least peak velocity
                                        (2 pi f A) that halves the stuck fraction at PHI
    summarize.py fewest grid.csv PHI    the amplitude and frequency with the fewest stuck at PHI
    summarize.py route DIR          T against the route's T, from DIR/route_<phi>_<seed>_<A>_<f>.csv
"""
import glob
import math
import os
import sqlite3
import sys

import pandas as pd

GRAVITY = 5.0e5  # |g| of the default droplet (length / time^2)


def droplets(path):
    with sqlite3.connect(path) as db:
        d = pd.read_sql("SELECT porosity_index, medium_index, droplet, outcome, tortuosity, steps "
                        "FROM sweep_droplets_view", db)
        m = pd.read_sql("SELECT porosity_index, medium_index, target_porosity, porosity FROM sweep_media_view", db)
    return d.merge(m, on=["porosity_index", "medium_index"])


def over_media(g, column):
    """Mean of column over the media's own means, and its standard error (media as clusters)."""
    per = g.groupby("medium_index")[column].mean().dropna()
    se = per.std(ddof=1) / math.sqrt(len(per)) if len(per) > 1 else float("nan")
    return per.mean(), se


def table(kind, folder):
    ref = droplets(os.path.join(folder, f"{kind}_0_0_x.db"))
    rows = []
    for path in sorted(glob.glob(os.path.join(folder, f"{kind}_*.db"))):
        _, a, f, axis = os.path.basename(path)[:-3].split("_")
        a, f = float(a), float(f)
        d = ref.merge(droplets(path), on=["porosity_index", "medium_index", "droplet"], suffixes=("_0", ""))
        for _, g in d.groupby("porosity_index"):
            passed = g["outcome"] == "passed"
            stuck0 = g["outcome_0"] == "stuck"
            freed = passed & (g["outcome_0"] != "passed")
            both = passed & (g["outcome_0"] == "passed")
            g = g.assign(stuck=(g["outcome"] == "stuck").astype(float), stuck_0=stuck0.astype(float),
                         t=g["tortuosity"].where(passed))
            stuck, stuck_se = over_media(g, "stuck")
            stuck_0, _ = over_media(g, "stuck_0")
            t, t_se = over_media(g, "t")
            rows.append({
                "amplitude": a, "frequency": f, "axis": axis if a > 0 else "",
                "gamma": round(a * (2 * math.pi * f) ** 2 / GRAVITY, 3),
                "target_porosity": g["target_porosity"].iloc[0], "porosity": round(g["porosity"].mean(), 4),
                "media": g["medium_index"].nunique(), "droplets": len(g),
                "passed": int(passed.sum()), "stuck": int((g["outcome"] == "stuck").sum()),
                "stuck_unshaken": int(stuck0.sum()),
                "stuck_fraction": round(stuck, 4), "stuck_fraction_se": round(stuck_se, 4),
                "stuck_ratio": round(stuck / stuck_0, 3) if stuck_0 > 0 else float("nan"),
                "freed": int(freed.sum()),
                "mean_tortuosity": round(t, 4), "mean_tortuosity_se": round(t_se, 4),
                "freed_mean_tortuosity": round(g["tortuosity"][freed].mean(), 4) if freed.any() else float("nan"),
                "unshaken_passed_changed": int((g["tortuosity"][both] != g["tortuosity_0"][both]).sum()),
                "steps_ratio": round(g["steps"].sum() / g["steps_0"].sum(), 3),
            })
    return pd.DataFrame(rows).sort_values(["frequency", "amplitude", "axis", "target_porosity"])


def route(folder):
    """Per setting and porosity: T and the route's T of the droplets the shaking freed, and of all
    that passed, each droplet paired with itself unshaken (route_<phi>_<seed>_0_0.csv)."""
    rows = []
    names = [os.path.basename(p)[:-4].split("_") for p in glob.glob(os.path.join(folder, "route_*.csv"))]
    settings = sorted({(n[3], n[4]) for n in names if n[3] != "0"}, key=lambda s: (float(s[0]), float(s[1])))
    for a, f in settings:
        for phi in sorted({n[1] for n in names}, key=float):
            runs = []
            for seed in sorted({n[2] for n in names if n[1] == phi}):
                still = pd.read_csv(os.path.join(folder, f"route_{phi}_{seed}_0_0.csv"))
                shaken = pd.read_csv(os.path.join(folder, f"route_{phi}_{seed}_{a}_{f}.csv"))
                runs.append(still.merge(shaken, on="droplet", suffixes=("_0", "")).assign(seed=seed))
            d = pd.concat(runs)
            passed = d["outcome"] == "passed"
            freed = passed & (d["outcome_0"] != "passed")
            unshaken = passed & d["shaken_at"].isna()
            rows.append({
                "amplitude": float(a), "frequency": float(f), "target_porosity": float(phi),
                "media": d["seed"].nunique(), "droplets": len(d),
                "passed_unshaken": int((d["outcome_0"] == "passed").sum()), "passed": int(passed.sum()),
                "freed": int(freed.sum()),
                "mean_tortuosity_unshaken": round(d["tortuosity_0"].mean(), 4),
                "mean_tortuosity": round(d["tortuosity"][passed].mean(), 4),
                "mean_route_tortuosity": round(d["route_tortuosity"][passed].mean(), 4),
                "freed_mean_tortuosity": round(d["tortuosity"][freed].mean(), 4),
                "freed_mean_route_tortuosity": round(d["route_tortuosity"][freed].mean(), 4),
                "freed_route_tortuosity_se": round(d["route_tortuosity"][freed].std(ddof=1) / math.sqrt(freed.sum()), 4),
                "never_shaken_passed": int(unshaken.sum()),
                "never_shaken_changed": int((d["tortuosity"][unshaken] != d["tortuosity_0"][unshaken]).sum()),
            })
    return pd.DataFrame(rows)


if __name__ == "__main__":
    if sys.argv[1] in ("gentlest", "fewest"):
        grid = pd.read_csv(sys.argv[2])
        at = grid[(grid["target_porosity"] == float(sys.argv[3])) & (grid["amplitude"] > 0)]
        at = at.assign(velocity=at["amplitude"] * at["frequency"])
        if sys.argv[1] == "gentlest":
            pick = at[at["stuck_ratio"] <= 0.5].sort_values(["velocity", "amplitude"]).iloc[0]
        else:
            pick = at.sort_values(["stuck_fraction", "velocity"]).iloc[0]
        print(f"{pick['amplitude']:g} {pick['frequency']:g}")
    elif sys.argv[1] == "route":
        route(sys.argv[2]).to_csv(sys.stdout, index=False)
    else:
        table(sys.argv[1], sys.argv[2]).to_csv(sys.stdout, index=False)
