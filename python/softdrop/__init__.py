"""softdrop: soft 2D droplets pushed through porous media of disc grains.

The same engine as the `softdrop` program: the same inputs and seed give the same numbers, bit
for bit. Lengths, times and masses are in the paper's numerical units (see docs/model.md).

    import softdrop
    medium = softdrop.Medium.generate("non-overlapping", porosity=0.8, seed=1)
    run = softdrop.simulate(medium, x0=200, path=True)
    table = softdrop.simulate_many(medium, 200, seed=3)   # a pandas DataFrame
"""
from ._core import DropletParams, Medium, RunOptions, __version__  # noqa: F401
from . import _core

__all__ = ["DropletParams", "Medium", "RunOptions", "simulate", "simulate_many", "__version__"]


class Result(dict):
    """One droplet's run: outcome, reason, tortuosity (NaN unless passed), steps, start_x,
    touched (grain indices), min_area_ratio, max_penetration, and path (t, x, y rows) if asked."""

    def __getattr__(self, name):
        try:
            return self[name]
        except KeyError as e:
            raise AttributeError(name) from e


def simulate(medium, x0=None, params=None, run=None, path=False):
    """Pushes one droplet from x = x0 (default: the middle of the box) above the medium to an
    outcome. Releases the GIL while it runs; Ctrl-C raises KeyboardInterrupt."""
    x0 = 0.5 * medium.width if x0 is None else float(x0)
    return Result(_core._simulate(medium, x0, params or DropletParams(), run or RunOptions(), bool(path)))


def simulate_many(medium, n, seed=1, threads=0, params=None, run=None):
    """n droplets from random starts (drawn from `seed` as `softdrop simulate --droplets n --seed`
    draws them), on `threads` threads (0: all). Returns a pandas DataFrame, one row a droplet, with
    the columns of the program's --runs CSV plus the reason."""
    import pandas as pd

    rows = _core._simulate_many(medium, int(n), int(seed), int(threads), params or DropletParams(), run or RunOptions())
    frame = pd.DataFrame(rows)
    frame.insert(0, "droplet", range(len(frame)))
    frame["touched"] = frame["touched"].map(len)
    return frame[["droplet", "start_x", "outcome", "tortuosity", "steps", "touched", "min_area_ratio",
                  "max_penetration", "reason"]]
