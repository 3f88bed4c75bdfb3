"""Draws curves.png and curves_seconds.png from curves.csv: for every problem (a panel, three to a
row) the median best T over seeds against evaluations (curves.png) or wall seconds
(curves_seconds.png), one line a strategy, with the band from the least to the largest seed.
Where some seeds' searches went further than the others, each goes on as a thin line of its own.
A strategy NAME+rN (with relocation) is drawn solid, NAME alone dashed, in NAME's colour; restarts
(NAME+rN+oK) dash-dotted.

    python3 results/search/plot.py results/search/curves.csv results/search/curves.png
    (curves_seconds.png is written beside curves.png)
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

COLOURS = {"paper": "#4d4d4d", "es": "#d62728", "lahc": "#1f77b4", "anneal": "#2ca02c"}
PROBLEMS = ["default", "dense", "large", "fine", "fine60", "small"]


def band(runs, column, grid):
    """Median, least and largest best T over the runs at each x of grid (NaN where none reached x)."""
    values = np.full((len(runs), grid.size), np.nan)
    for k, run in enumerate(runs):
        x = run[column].to_numpy()
        t = run["best_tortuosity"].to_numpy()
        at = np.searchsorted(x, grid, side="right") - 1  # the last generation at or before x
        ok = (at >= 0) & (grid <= x[-1])
        values[k, ok] = t[at[ok]]
    reached = ~np.all(np.isnan(values), axis=0)
    out = np.full((3, grid.size), np.nan)
    out[0, reached] = np.nanmedian(values[:, reached], axis=0)
    out[1, reached] = np.nanmin(values[:, reached], axis=0)
    out[2, reached] = np.nanmax(values[:, reached], axis=0)
    return out


def draw(curves, problems, column, label, png):
    """One panel a problem, three to a row, best T against `column`."""
    across = min(3, len(problems))
    down = -(-len(problems) // across)
    fig, axes = plt.subplots(down, across, figsize=(4.3 * across, 3.4 * down), squeeze=False)
    for k, problem in enumerate(problems):
        ax = axes[k // across][k % across]
        of_problem = curves[curves.problem == problem]
        for strategy in sorted(set(of_problem.strategy)):
            runs = [r.sort_values("generation") for _, r in of_problem[of_problem.strategy == strategy].groupby("seed")]
            base = strategy.split("+")[0]
            line = "-." if "+o" in strategy else "-" if "+r" in strategy else "--"
            style = dict(color=COLOURS.get(base, "#9467bd"), linestyle=line)
            top = max(r[column].iloc[-1] for r in runs)
            grid = np.linspace(0, top, 400)
            median, least, largest = band(runs, column, grid)
            # The median only where every seed counts; a search that went further goes on alone.
            common = grid <= min(r[column].iloc[-1] for r in runs)
            ax.plot(grid[common], median[common], label=f"{strategy} ({len(runs)})", linewidth=1.4, **style)
            ax.fill_between(grid[common], least[common], largest[common], color=style["color"], alpha=0.08,
                            linewidth=0)
            for r in runs:
                beyond = r[r[column] >= grid[common][-1]]
                if len(beyond) > 1:
                    ax.step(beyond[column], beyond["best_tortuosity"], where="post", linewidth=0.7, **style)
        ax.set_xlabel(label)
        ax.set_ylabel("best T")
        ax.set_title(problem, fontsize=10)
        ax.axhline(2.42, color="#999999", linewidth=0.8, linestyle=":")
        ax.grid(alpha=0.3)
        ax.legend(fontsize=6.5, loc="lower right", title="strategy (seeds)", title_fontsize=6.5)
    for k in range(len(problems), down * across):
        axes[k // across][k % across].axis("off")
    fig.suptitle(f"Best T found against {label}: median over seeds, band from the least to the largest seed "
                 "(dotted: the paper's 2.42)", fontsize=10)
    fig.tight_layout()
    fig.savefig(png, dpi=110)


def main(csv, png):
    curves = pd.read_csv(csv, float_precision="round_trip")
    problems = [p for p in PROBLEMS if p in set(curves.problem)]
    problems += sorted(set(curves.problem) - set(problems))
    draw(curves, problems, "evaluations", "evaluations", png)
    root, ext = png.rsplit(".", 1)
    draw(curves, problems, "seconds", "wall seconds", f"{root}_seconds.{ext}")


if __name__ == "__main__":
    if len(sys.argv) != 3:
        sys.exit("usage: plot.py CURVES_CSV OUTPUT_PNG")
    main(sys.argv[1], sys.argv[2])
