"""stuck.png: the stuck fraction of the grid (grid.csv, run.sh) against the shaking's peak
acceleration over gravity, Gamma = A (2 pi f)^2 / |g| (top), and against its peak velocity over
the speed of a fall through the droplet's radius, V = 2 pi f A / sqrt(2 |g| R) (bottom); one panel
per porosity, a line per frequency, the unshaken value dashed. tortuosity.png: <T> of the droplets
that passed, the same way."""
import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import pandas as pd
from matplotlib.ticker import NullFormatter, ScalarFormatter

GRAVITY, RADIUS = 5.0e5, 8.0  # the default droplet's |g| and R
grid = pd.read_csv("grid.csv")
grid["velocity"] = 2 * math.pi * grid["frequency"] * grid["amplitude"] / math.sqrt(2 * GRAVITY * RADIUS)
porosities = sorted(grid["target_porosity"].unique())
for column, error, label, name in [("stuck_fraction", "stuck_fraction_se", "stuck fraction", "stuck.png"),
                                   ("mean_tortuosity", "mean_tortuosity_se", "⟨T⟩ of the passed droplets",
                                    "tortuosity.png")]:
    fig, axes = plt.subplots(2, len(porosities), figsize=(4 * len(porosities), 6.4), sharey=True)
    for row, (x, xlabel) in enumerate([("gamma", "Γ = A (2πf)² / |g|"), ("velocity", "V = 2πfA / √(2|g|R)")]):
        for ax, phi in zip(axes[row], porosities):
            at = grid[grid["target_porosity"] == phi]
            still = at[at["amplitude"] == 0].iloc[0]
            ax.axhline(still[column], color="0.4", ls="--", lw=1, label="no shaking")
            for f, g in at[at["amplitude"] > 0].groupby("frequency"):
                ax.errorbar(g[x], g[column], yerr=g[error], marker="o", ms=4, capsize=2, label=f"f = {f:g}")
            ax.set_xscale("log")
            if column == "mean_tortuosity":
                ax.set_yscale("log")
                ax.set_yticks([1.5, 2, 3, 5, 10])
                ax.yaxis.set_major_formatter(ScalarFormatter())
                ax.yaxis.set_minor_formatter(NullFormatter())
            ax.set_title(f"φ = {phi:g}")
            ax.set_xlabel(xlabel)
        axes[row][0].set_ylabel(label)
    axes[0][-1].legend(frameon=False, fontsize=8)
    fig.tight_layout()
    fig.savefig(name, dpi=150)
