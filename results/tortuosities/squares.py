"""The flow tortuosity of freely overlapping squares, Matyka, Khalili and Koza's (2008) medium, to set
softdrop's flow solve beside their lattice-Boltzmann law T = 1 - p ln(phi). Squares of side A pixels
at uniform random places in an L x L box periodic in both directions (buffer_rows=0: the image is a
unit cell), added until the porosity falls to the target; SEEDS boxes a porosity (seeds 1 to
SEEDS). Writes squares_L_A.csv, or squares_L_A_PHIS.csv for other porosities than the default
five (one row a box), and prints p = (T - 1) / (-ln phi) per porosity, mean and standard error
over the boxes.

    /usr/bin/python3 squares.py [L A SEEDS [PHIS]]      (default 400 8 4 0.5,0.6,0.7,0.8,0.9: about 3 minutes)
"""
import math
import os
import sys

import numpy as np
import pandas as pd

DEFAULT_PHIS = "0.5,0.6,0.7,0.8,0.9"


def squares(L, A, porosity, seed):
    """A boolean L x L image, True in the pore space: squares of side A at random places, periodic."""
    rng = np.random.default_rng(seed)
    pore = np.ones((L, L), dtype=bool)
    rows = np.arange(A)
    while pore.mean() > porosity:
        x, y = rng.integers(0, L, size=2)
        pore[np.ix_((y + rows) % L, (x + rows) % L)] = False
    return pore


def main():
    import softdrop  # the built module (PYTHONPATH=build/python); squares() alone does not need it

    L, A, SEEDS = (int(v) for v in sys.argv[1:4]) if len(sys.argv) >= 4 else (400, 8, 4)
    PHIS = sys.argv[4] if len(sys.argv) >= 5 else DEFAULT_PHIS
    rows = []
    for porosity in (float(v) for v in PHIS.split(",")):
        for seed in range(1, SEEDS + 1):
            image = squares(L, A, porosity, seed)
            try:
                r = softdrop.tortuosity(image, pixel_size=1.0, buffer_rows=0)
            except ValueError as e:  # no pore path from the top to the bottom
                print(f"squares: porosity {porosity}, seed {seed}: {e}", file=sys.stderr)
                continue
            rows.append({"target_porosity": porosity, "seed": seed, "porosity": r.porosity,
                         "hydrodynamic_tortuosity": r.hydrodynamic_tortuosity,
                         "p": (r.hydrodynamic_tortuosity - 1) / -math.log(r.porosity),
                         "permeability": r.permeability})
    frame = pd.DataFrame(rows)
    name = f"squares_{L}_{A}" + ("" if PHIS == DEFAULT_PHIS else f"_{PHIS.replace(',', '_')}")
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), f"{name}.csv")
    frame.to_csv(out, index=False)
    summary = frame.groupby("target_porosity").agg(boxes=("p", "size"), T=("hydrodynamic_tortuosity", "mean"),
                                                   p=("p", "mean"), p_se=("p", "sem"))
    print(f"L = {L}, A = {A} (L / A = {L // A})")
    print(summary.round(4).to_string())


if __name__ == "__main__":
    main()
