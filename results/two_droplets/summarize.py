"""Tables of the two-droplet study (run.sh), from the run's CSVs in DIR:

    summarize.py DIR    writes pairs.csv, area.csv and area_example.csv here

pairs.csv, one row per porosity: how often the rings met, whether the second followed the first
(the grains both touched over the grains either touched, and T2 - T1), and what the second did to
the first and the first to the second, each pair compared with the same start run alone.
area.csv: Delta S = S / S0 of each droplet inside the medium (S0 its area at rest above it), at
phi = 0.79, by order and by whether its pair met. area_example.csv: S / S0 and the centre's y
against time since the first droplet began, for the first pair in contact, for figure.py.
"""
import glob
import math
import os
import sys

import pandas as pd

HEIGHT = 500.0  # the media's height (the simulate default)


def mean_se(s):
    s = s.dropna()
    n = len(s)
    if n == 0:
        return float("nan"), float("nan"), 0
    return s.mean(), (s.std(ddof=1) / math.sqrt(n) if n > 1 else float("nan")), n


def load(folder, kind, phi):
    frames = []
    for path in sorted(glob.glob(os.path.join(folder, f"{kind}_{phi}_[0-9]*.csv"))):
        d = pd.read_csv(path)
        d["medium"] = int(os.path.basename(path)[:-4].split("_")[-1])
        frames.append(d)
    return pd.concat(frames, ignore_index=True)


def pairs_table(folder):
    rows = []
    for phi in ["0.79", "0.79half", "0.79after20", "0.79after80", "0.5", "0.6", "0.7"]:
        pairs = load(folder, "pairs", phi)
        alone = load(folder, "alone", phi)[["medium", "droplet", "outcome", "tortuosity", "steps"]]
        first = pairs[pairs["order"] == 1].set_index(["medium", "droplet"])
        second = pairs[pairs["order"] == 2].set_index(["medium", "droplet"])
        alone = alone.set_index(["medium", "droplet"])
        d = first.join(second, rsuffix="_2").join(alone, rsuffix="_alone")
        n = len(d)
        # A second droplet whose start the first never cleared (stuck just below it) has no row.
        released = d["outcome_2"].notna()
        met = d["contact_steps"] > 0
        # Identical droplets from one start that never meet run the same path to the bit: a check
        # of the pairs that did not meet (both droplets against the alone run). A droplet held
        # (found stuck while the other moved) runs on where the alone run ended, so its steps
        # differ; its outcome is the same unless it crept free in the extra time.
        passed_alone = d["outcome_alone"] == "passed"
        same = (released & (~met) & (d["outcome"] == d["outcome_alone"]) & (d["outcome_2"] == d["outcome_alone"]) &
                (~passed_alone | ((d["steps"] == d["steps_alone"]) & (d["steps_2"] == d["steps_alone"]) &
                                  (d["tortuosity"] == d["tortuosity_alone"]))))
        union = d["touched"] + d["touched_2"] - d["shared_touched"]
        jaccard = (d["shared_touched"] / union).where(union > 0)
        both = (d["outcome"] == "passed") & (d["outcome_2"] == "passed")
        dt = (d["tortuosity_2"] - d["tortuosity"]).where(both & met)
        alone_stuck = d["outcome_alone"] == "stuck"
        held = d["held_at"].notna()
        row = {
            "porosity": float(phi[:4].rstrip("ahf")),
            "kind": "non-overlapping" if phi.startswith("0.79") else "overlapping",
            "dt": 3e-6 if phi.endswith("half") else 6e-6,
            "second_after": int(phi.split("after")[1]) if "after" in phi else 40,
            "pairs": n,
            "released": released.mean(),
            "met": met.mean(),
            "unmet_same_as_alone": int(same.sum()),
            "unmet": int((released & ~met).sum()),
            "alone_stuck": alone_stuck.mean(),
            "first_stuck": (d["outcome"] == "stuck").mean(),
            "second_stuck": (d["outcome_2"] == "stuck").mean(),
            "first_held": held.mean(),
            # Among the pairs that met: a first droplet stuck alone that passed with the second
            # behind it; one that passes alone, stuck with the second behind it; and a second
            # droplet stuck where the same start alone passes (held back by the first).
            "freed": (met & alone_stuck & (d["outcome"] == "passed")).sum(),
            "stopped": (met & passed_alone & (d["outcome"] == "stuck")).sum(),
            "clogged": (met & passed_alone & (d["outcome_2"] == "stuck")).sum(),
            # As shares: of the first droplets stuck alone, and of the starts that pass alone.
            "freed_share": (met & alone_stuck & (d["outcome"] == "passed")).sum() / max(1, alone_stuck.sum()),
            "clogged_share": (met & passed_alone & (d["outcome_2"] == "stuck")).sum() / max(1, passed_alone.sum()),
            # A held first droplet that never met the second and passed: freed by the extra time.
            "freed_unmet": ((~met) & alone_stuck & (d["outcome"] == "passed")).sum(),
            "both_stuck": ((d["outcome"] == "stuck") & (d["outcome_2"] == "stuck")).mean(),
        }
        for name, s in [("alone", d["tortuosity_alone"]), ("first", d["tortuosity"]), ("second", d["tortuosity_2"])]:
            m, se, k = mean_se(s)
            row[f"mean_tortuosity_{name}"], row[f"standard_error_{name}"] = m, se
        m, se, k = mean_se(dt)
        row["met_tortuosity_difference"], row["met_tortuosity_difference_error"], row["met_both_passed"] = m, se, k
        m, se, _ = mean_se(dt.abs())
        row["met_abs_tortuosity_difference"] = m
        # What the second did to the first's T: the first against its own start alone.
        pushed = (d["tortuosity"] - d["tortuosity_alone"]).where(met & (d["outcome"] == "passed") & passed_alone)
        m, se, k = mean_se(pushed)
        row["met_first_tortuosity_change"], row["met_first_tortuosity_change_error"] = m, se
        # What the first did to the second's T: the second against the same start alone (the
        # second alone would have run the first's alone run, to the bit).
        followed = (d["tortuosity_2"] - d["tortuosity_alone"]).where(met & (d["outcome_2"] == "passed") & passed_alone)
        m, se, k = mean_se(followed)
        row["met_second_tortuosity_change"], row["met_second_tortuosity_change_error"] = m, se
        row["met_shared_fraction"] = mean_se(jaccard.where(met))[0]
        row["unmet_shared_fraction"] = mean_se(jaccard.where(~met))[0]
        rows.append(row)
    return pd.DataFrame(rows)


def area_tables(folder):
    rows, example = [], None
    for path in sorted(glob.glob(os.path.join(folder, "trace_*.csv"))):
        m = os.path.basename(path)[:-4].split("_")[1]
        trace = pd.read_csv(path)
        paths = pd.read_csv(os.path.join(folder, f"paths_{m}.csv"))
        runs = pd.read_csv(os.path.join(folder, f"traced_{m}.csv"))
        t = trace.merge(paths, on=["droplet", "order", "time"])
        t["ratio"] = t["area"] / t.groupby(["droplet", "order"])["area"].transform("first")
        met = runs.groupby("droplet")["contact_steps"].first() > 0
        inside = t[(t["y"] >= 0) & (t["y"] < HEIGHT)]
        for (droplet, order), g in inside.groupby(["droplet", "order"]):
            rows.append({"medium": int(m), "droplet": droplet, "order": order, "met": bool(met[droplet]),
                         "min_ratio": g["ratio"].min(), "max_ratio": g["ratio"].max()})
        if example is None and met.any():
            k = met[met].index[0]
            released_at = runs[runs["droplet"] == k]["released_at"].iloc[0]
            example = t[t["droplet"] == k][["order", "time", "ratio", "y"]].assign(medium=int(m), droplet=k)
            # On the first droplet's clock: the second's own time plus its release.
            example["time"] = example["time"] + (example["order"] == 2) * released_at
    per = pd.DataFrame(rows)
    table = []
    for (order, met), g in per.groupby(["order", "met"]):
        table.append({"order": order, "met": met, "droplets": len(g),
                      "mean_min_area_ratio": g["min_ratio"].mean(), "mean_max_area_ratio": g["max_ratio"].mean(),
                      "lowest_area_ratio": g["min_ratio"].min(), "highest_area_ratio": g["max_ratio"].max(),
                      "swelled": (g["max_ratio"] > 1.0).mean(), "shrank": (g["min_ratio"] < 1.0).mean()})
    return pd.DataFrame(table), example


def main():
    folder = sys.argv[1]
    pairs_table(folder).to_csv("pairs.csv", index=False, float_format="%.4g")
    area, example = area_tables(folder)
    area.to_csv("area.csv", index=False, float_format="%.4g")
    example.to_csv("area_example.csv", index=False, float_format="%.6g")


if __name__ == "__main__":
    main()
