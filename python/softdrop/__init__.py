"""softdrop: soft 2D droplets pushed through porous media of disc grains.

The same engine as the `softdrop` program: the same inputs and seed give the same numbers, bit
for bit. Lengths, times and masses are in the paper's numerical units (see docs/model.md).

    import softdrop
    medium = softdrop.Medium.generate("non-overlapping", porosity=0.8, seed=1)
    run = softdrop.simulate(medium, x0=200, path=True)
    table = softdrop.simulate_many(medium, 200, seed=3)   # a pandas DataFrame
"""
from ._core import DropletParams, Medium, RunOptions, StoreError, __version__  # noqa: F401
from . import _core

__all__ = ["DropletParams", "Medium", "RunOptions", "StoreError", "simulate", "simulate_many", "read_history",
           "best_arrangement", "__version__"]


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


def read_history(db):
    """A search history (the SQLite file of `softdrop optimize`), read by the program's own store:
    a dict of pandas DataFrames `runs`, `generations` and `candidates` (one row a run, generation,
    candidate; the columns of the database's tables, see the README). A file the store refuses
    raises StoreError naming it."""
    import pandas as pd

    rows = _core._read_history(str(db))
    frames = {name: pd.DataFrame(rows[name]) for name in ("runs", "generations", "candidates")}
    for name, column in (("generations", "accepted_candidate"), ("candidates", "moved_grain")):
        if column in frames[name]:
            frames[name][column] = frames[name][column].astype("Int64")  # missing: <NA>
    return frames


def best_arrangement(db, run=1, generation=-1):
    """The arrangement a search kept as of `generation` (-1: the latest; the best for the paper's
    strategy): a Result with medium (a Medium), generation, tortuosity, touched and path (x, y rows)."""
    return Result(_core._arrangement(str(db), int(run), int(generation)))
