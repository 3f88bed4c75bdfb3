#!/usr/bin/env python3
"""What the media's dead ends allow: how many starts a rigid disc passes when gravity alone moves it.

A rigid, frictionless disc without inertia (softdrop.rigid_descent) falls, slides along the grains'
upper halves and stops in the first dead end. A droplet that neither deforms nor bounces passes
exactly where it passes, so its pass fraction is the medium's own limit for such a droplet, and the
droplet's measured pass fraction (radius.csv, radius_non_overlapping.csv) set beside it shows what
deforming and bouncing add. Disc radii 0 (a point) to 8, in the calibration's media: grains of
radii 16 to 48 in a 500 x 500 periodic box, overlapping and non-overlapping (gaps of 13 % of the
larger radius), the calibration's six porosities, 200 media x 20 uniform starts each (media seeds
1 to 200, starts from one fixed generator: not the calibration's own media, the same ensemble).

Writes rigid_bound.csv (one row per kind, porosity and disc radius) and rigid_bound.png. Then,
start by start: the default droplet (softdrop.simulate_many) and the rigid discs of radius 0 and 8
from the same starts in the same media, 100 overlapping media x 20 starts at porosities 0.5 and 0.7:
rigid_bound_starts.csv, one row per start, and rigid_bound_paths.png, the paths from three of those
starts. Needs the Python module (PYTHONPATH=build/python); about 3 minutes on 2 cores.

    PYTHONPATH=build/python /usr/bin/python3 results/calibration/rigid_bound.py
"""
import os
import sys
import time

import matplotlib
import numpy as np
import pandas as pd

import softdrop

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

POROSITIES = [0.5, 0.6, 0.7, 0.8, 0.9, 0.95]
RADII = [0.0, 2.0, 4.0, 6.0, 8.0]
KINDS = ["overlapping", "non-overlapping"]
MEDIA, STARTS = 200, 20


def paper_tortuosity(phi):
    return 1.58 - 0.58 * phi ** 3.87


def measure():
    rows = []
    rng = np.random.default_rng(20261204)
    began = time.time()
    for k, kind in enumerate(KINDS):
        for p, phi in enumerate(POROSITIES):
            media = [softdrop.Medium.generate(kind, porosity=phi, seed=seed) for seed in range(1, MEDIA + 1)]
            starts = rng.uniform(0, media[0].width, size=(MEDIA, STARTS))
            for radius in RADII:
                runs = [softdrop.rigid_descent(m, starts[i], radius=radius) for i, m in enumerate(media)]
                per_medium = np.array([(r.outcome == "passed").mean() for r in runs])
                passed = pd.concat(runs).query("outcome == 'passed'")
                rows.append({
                    "kind": kind, "target_porosity": phi, "disc_radius": radius, "media": MEDIA,
                    "starts": MEDIA * STARTS, "passed": len(passed),
                    "pass_fraction": per_medium.mean(),
                    "pass_standard_error": per_medium.std(ddof=1) / np.sqrt(MEDIA),
                    "media_none_passed": int((per_medium == 0).sum()),
                    "mean_tortuosity": passed.tortuosity.mean() if len(passed) else float("nan"),
                    "paper_tortuosity": paper_tortuosity(phi),
                })
            done = (k * len(POROSITIES) + p + 1) / (len(KINDS) * len(POROSITIES))
            elapsed = time.time() - began
            print(f"\r{kind} phi = {phi}: {100 * done:.0f} %, ETA {elapsed / done - elapsed:.0f} s",
                  end="", file=sys.stderr, flush=True)
    print(file=sys.stderr)
    return pd.DataFrame(rows)


def start_by_start(porosities=(0.5, 0.7), media=100, starts=20):
    """The default droplet and rigid discs of radius 0 and 8 from the same starts in the same media."""
    frames = []
    began = time.time()
    for p, phi in enumerate(porosities):
        for seed in range(1, media + 1):
            medium = softdrop.Medium.generate("overlapping", porosity=phi, seed=seed)
            droplets = softdrop.simulate_many(medium, starts, seed=seed)
            point = softdrop.rigid_descent(medium, droplets.start_x.values, radius=0)
            disc = softdrop.rigid_descent(medium, droplets.start_x.values, radius=8)
            frames.append(pd.DataFrame({
                "target_porosity": phi, "medium_seed": seed, "start_x": droplets.start_x,
                "droplet_outcome": droplets.outcome, "droplet_t": droplets.tortuosity,
                "point_outcome": point.outcome, "point_t": point.tortuosity,
                "disc8_outcome": disc.outcome, "disc8_t": disc.tortuosity}))
            done = (p * media + seed) / (len(porosities) * media)
            elapsed = time.time() - began
            print(f"\rstart by start, phi = {phi}: {100 * done:.0f} %, ETA {elapsed / done - elapsed:.0f} s",
                  end="", file=sys.stderr, flush=True)
    print(file=sys.stderr)
    return pd.concat(frames, ignore_index=True)


def plot_paths(starts):
    """The droplet's path and the rigid discs' from three starts at phi = 0.5: the first where the
    droplet passes and the point stops, the first where the point passes and the droplet stops,
    and the first where both pass."""
    at = starts[starts.target_porosity == 0.5]
    cases = [("droplet passes, point stops", (at.droplet_outcome == "passed") & (at.point_outcome == "stuck")),
             ("point passes, droplet stops", (at.droplet_outcome == "stuck") & (at.point_outcome == "passed")),
             ("both pass", (at.droplet_outcome == "passed") & (at.point_outcome == "passed"))]
    fig, axes = plt.subplots(1, 3, figsize=(13, 5))
    for ax, (title, chosen) in zip(axes, cases):
        row = at[chosen].iloc[0]
        medium = softdrop.Medium.generate("overlapping", porosity=0.5, seed=int(row.medium_seed))
        droplet = np.asarray(softdrop.simulate(medium, x0=row.start_x, path=True).path)[:, 1:]
        paths = [(droplet, "C3", "-", f"droplet, T = {row.droplet_t:.3f}" if row.droplet_outcome == "passed"
                  else "droplet, stops")]
        for radius, colour in ((0.0, "k"), (8.0, "C0")):
            rigid = softdrop.rigid_descent(medium, row.start_x, radius=radius, path=True)
            label = f"rigid disc r = {radius:g}, " + (f"T = {rigid.tortuosity[0]:.3f}" if rigid.outcome[0] == "passed"
                                                       else "stops")
            paths.append((rigid.path[0], colour, "--", label))
        xs = np.concatenate([p[:, 0] for p, *_ in paths])
        lo, hi = min(xs.min(), 0) - 30, max(xs.max(), medium.width) + 30
        for image in range(int(np.floor(lo / medium.width)), int(np.ceil(hi / medium.width)) + 1):
            for x, y, r in medium.grains:
                ax.add_patch(plt.Circle((x + image * medium.width, y), r, color="0.75", lw=0))
        for path, colour, style, label in paths:
            keep = path[:, 1] >= -30
            ax.plot(path[keep, 0], path[keep, 1], style, color=colour, lw=1.2, label=label)
        ax.axvspan(0, medium.width, ymin=0, ymax=1, fill=False, ls=":", lw=0.8)
        ax.set_xlim(lo, hi)
        ax.set_ylim(-30, medium.height + 60)
        ax.set_aspect("equal")
        ax.set_title(f"{title} (medium {int(row.medium_seed)}, x0 = {row.start_x:.1f})", fontsize=8)
        ax.legend(fontsize=7, loc="lower left")
    fig.suptitle("paths from the same start, overlapping medium at φ = 0.5 (dotted: the periodic box)", fontsize=9)
    fig.tight_layout()
    fig.savefig("rigid_bound_paths.png", dpi=100)


def droplet_points(name):
    """The droplet's pass fraction per radius and porosity from a committed radius study."""
    rows, points = pd.read_csv(f"{name}.csv"), pd.read_csv(f"{name}_points.csv")
    points = points.merge(rows[["setting", "radius"]], on="setting")
    points["pass_fraction"] = points.passed / points.droplets
    return points


def plot(table):
    fig, axes = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
    for ax, kind, name in zip(axes, KINDS, ["radius", "radius_non_overlapping"]):
        rigid = table[table.kind == kind]
        colours = {0.0: "k", 4.0: "C0", 8.0: "C3"}
        for radius, group in rigid.groupby("disc_radius"):
            if radius in colours:
                ax.errorbar(group.target_porosity, group.pass_fraction, yerr=group.pass_standard_error, ls="--",
                            marker="s", ms=3, capsize=2, color=colours[radius], label=f"rigid disc, r = {radius:g}")
        droplets = droplet_points(name)
        for radius, group in droplets.groupby("radius"):
            if float(radius) in colours:
                ax.plot(group.target_porosity, group.pass_fraction, "o-", ms=4, color=colours[float(radius)],
                        label=f"droplet, R = {radius:g}")
        ax.axhline(0.25, color="gray", lw=0.8, ls=":", label="a quarter")
        ax.set_title(f"{kind} media", fontsize=9)
        ax.set_xlabel("porosity φ")
        ax.legend(fontsize=7)
    axes[0].set_ylabel("fraction that passes")
    fig.suptitle("gravity alone: rigid, inertialess discs (dashed; bars: SE over 200 media) and the droplet "
                 "(solid; 200 media × 20 droplets)", fontsize=9)
    fig.tight_layout()
    fig.savefig("rigid_bound.png", dpi=110)


def main():
    os.chdir(os.path.dirname(os.path.abspath(__file__)))
    if sys.argv[1:] == ["paths"]:  # redraw rigid_bound_paths.png from the committed starts
        plot_paths(pd.read_csv("rigid_bound_starts.csv"))
        return
    table = measure()
    table.to_csv("rigid_bound.csv.tmp", index=False)
    os.replace("rigid_bound.csv.tmp", "rigid_bound.csv")
    plot(table)
    starts = start_by_start()
    starts.to_csv("rigid_bound_starts.csv.tmp", index=False)
    os.replace("rigid_bound_starts.csv.tmp", "rigid_bound_starts.csv")
    plot_paths(starts)


if __name__ == "__main__":
    main()
