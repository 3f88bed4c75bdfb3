"""Draws objectives/held_out.png from objectives/runs.csv: for each problem (a column), the held-out
value of the searches' bests, as the default objective scores a medium (<T> over 200 random starts
no search used, a droplet that did not pass counted as T = 1), against the droplet runs the search
spent (top) and its wall seconds (bottom). A point is the median over the seeds of one objective,
strategy, lambda and length (moved sideways by a few per cent so that those of one budget do not
hide each other), its bar the least to the largest seed; the grey band is the starting media's
(random media of the problem), median and range.

    python3 results/search/objectives_plot.py results/search/objectives/runs.csv results/search/objectives/held_out.png
"""
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import pandas as pd  # noqa: E402

MARKERS = {"single": "v", "mean": "o", "quantile": "s", "lower-bound": "D"}
COLOURS = {"es": "#d62728", "paper": "#4d4d4d", "lahc": "#1f77b4", "anneal": "#2ca02c", "cmaes": "#9467bd"}
TITLES = {"default": "default: 20 grains of radii 16-48,\nthe calibrated droplet (exponential step)",
          "forty": "forty: 40 grains of radii 12-32,\nthe default droplet"}


def main(csv, out):
    runs = pd.read_csv(csv)
    problems = [p for p in TITLES if p in set(runs["problem"])]
    fig, axes = plt.subplots(2, len(problems), figsize=(6.2 * len(problems), 8.4), squeeze=False, sharey="col")
    for col, problem in enumerate(problems):
        of = runs[runs["problem"] == problem]
        start = of.drop_duplicates("seed")["start_stuck_as_1"]
        for row, (x, label) in enumerate([("droplets", "droplet runs of the search"), ("wall_seconds", "wall seconds")]):
            ax = axes[row][col]
            ax.axhspan(start.min(), start.max(), color="0.9", zorder=0)
            ax.axhline(start.median(), color="0.6", lw=1, zorder=1, label="starting media (median, range)")
            for k, ((objective, strategy, lam, generations), g) in enumerate(of.groupby(
                    ["objective", "strategy", "lambda", "generations"])):
                y = g["held_out_stuck_as_1"]
                xm = g[x].median() * 1.04 ** (k - 4)  # spread apart the searches of one budget
                ax.errorbar([xm], [y.median()], yerr=[[y.median() - y.min()], [y.max() - y.median()]],
                            fmt=MARKERS.get(objective, "o"), color=COLOURS.get(strategy, "k"), ms=7, capsize=3,
                            label=f"{objective}, {strategy}, λ {lam}, {generations} gen. ({len(g)} seeds)")
            ax.set_xscale("log")
            ax.set_xlabel(label)
            ax.grid(alpha=0.3)
            if col == 0:
                ax.set_ylabel("held-out <T>, stuck as T = 1")
            if row == 0:
                ax.set_title(TITLES[problem], fontsize=10)
                ax.legend(fontsize=7, loc="upper left", framealpha=0.9)
    fig.suptitle("The searches' bests on 200 held-out starts: median and range over the seeds", fontsize=11)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2])
