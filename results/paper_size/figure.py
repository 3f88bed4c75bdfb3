"""The paper-size study's figure: <T>(phi) by both averagings with the paper's f and our fit, and
below it each point's distance from the paper's f in its own standard errors (over media).
Reads points.csv and fit.json, writes t_phi.png. Run by run.sh; needs python3-matplotlib and
python3-pandas.
    python3 results/paper_size/figure.py"""
import json
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

here = os.path.dirname(os.path.abspath(__file__))
points = pd.read_csv(os.path.join(here, "points.csv"))
with open(os.path.join(here, "fit.json")) as f:
    fit = json.load(f)["power"]


def paper(phi):
    return 1.58 - 0.58 * np.asarray(phi) ** 3.87


def ours(phi):
    return fit["a"]["value"] - fit["c"]["value"] * np.asarray(phi) ** fit["b"]["value"]


def quoted(name):  # a value at its error's precision: two significant digits of the error
    value, error = fit[name]["value"], fit[name]["error"]
    places = max(0, 1 - int(np.floor(np.log10(error))))
    return f"{name} = {value:.{places}f} ± {error:.{places}f}"


fig, (top, low) = plt.subplots(2, 1, sharex=True, figsize=(6.4, 6.0), gridspec_kw={"height_ratios": [3, 1.3]})
grid = np.linspace(0.42, 0.92, 200)
top.plot(grid, paper(grid), color="0.5", lw=2, label="paper: 1.58 − 0.58 φ^3.87")
top.plot(grid, ours(grid), color="tab:red", lw=1.2,
         label="ours (pooled): " + ", ".join(quoted(k) for k in ("a", "b", "c")))
series = (("mean_tortuosity", "media_standard_error", "o", "black", "pooled over droplets", -0.004),
          ("per_medium_tortuosity", "per_medium_standard_error", "s", "tab:blue", "per medium first", +0.004))
for mean, error, marker, colour, label, shift in series:
    phi, t, se = points["porosity"], points[mean], points[error]
    top.errorbar(phi + shift, t, yerr=se, fmt=marker, ms=4, color=colour, capsize=2, label=f"⟨T⟩ {label}")
    low.plot(phi + shift, (t - paper(phi)) / se, marker, ms=4, color=colour)
top.set_ylabel("tortuosity ⟨T⟩")
top.legend(loc="lower left", frameon=False, fontsize=8)
low.axhspan(-2, 2, color="0.92")
low.axhline(0, color="0.5", lw=1)
low.set_ylabel("(⟨T⟩ − f) / SE")
low.set_xlabel("porosity φ")
fig.tight_layout()
fig.savefig(os.path.join(here, "t_phi.png"), dpi=150)
