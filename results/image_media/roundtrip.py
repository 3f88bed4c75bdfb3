"""Disc media pushed through as images: the same droplets on six overlapping media of grains and on
the same media drawn as binary images at 1, 2 and 4 pixels a length unit.

    /usr/bin/python3 results/image_media/roundtrip.py      # about 3 minutes on 2 cores

Writes roundtrip.csv (a row a droplet and resolution), summary.csv (a row a resolution) and
roundtrip.png. Run from the repository with the module built (build/python), or installed."""
import os
import sys

import numpy as np
import pandas as pd

here = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(here, "..", "..", "build", "python"))
import softdrop  # noqa: E402

SEEDS = range(21, 27)  # media no test or tuning used (the unit test's are 11 and 14)
DROPLETS = 100
BOX = 250.0


def medium(seed):
    """An overlapping medium of grains of radius 8 to 20, less the grains that cross the top of the
    box: an image of the box would cut them flat, where a droplet could come to rest."""
    g = softdrop.Medium.generate(porosity=0.75, seed=seed, width=BOX, height=BOX, r_min=8, r_max=20)
    grains = g.grains
    keep = grains[:, 1] + grains[:, 2] < BOX - 1
    return softdrop.Medium.from_arrays(grains[keep, 0], grains[keep, 1], grains[keep, 2], BOX, BOX)


def run():
    rows = []
    for seed in SEEDS:
        discs = medium(seed)
        a = softdrop.simulate_many(discs, DROPLETS, seed=7)
        for pixels in (250, 500, 1000):
            image = softdrop.Medium.from_image(discs.to_image(pixels), pixel_size=BOX / pixels)
            b = softdrop.simulate_many(image, DROPLETS, seed=7)
            for k in range(DROPLETS):
                rows.append(dict(medium_seed=seed, pixels_per_unit=pixels / BOX, droplet=k,
                                 start_x=a.start_x[k], discs_outcome=a.outcome[k], image_outcome=b.outcome[k],
                                 discs_tortuosity=a.tortuosity[k], image_tortuosity=b.tortuosity[k]))
            print(f"medium {seed}, {pixels} pixels across", file=sys.stderr, flush=True)
    return pd.DataFrame(rows)


def summarize(d):
    out = []
    for p, g in d.groupby("pixels_per_unit"):
        both = g[(g.discs_outcome == "passed") & (g.image_outcome == "passed")]
        diff = both.image_tortuosity - both.discs_tortuosity
        out.append(dict(pixels_per_unit=p, droplets=len(g), same_outcome=(g.discs_outcome == g.image_outcome).mean(),
                        passed_discs=(g.discs_outcome == "passed").mean(),
                        passed_image=(g.image_outcome == "passed").mean(), passed_both=len(both),
                        mean_tortuosity_discs=both.discs_tortuosity.mean(),
                        mean_tortuosity_image=both.image_tortuosity.mean(),
                        mean_difference=diff.mean(), standard_error=diff.std(ddof=1) / np.sqrt(len(diff))))
    return pd.DataFrame(out)


def figure(d, s, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (left, right) = plt.subplots(1, 2, figsize=(9, 4))
    fine = d[(d.pixels_per_unit == 4) & (d.discs_outcome == "passed") & (d.image_outcome == "passed")]
    left.scatter(fine.discs_tortuosity, fine.image_tortuosity, s=8, alpha=0.6)
    lo, hi = 1.0, max(fine.discs_tortuosity.max(), fine.image_tortuosity.max())
    left.plot([lo, hi], [lo, hi], color="black", lw=0.8)
    left.set_xlabel("T, disc medium")
    left.set_ylabel("T, its image at 4 pixels a unit")
    left.set_title("each droplet (chaotic: one start apart)")
    right.errorbar(s.pixels_per_unit, s.mean_difference, yerr=s.standard_error, fmt="o", capsize=3)
    right.axhline(0, color="black", lw=0.8)
    right.set_xscale("log", base=2)
    right.set_xticks([1, 2, 4], ["1", "2", "4"])
    right.set_xlabel("pixels a length unit")
    right.set_ylabel("⟨T⟩ image − ⟨T⟩ discs (same droplets)")
    right.set_title("mean over droplets passing in both")
    fig.tight_layout()
    fig.savefig(path, dpi=120)


if __name__ == "__main__":
    d = run()
    d.to_csv(os.path.join(here, "roundtrip.csv"), index=False)
    s = summarize(d)
    s.to_csv(os.path.join(here, "summary.csv"), index=False)
    print(s.to_string(index=False))
    figure(d, s, os.path.join(here, "roundtrip.png"))
