"""Gathers results/tortuosities/json/ (one `softdrop tortuosity --format json` a medium; without
it, the media.csv it made) and fine.csv (fine.sh: the geometric T and diffusive tau of some media
at twice the pixels) into media.csv, points.csv (per porosity: the mean of each tortuosity over the media and its standard
error over them), fits.csv (each tortuosity's mean fitted to the paper's power law and to
1 - p ln(porosity), by `softdrop fit`), convergence_1000.csv (fine.sh's values' change from 1000 to
2000 pixels, per porosity), correlations.csv (medium by medium, how the droplet's <T>
goes with each pore-space tortuosity at one porosity) and tortuosities.png.

    python3 analyse.py DIR SOFTDROP
"""
import glob
import json
import math
import os
import subprocess
import sys
import tempfile

import numpy as np
import pandas as pd

here, softdrop = sys.argv[1], sys.argv[2]
QUANTITIES = ["geometric_tortuosity", "hydrodynamic_tortuosity", "diffusive_tortuosity", "droplet_tortuosity"]

rows, blocked = [], {}
for path in sorted(glob.glob(os.path.join(here, "json", "*.err"))):
    target = os.path.basename(path).split("-")[0]
    blocked[target] = blocked.get(target, 0) + 1
for path in sorted(glob.glob(os.path.join(here, "json", "*.json"))):
    target, seed = os.path.basename(path)[:-5].split("-")
    j = json.load(open(path))
    row = {"target_porosity": float(target), "medium_seed": int(seed), "porosity": j["medium"]["porosity"],
           "grains": j["medium"]["grains"]}
    for q in QUANTITIES[:3] + ["permeability"]:
        row[q] = j[q]["values"][1]  # at 500 pixels across, 16 a smallest radius
        row[q.replace("_tortuosity", "") + "_change"] = j[q]["change"]  # relative, from 250 pixels
        row[q.replace("_tortuosity", "") + "_pixels"] = 500
    d = j["droplet_tortuosity"]
    row.update(droplet_tortuosity=d["mean_tortuosity"], droplet_standard_error=d["standard_error"],
               droplet_passed=d["passed"], droplet_starts=d["starts"])
    rows.append(row)
if rows:
    media = pd.DataFrame(rows).sort_values(["target_porosity", "medium_seed"])
else:  # the study's json/ is not kept: start again from its table
    media = pd.read_csv(os.path.join(here, "media.csv"), float_precision="round_trip")
    blocked = pd.read_csv(os.path.join(here, "points.csv")).set_index("target_porosity")["blocked"]
    blocked = {f"{t:g}": int(n) for t, n in blocked.items()}
    for q in ("geometric", "hydrodynamic", "diffusive", "permeability"):
        if q + "_pixels" not in media:
            media[q + "_pixels"] = 500
# fine.sh's values at 1000 pixels across (checked against 2000) replace the geometric T and the
# diffusive tau of the media it solved.
fine_path = os.path.join(here, "fine.csv")
if os.path.exists(fine_path):
    fine = pd.read_csv(fine_path, float_precision="round_trip").set_index(["target_porosity", "medium_seed"])
    keys = pd.MultiIndex.from_frame(media[["target_porosity", "medium_seed"]])
    solved = keys.isin(fine.index)
    for q in ("geometric", "diffusive"):
        media.loc[solved, q + "_tortuosity"] = fine.loc[keys[solved], q + "_at_1000"].to_numpy()
        media.loc[solved, q + "_change"] = fine.loc[keys[solved], q + "_change_1000_to_2000"].to_numpy()
        media.loc[solved, q + "_pixels"] = 1000
    # Their convergence, per porosity: the change from 1000 to 2000 pixels across, medium by medium.
    summary = []
    for target, group in fine.reset_index().groupby("target_porosity"):
        for q in ("geometric", "diffusive"):
            change = group[q + "_change_1000_to_2000"]
            summary.append({"value": q, "target_porosity": target, "media": len(group),
                            "median_change_1000_to_2000": change.abs().median(),
                            "largest_change_1000_to_2000": change.abs().max(),
                            "mean_change_1000_to_2000": change.mean()})
    pd.DataFrame(summary).round(5).to_csv(os.path.join(here, "convergence_1000.csv"), index=False)
media.to_csv(os.path.join(here, "media.csv"), index=False)

points = []
for target, group in media.groupby("target_porosity"):
    p = {"target_porosity": target, "media": len(group), "blocked": blocked.get(f"{target:g}", 0),
         "porosity": group["porosity"].mean()}
    for q in QUANTITIES + ["permeability"]:
        values = group[q].dropna()
        p[q] = values.mean()
        p[q + "_standard_error"] = values.std(ddof=1) / math.sqrt(len(values)) if len(values) > 1 else float("nan")
    for q in ("geometric", "hydrodynamic", "diffusive", "permeability"):
        p[q + "_largest_change"] = group[q + "_change"].abs().max()
    p["droplet_passed_fraction"] = group["droplet_passed"].sum() / group["droplet_starts"].sum()
    points.append(p)
points = pd.DataFrame(points)
points.to_csv(os.path.join(here, "points.csv"), index=False)

# Each tortuosity's mean against porosity, fitted by the program's own fit (NLopt, weighted by the
# standard errors over media): the paper's form a - c phi^b and the flow papers' 1 - p ln(phi).
fits = []
for q in QUANTITIES:
    with tempfile.NamedTemporaryFile("w", suffix=".csv", delete=False) as f:
        f.write("porosity,tortuosity,standard_error\n")
        for _, r in points.iterrows():
            if np.isfinite(r[q]) and r[q + "_standard_error"] > 0:
                f.write(f"{r['porosity']!r},{r[q]!r},{r[q + '_standard_error']!r}\n")
    run = subprocess.run([softdrop, "fit", "--points", f.name, "--format", "json"], capture_output=True, text=True)
    os.unlink(f.name)
    if run.returncode != 0:  # too few points with an error (one medium a porosity)
        print(f"analyse: {q}: not fitted: {run.stderr.strip()}", file=sys.stderr)
        continue
    out = json.loads(run.stdout)
    power, log = out["power"], out["log"]
    fits.append({"quantity": q, "points": out["points"],
                 "a": power["a"]["value"], "b": power["b"]["value"], "c": power["c"]["value"],
                 "power_reduced_chi2": power["reduced_chi2"], "p": log["p"]["value"], "p_error": log["p"]["error"],
                 "log_reduced_chi2": log["reduced_chi2"], "preferred": out["preferred"],
                 "paper_reduced_chi2": out["paper"]["chi2"] / out["paper"]["dof"]})
pd.DataFrame(fits).to_csv(os.path.join(here, "fits.csv"), index=False)

# Medium by medium at one porosity: does a medium whose flow (or pore paths) wind more push its
# droplets along longer paths? Media where at least 10 droplets passed.
correlations = []
for target, group in list(media.groupby("target_porosity")) + [("all", media)]:
    g = group[group["droplet_passed"] >= 10]
    row = {"target_porosity": target, "media": len(g)}
    for q in QUANTITIES[:3] + ["permeability"]:
        row["r_" + q] = g["droplet_tortuosity"].corr(g[q]) if len(g) > 2 else float("nan")
    correlations.append(row)
pd.DataFrame(correlations).to_csv(os.path.join(here, "correlations.csv"), index=False)

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    sys.exit(0)
fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.6))
styles = {"geometric_tortuosity": ("geometric T", "tab:green"), "hydrodynamic_tortuosity": ("flow T", "tab:blue"),
          "diffusive_tortuosity": ("diffusive τ", "tab:purple"), "droplet_tortuosity": ("droplet ⟨T⟩", "black")}
grid = np.linspace(0.43, 0.97, 200)
for q, (label, colour) in styles.items():
    left.errorbar(points["porosity"], points[q], yerr=points[q + "_standard_error"], fmt="o", ms=4, capsize=2,
                  color=colour, label=label)
    for fit in (f for f in fits if f["quantity"] == q):
        left.plot(grid, 1 - fit["p"] * np.log(grid), color=colour, lw=0.8, ls=":")
left.plot(grid, 1.58 - 0.58 * grid ** 3.87, color="0.5", lw=2, alpha=0.6, label="paper: 1.58 − 0.58 φ^3.87")
left.set_xlabel("porosity φ")
left.set_ylabel("tortuosity")
left.legend(frameon=False, fontsize=8)
left.set_title("means over media; dotted: 1 − p ln φ fits", fontsize=9)
shown = media[media["droplet_passed"] >= 10]
dots = right.scatter(shown["hydrodynamic_tortuosity"], shown["droplet_tortuosity"], c=shown["porosity"], s=9,
                     cmap="viridis")
fig.colorbar(dots, ax=right, label="porosity φ")
right.set_xlabel("flow T of the medium")
right.set_ylabel("droplet ⟨T⟩ of the medium")
right.set_title("medium by medium (at least 10 droplets passed)", fontsize=9)
fig.tight_layout()
fig.savefig(os.path.join(here, "tortuosities.png"), dpi=110)
