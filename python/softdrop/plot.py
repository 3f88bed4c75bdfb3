"""Pictures of media, droplets' paths, searches and studies, with matplotlib (optional: Debian
python3-matplotlib).

Every function draws into `ax` when given one, or into a new figure, and returns the Figure, as
PoreSpy's and Optuna's plotting functions do:

    import softdrop, softdrop.plot
    m = softdrop.Medium.generate("non-overlapping", porosity=0.8, seed=1)
    runs = [softdrop.simulate(m, x0=x, path=True) for x in (100, 250, 400)]
    softdrop.plot.paths(m, runs).savefig("paths.png")
    softdrop.plot.best_curve("search.db", run=1)
    softdrop.plot.porosity(softdrop.read_sweep("sweep.db")["points"])

Lengths are the model's units, y up, as the program's own pictures (`softdrop render`) draw them.
"""
import numpy as np

# The paper's least-squares fit of T against porosity (Matyka, Fig. 5): f(phi) = a - c phi^b.
PAPER_FIT = {"a": 1.58, "b": 3.87, "c": 0.58}


def paper_fit(phi):
    """The paper's fit of T against porosity at `phi` (a number or an array)."""
    return PAPER_FIT["a"] - PAPER_FIT["c"] * np.asarray(phi, dtype=float) ** PAPER_FIT["b"]


def _axes(ax):
    if ax is not None:
        return ax
    import matplotlib.pyplot as plt

    return plt.figure().add_subplot()


def _grain_copies(medium):
    """(x, y, r, index) of every grain and, in a periodic box, of its copy across the side it
    crosses, so that the picture shows what the droplet meets."""
    grains = np.asarray(medium.grains)
    out = []
    for i, (x, y, r) in enumerate(grains):
        out.append((x, y, r, i))
        if medium.periodic:
            if x - r < 0:
                out.append((x + medium.width, y, r, i))
            if x + r > medium.width:
                out.append((x - medium.width, y, r, i))
    return out


def medium(m, ax=None, touched=(), color="0.55", touched_color="0.25", shares=None):
    """The grains of medium `m` in its box (periodic copies included); grains whose indices are in
    `touched` are drawn in `touched_color`. `shares`, one number from 0 to 1 a grain (say, the
    share of many droplets that touched it), shades each grain between `color` and
    `touched_color` as `softdrop render search` does: the least share above 0 still shows, and 0
    leaves the grain plain. Returns the Figure."""
    from matplotlib.colors import to_rgba
    from matplotlib.patches import Circle, Rectangle

    ax = _axes(ax)
    n = len(np.asarray(m.grains))
    weight = np.zeros(n)
    if shares is not None:
        s = np.asarray(shares, dtype=float)
        if s.shape != (n,):
            raise ValueError(f"shares: one number for each of the {n} grains, not an array of shape {s.shape}")
        if not np.all((s >= 0) & (s <= 1)):
            raise ValueError("shares: each must be in [0, 1]")
        weight = np.where(s > 0, 0.15 + 0.85 * s, 0.0)
    for i in touched:
        weight[int(i)] = 1.0
    plain, dark = np.array(to_rgba(color)), np.array(to_rgba(touched_color))
    for x, y, r, i in _grain_copies(m):
        face = tuple((1 - weight[i]) * plain + weight[i] * dark)
        ax.add_patch(Circle((x, y), r, facecolor=face, edgecolor="none"))
    ax.add_patch(Rectangle((0, 0), m.width, m.height, fill=False, edgecolor="black", linewidth=0.8))
    ax.set_xlim(0, m.width)
    ax.set_ylim(0, m.height)
    ax.set_aspect("equal")
    ax.set_xlabel("x")
    ax.set_ylabel("y")
    return ax.figure


def _xy(path):
    """x and y columns of a path: rows of x, y (every path softdrop gives)."""
    p = np.asarray(path, dtype=float)
    if p.ndim != 2 or p.shape[1] != 2:
        raise ValueError(f"path: rows of (x, y) expected, not an array of shape {p.shape}")
    return p[:, 0], p[:, 1]


def _pieces(x, y, width):
    """A periodic path cut where it wraps across the side (a jump of more than half the box)."""
    cuts = np.nonzero(np.abs(np.diff(x)) > 0.5 * width)[0] + 1
    return zip(np.split(x, cuts), np.split(y, cuts))


def paths(m, runs, ax=None, color="tab:blue", linewidth=0.8, alpha=0.7, shade=True):
    """Medium `m` with the centre-of-mass paths of `runs`: results of simulate(..., path=True),
    or path arrays (rows of x, y). A path that wraps across a periodic side is drawn
    in pieces. With `shade`, each grain is shaded by the share of the results that touched it
    (medium's `shares`; path arrays carry no touched grains). Returns the Figure."""
    ax = _axes(ax)
    results = [run for run in runs if isinstance(run, dict) and "touched_grains" in run]
    shares = None
    if shade and results:
        counts = np.zeros(len(np.asarray(m.grains)))
        for run in results:
            counts[np.asarray(run["touched_grains"], dtype=int)] += 1
        shares = counts / len(results)
    medium(m, ax=ax, shares=shares)
    for run in runs:
        path = run["path"] if isinstance(run, dict) else run
        x, y = _xy(path)
        for px, py in _pieces(x, y, m.width) if m.periodic else [(x, y)]:
            ax.plot(px, py, color=color, linewidth=linewidth, alpha=alpha)
    return ax.figure


def best_curve(history, run=1, ax=None):
    """A search's best T against generation, as `softdrop render search --curve` draws it: the
    in-search value of each arrangement kept (read_history's `best`, the rows of `softdrop history
    --best`: the single objective's T, or a robust objective's mean of its re-runs where its tenure
    ended), as steps to the last generation; with a robust objective also each generation's re-run
    of the arrangement it stood on (parent_tortuosity, grey dots); and every held-out value stored
    (validations) with its standard error. `history` is read_history's frames or a database path.
    Returns the Figure."""
    if not isinstance(history, dict):
        from . import read_history

        history = read_history(history, arrangements=False)
    g = history["generations"]
    g = g[g["run"] == run]
    if g.empty:
        raise ValueError(f"run = {run}: no such run in the history")
    best = history["best"]
    best = best[best["run"] == run]
    robust = best["re_runs"].notna().any()
    ax = _axes(ax)
    x = np.append(best["generation"].to_numpy(), g["generation"].max())  # flat to the last generation
    y = np.append(best["best_tortuosity"].to_numpy(), best["best_tortuosity"].iloc[-1])
    ax.step(x, y, where="post", color="black",
            label="in the search (the mean of its re-runs)" if robust else "in the search (x0 = W/2)")
    if "parent_tortuosity" in g and g["parent_tortuosity"].notna().any():
        ax.plot(g["generation"], g["parent_tortuosity"], ".", color="0.6", markersize=2, label="re-run on fresh starts")
    v = history.get("validations")
    if v is not None and not v.empty:
        v = v[v["run"] == run]
        ax.errorbar(v["generation"], v["mean_tortuosity"], yerr=v["standard_error"], fmt="o", color="tab:red",
                    label="held out: ⟨T⟩ over random starts")
    ax.set_xlabel("generation")
    ax.set_ylabel("tortuosity T of the best")
    ax.legend(loc="best", frameon=False)
    return ax.figure


def porosity(points, ax=None, paper=True, mean="mean_tortuosity", error="media_standard_error", residuals=False,
             label="softdrop"):
    """<T> against porosity: read_sweep's `points` with error bars, and the paper's fit
    (paper=True). `mean` is the column of <T> (mean_tortuosity, pooled over the droplets;
    per_medium_tortuosity, each medium's first) and `error` its error (media_standard_error, the
    media as clusters, or standard_error over droplets; per_medium_standard_error goes with
    per_medium_tortuosity). A table of other columns (a points file read by pandas, say) may name
    its own, beside its porosity column.

    residuals=True adds a panel below with (<T> - f(phi)) / error against the paper's f, with the
    band of +-2; it needs a new figure (ax=None). Returns the Figure."""
    for column in ("porosity", mean, error):
        if column not in points:
            raise ValueError(f"points: no column {column!r} (columns: {', '.join(map(str, points.columns))})")
    phi, t, se = (np.asarray(points[c], dtype=float) for c in ("porosity", mean, error))
    if residuals:
        if ax is not None:
            raise ValueError("residuals=True draws two panels of a new figure: leave ax out")
        import matplotlib.pyplot as plt

        fig, (ax, low) = plt.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": [3, 1]})
    ax = _axes(ax)
    ax.errorbar(phi, t, yerr=se, fmt="o", color="black", capsize=2, label=label)
    if paper or residuals:
        grid = np.linspace(min(np.nanmin(phi), 0.4), 1.0, 200)
        ax.plot(grid, paper_fit(grid), color="tab:red", label="paper's fit 1.58 − 0.58 φ^3.87")
    ax.set_ylabel("⟨T⟩")
    ax.legend(loc="best", frameon=False)
    if not residuals:
        ax.set_xlabel("porosity φ")
        return ax.figure
    pull = (t - paper_fit(phi)) / se
    low.axhspan(-2, 2, color="0.9")
    low.axhline(0, color="tab:red", linewidth=1)
    low.plot(phi, pull, "o", color="black")
    low.set_xlabel("porosity φ")
    low.set_ylabel("(⟨T⟩ − f) / se")
    return ax.figure


def area_trace(run, ax=None):
    """A droplet's area over its area before the medium, against time: a result of
    simulate(..., trace=True), with the times it entered and left the medium. Returns the Figure."""
    if "trace" not in run:
        raise ValueError("run: no area trace (simulate(..., trace=True) records one)")
    trace = np.asarray(run["trace"], dtype=float)
    ax = _axes(ax)
    ax.plot(trace[:, 0], trace[:, 2], color="black")
    for key, style in (("enter", "--"), ("leave", ":")):
        if key in run and np.isfinite(run[key]):
            ax.axvline(run[key], color="0.5", linestyle=style, label=f"{key}s the medium")
    ax.set_xlabel("time")
    ax.set_ylabel("S / S₀")
    if ax.get_legend_handles_labels()[0]:
        ax.legend(loc="best", frameon=False)
    return ax.figure
