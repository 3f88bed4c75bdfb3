"""softdrop: soft 2D droplets pushed through porous media of disc grains.

The same engine as the `softdrop` program: the same inputs and seed give the same numbers, bit
for bit. Lengths, times and masses are in the paper's numerical units (see docs/model.md).

    import softdrop
    medium = softdrop.Medium.generate("non-overlapping", porosity=0.8, seed=1)
    run = softdrop.simulate(medium, x0=200, path=True)
    table = softdrop.simulate_many(medium, 200, seed=3)   # a pandas DataFrame
    summary = softdrop.optimize("search.db", generations=50, lambda_=2, quiet=True)
    history = softdrop.read_history("search.db")          # DataFrames
"""
import numbers as _numbers
import os as _os

from ._core import DropletParams, Medium, RunOptions, StoreError, __version__  # noqa: F401
from . import _core

__all__ = ["DropletParams", "Medium", "Result", "RunOptions", "StoreError", "simulate", "simulate_many", "simulate_pair",
           "simulate_pairs", "held_out", "tortuosity", "optimize",
           "sweep", "rigid_descent", "read_history", "read_sweep", "sweep_droplet", "best_arrangement", "columns",
           "__version__"]


class Result(dict):
    """One droplet's run: outcome, reason, tortuosity (NaN unless passed), steps, start_x,
    touched (how many grains it touched) and touched_grains (their indices), min_area_ratio,
    max_penetration, shaken_at (when a shaken medium began to shake; NaN: never) and
    route_tortuosity (T of the path taken once a shaking period; T itself if never shaken), and
    path and trace if asked (see simulate). The names are the program's
    (softdrop.columns() lists them). Keys read as attributes too: run.tortuosity."""

    def __getattr__(self, name):
        try:
            return self[name]
        except KeyError as e:
            raise AttributeError(name) from e


def simulate(medium, x0=None, params=None, run=None, path=False, trace=False, trace_interval=100):
    """Pushes one droplet from x = x0 (default: the middle of the box) above the medium to an
    outcome. path=True adds `path`, rows of x, y of the droplet's centre (every run.path_interval
    steps, 100 if unset; the shape of every path softdrop gives), and `path_time`, their times.
    trace=True adds the area trace as `softdrop simulate --trace` records it: `trace`, rows of time,
    area, area_ratio (S / S0, every trace_interval steps), with `enter`, `leave` (times the droplet
    reached and left the medium, NaN: never), `s0`, and `inside_min_area_ratio`,
    `inside_max_area_ratio` (over every step inside the medium). Releases the GIL while it runs;
    Ctrl-C raises KeyboardInterrupt."""
    medium = _medium(medium)
    x0 = 0.5 * medium.width if x0 is None else float(x0)
    interval = int(trace_interval) if trace else 0
    if trace and interval < 1:
        raise ValueError(f"trace_interval = {interval}: must be >= 1")
    return Result(_core._simulate(medium, x0, params or DropletParams(), run or RunOptions(), bool(path), interval))


def simulate_many(medium, n, seed=1, threads=0, params=None, run=None):
    """n droplets from random starts (drawn from `seed` as `softdrop simulate --droplets n --seed`
    draws them), on `threads` threads (0: all). Returns a pandas DataFrame, one row a droplet, with
    the columns of the program's --runs CSV plus the reason."""
    rows = _core._simulate_many(_medium(medium), _whole(n, "n"), _whole(seed, "seed", 0), _whole(threads, "threads"),
                                params or DropletParams(), run or RunOptions())
    return _runs_frame(rows)


def simulate_pair(medium, x0=None, release="distance", after=40.0, offset_x=0.0, params=None, run=None, path=False,
                  trace=False, trace_interval=100):
    """Two droplets, one after the other, as `softdrop simulate --second-droplet` runs them: the
    first from x = x0 (default: the middle of the box), the second, the same droplet, from x0 +
    offset_x, released once the first is `after` length units below its start (release="distance")
    or `after` time units after it began ("delay"). Their rings collide. Returns a Result: `first`
    and `second`, each a Result as simulate gives it (with `path` and `path_time` if path=True) plus
    held_at (when it was first found stuck while the other still moved, since its own start; NaN:
    never) and, with trace=True, `trace`: rows of time, area every trace_interval steps of its own
    run; and the pair's released, released_at (since the first began; NaN: never), contact_steps
    and shared_touched (grains both touched)."""
    medium = _medium(medium)
    x0 = 0.5 * medium.width if x0 is None else float(x0)
    interval = int(trace_interval) if trace else 0
    if trace and interval < 1:
        raise ValueError(f"trace_interval = {interval}: must be >= 1")
    out = _core._simulate_pair(medium, x0, str(release), float(after), float(offset_x), params or DropletParams(),
                               run or RunOptions(), bool(path), interval)
    out["first"], out["second"] = Result(out["first"]), Result(out["second"])
    return Result(out)


def simulate_pairs(medium, n, seed=1, threads=0, release="distance", after=40.0, offset_x=0.0, params=None, run=None):
    """n pairs from random starts (the first droplets' starts drawn as simulate_many draws them), on
    `threads` threads (0: all); see simulate_pair. Returns a pandas DataFrame, one row a droplet, with
    the columns of `softdrop simulate --second-droplet --runs` (droplet is the pair's number, order
    1 the first and 2 the second) plus the reason."""
    import pandas as pd

    pairs = _core._simulate_pairs(_medium(medium), _whole(n, "n"), _whole(seed, "seed", 0), _whole(threads, "threads"),
                                  str(release), float(after), float(offset_x), params or DropletParams(),
                                  run or RunOptions())
    rows = []
    for i, p in enumerate(pairs):
        for order, key in ((1, "first"), (2, "second")):
            if order == 2 and not p["released"]:
                continue
            d = dict(p[key], droplet=i, order=order, released_at=p["released_at"], contact_steps=p["contact_steps"],
                     shared_touched=p["shared_touched"])
            rows.append(d)
    return pd.DataFrame(rows)[["droplet", "order", "start_x", "outcome", "tortuosity", "steps", "touched",
                               "min_area_ratio", "max_penetration", "shaken_at", "route_tortuosity", "released_at",
                               "held_at", "contact_steps", "shared_touched", "reason"]]


def held_out(medium, starts=200, seed=1, half_dt=True, threads=0, params=None, run=None):
    """The held-out value of a medium, as `softdrop validate` gives it: `starts` droplets from random
    starts across the top (drawn as simulate_many draws them), and with half_dt the same starts at
    dt / 2 (twice the step budget). Returns a Result with at_dt and at_half_dt (dicts: dt, starts,
    passed, pass_fraction, mean_tortuosity, standard_error, q1, median, q3; None where nothing passed),
    dt_shift and dt_shift_error (the mean of T(dt/2) - T(dt) over the `paired` starts that passed
    at both), and runs, a pandas DataFrame with one row a droplet and time step. Ctrl-C stops it
    after the droplets in flight."""
    import pandas as pd

    out = _core._held_out(_medium(medium), _whole(starts, "starts"), _whole(seed, "seed", 0), bool(half_dt),
                          _whole(threads, "threads"), params or DropletParams(), run or RunOptions())
    out["runs"] = pd.DataFrame(out["runs"])
    return Result(out)


def tortuosity(medium, pixels=500, pixel_size=1.0, periodic=True, flow=True, buffer_rows=-1):
    """The pore space's tortuosities, as `softdrop tortuosity` measures them at one resolution.
    `medium` is a Medium (drawn `pixels` across its width, a pixel being pore where its centre lies
    in no grain), or a grain file's name, or a 2D binary image: a numpy array, True (or 1) in the
    pore space, rows from the top (PoreSpy's convention, and Medium.to_image's), of pixels of side
    `pixel_size`, periodic in x or not. Returns a Result: geometric_tortuosity (the shortest path
    from each pore pixel of the top row to the bottom, over the height, averaged over them: fast
    marching), geometric_standard_error, starts and connected (top pixels, and those with a path
    down), diffusive_tortuosity (porosity D / D_eff from a steady diffusion between the top and the
    bottom: PoreSpy's tortuosity_fd),
    formation_factor, effective_diffusivity, porosity (of the image), pixel, and the fields as arrays
    of the image's shape, rows from the top: distance (to the bottom edge, length units; inf where
    no path) and concentration (NaN in the solid). flow=True adds the creeping flow driven
    downwards (Stokes, no slip on the solid): hydrodynamic_tortuosity (<|u|> / <-u_y> over the pore
    pixels, Matyka 2008's definition), permeability (Darcy's k, length units squared), buffer_rows
    (rows of open fluid added above and below, the box then periodic in y; buffer_rows=0 treats the
    image itself as periodic in y, a unit cell), and the fields velocity_x, velocity_y (units of
    f h^2 / mu: force per volume f, pixel h, viscosity mu) and pressure. Both values converge at first order in the pixel
    size: compare a resolution with its double. Raises ValueError for an image that is not binary
    or is empty, a bad pixel size, or no pore path from the top to the bottom."""
    import numpy as np

    if isinstance(medium, np.ndarray):
        return Result(_core._tortuosity_of_image(medium, float(pixel_size), bool(periodic), bool(flow),
                                                 _whole(buffer_rows, "buffer_rows", -1)))
    return Result(_core._tortuosity_of_medium(_medium(medium), _whole(pixels, "pixels", 2), bool(flow),
                                              _whole(buffer_rows, "buffer_rows", -1)))


def rigid_descent(medium, x0, radius=0.0, path=False):
    """The geometric limit of passage: a rigid, frictionless disc of `radius` (0: a point) without
    inertia, dropped with its centre at x0 (one start or a sequence) and moved by gravity alone. It
    falls, slides along grains' upper halves and stops in the first dead end (between two grains, or
    a grain and a wall). Exact circle geometry; the same inputs give the same bits. Returns a pandas
    DataFrame, one row a start: start_x, outcome ("passed" or "stuck"), tortuosity (path length
    between y = H and 0 over H; NaN unless passed), x and y (where it crossed y = 0 or stopped),
    slides (grain surfaces it slid along). path=True adds `path`, each an array of rows x, y from
    the start above the medium (arcs every 0.02 rad; x runs on across the periodic edge, as a
    droplet's path does). A droplet that neither deforms nor bounces passes where this disc passes."""
    import numpy as np
    import pandas as pd

    starts = np.atleast_1d(np.asarray(x0, dtype=float))
    columns = _core._rigid_descents(medium, float(radius), starts.tolist(), bool(path))
    paths = columns.pop("path", None)
    frame = pd.DataFrame(columns)
    frame.insert(1, "outcome", np.where(frame.pop("passed"), "passed", "stuck"))
    if paths is not None:
        frame["path"] = paths
    return frame


def _runs_frame(rows):
    """simulate_many's DataFrame from the core's rows (one dict a droplet)."""
    import pandas as pd

    frame = pd.DataFrame(rows)
    frame.insert(0, "droplet", range(len(frame)))
    return frame[["droplet", "start_x", "outcome", "tortuosity", "steps", "touched", "min_area_ratio",
                  "max_penetration", "shaken_at", "route_tortuosity", "reason"]]


def _medium(medium):
    """A Medium, or a grain file's name (str or os.PathLike) read into one."""
    if isinstance(medium, Medium):
        return medium
    if isinstance(medium, (str, _os.PathLike)):
        return Medium.load(medium)
    raise TypeError(f"medium: a Medium or a grain file name, not {type(medium).__name__}")


def _whole(value, name, least=None):
    """An integer argument: a float such as 2.5 is refused rather than cut to 2."""
    if isinstance(value, bool) or not isinstance(value, _numbers.Integral):
        raise TypeError(f"{name}: a whole number, not {value!r}")
    if least is not None and value < least:
        raise ValueError(f"{name} = {value}: must be >= {least}")
    return int(value)


def _db_path(db, name="db"):
    """The file name of a database argument: a str or os.PathLike, not empty (SQLite would make a
    temporary database of "" and throw the run away; str(None) would be a file named None)."""
    if isinstance(db, bytes) or not isinstance(db, (str, _os.PathLike)):
        raise TypeError(f"{name}: a file name (str or os.PathLike), not {db!r}")
    path = _os.fspath(db)
    if not path:
        raise ValueError(f"{name}: an empty file name")
    return path


def _with_progress(callback, progress, unit, done_and_total):
    """The callback, with a progress bar in Python (tqdm when it is installed, else a logging line
    each tenth of the way) fed by its events: what a notebook shows, where the program's own
    progress on the C-level stderr does not reach. done_and_total(event) -> (done, total)."""
    if not progress:
        return callback, lambda: None
    import logging

    try:
        from tqdm.auto import tqdm
    except ImportError:
        tqdm = None
    log = logging.getLogger("softdrop")
    state = {"bar": None, "logged": -1}

    def step(event):
        done, total = done_and_total(event)
        if tqdm is not None:
            if state["bar"] is None:
                state["bar"] = tqdm(total=total, initial=done - 1, unit=unit)
            state["bar"].update(done - state["bar"].n)
            state["bar"].set_postfix_str(_postfix(event), refresh=False)
        elif total > 0 and (10 * done) // total > state["logged"]:
            state["logged"] = (10 * done) // total
            log.info("%s %d/%d (%s)", unit, done, total, _postfix(event))
        return callback(event) if callback else True

    def close():
        if state["bar"] is not None:
            state["bar"].close()

    return step, close


def _postfix(event):
    if "best_tortuosity" in event:
        return f"best T {event['best_tortuosity']:.4f}"
    mean = event.get("mean_tortuosity")
    return f"<T> {mean:.4f}" if isinstance(mean, float) and mean == mean else ""


def _run_with_progress(run, db, callback, progress, options, unit, done_and_total):
    for name, value in options.items():
        if isinstance(value, Medium):
            raise TypeError(f"{name}: a grain file name, not a Medium (save it first: medium.save(path))")
    if progress:
        options = dict(options, quiet=True)  # the bar instead of the program's line on the C-level stderr
    step, close = _with_progress(callback, progress, unit, done_and_total)
    try:
        return Result(run(db, options, step if (callback or progress) else None))
    finally:
        close()


def optimize(db="softdrop.db", callback=None, progress=False, **options):
    """Runs a search in this process, as `softdrop optimize` does: the options are the program's
    long options as keywords (generations=500, lambda_=4, strategy="es", relocate_every=3,
    resume=1, quiet=True, config="droplet.toml", ...), each read as the type of its default (None:
    the default, as if not given), with the same defaults, presets and checks, and the history file
    is the one the program writes.

    `callback(event)`, if given, is called after each generation is committed, with a dict: run,
    generation, kind, accepted_candidate (None: none kept), candidates, seconds, best_tortuosity,
    best_generation, target_generations. Returning False stops the search there; the run is marked
    interrupted and `optimize(db, resume=run)` continues it exactly. Ctrl-C stops it the same way,
    then raises KeyboardInterrupt; an exception in the callback stops it and is raised again.

    progress=True shows a progress bar in Python (tqdm, as in a notebook; without tqdm, a
    `logging` line on the "softdrop" logger each tenth of the way) instead of the program's line.

    Returns the summary `softdrop optimize --format json` prints (run, termination, best_tortuosity,
    evaluations, ...). Bad options raise ValueError with the program's message; a database the
    store refuses raises StoreError naming it."""
    return _run_with_progress(_core._optimize, db, callback, progress, options, "generation",
                              lambda e: (e["generation"], e["target_generations"]))


def sweep(db="sweep.db", callback=None, progress=False, **options):
    """Runs a sweep in this process, as `softdrop sweep` does (the tortuosity-porosity study):
    options as for optimize (porosities=[0.6, 0.8], media=4, droplets=20, preset="quick",
    threads=2, ...). The store is the program's: running it again goes on with the media not yet
    stored.

    `callback(event)` is called after each medium is committed, with a dict: sweep,
    porosity_index, medium_index, target_porosity, passed, mean_tortuosity, media_done, media_to_do.
    Returning False stops after the media in flight (they are stored); Ctrl-C does too, then
    raises KeyboardInterrupt. Returns a summary: sweep, status, media, done (media stored),
    media_this_session, droplets_this_session, wall_seconds. read_sweep(db) has the records.
    progress=True shows a progress bar over the media, as for optimize."""
    return _run_with_progress(_core._sweep, db, callback, progress, options, "medium",
                              lambda e: (e["media_done"], e["media_to_do"]))


def read_history(db, arrangements=True):
    """A search history (the SQLite file of `softdrop optimize`), read by the program's own store:
    a dict of pandas DataFrames with the columns of the database's views (runs_view, ...; the
    names of softdrop.columns()): `runs`, `generations`, `candidates`, `grains` and `paths` (the
    arrangements the search kept: generation 0's and each accepted one; arrangements=False leaves
    these two empty), `validations` (held-out values of arrangements: `softdrop validate`, and the
    end of a search), `best` (each run's best-T curve as `softdrop history --run N --best` gives it,
    with the held-out value stored for each arrangement on it; re_runs is <NA> for the single
    objective) and `params` (one row a run: run and the options stored with it, typed). A file the
    store refuses raises StoreError naming it."""
    import json

    import pandas as pd

    tables = _core._read_history(_db_path(db), bool(arrangements))
    frames = {name: pd.DataFrame(columns) for name, columns in tables.items()}
    for name, column in (("generations", "accepted_candidate"), ("candidates", "moved_grain"), ("runs", "island"),
                         ("runs", "archipelago"), ("validations", "half_dt_passed"), ("validations", "paired"),
                         ("best", "held_out_starts"), ("best", "re_runs")):
        frames[name][column] = frames[name][column].astype("Int64")  # missing: <NA>
    frames["grains"]["touched"] = frames["grains"]["touched"].astype(bool)
    rows = []
    for run_id, text in zip(frames["runs"]["run"], frames["runs"]["params"]):
        try:
            row = json.loads(text)
        except ValueError as e:  # JSONDecodeError, or text that is not UTF-8
            raise StoreError(f"db '{_os.fspath(db)}': run {run_id}: its params are not JSON ({e})") from None
        if not isinstance(row, dict):
            raise StoreError(f"db '{_os.fspath(db)}': run {run_id}: its params are not a JSON object")
        rows.append(row)
    params = pd.json_normalize(rows)
    params.insert(0, "run", frames["runs"]["run"].to_numpy())
    frames["params"] = params
    return frames


def read_sweep(db, sweep=None):
    """The records of `softdrop sweep` (all sweeps of the file, or the one with id `sweep`), read
    by the program's own store: a dict of pandas DataFrames `sweeps`, `media`, `droplets` and
    `second_droplets` (the database's views; mean_tortuosity, standard_error and tortuosity are NaN
    where nothing passed; second_droplets is empty but for a sweep of pairs, sweep(second_droplet=...):
    a row per released second, its pair's first the droplets row of the same droplet), and `points` (per target porosity, as `softdrop sweep-report` aggregates them, with the standard
    error over droplets and, in media_standard_error, over media as clusters; per_medium_tortuosity is the
    other averaging, each medium's <T> first and then their mean, with per_medium_standard_error).
    A file the store refuses raises StoreError naming it."""
    import pandas as pd

    if sweep is not None and (isinstance(sweep, bool) or not isinstance(sweep, _numbers.Integral) or sweep < 1):
        raise ValueError(f"sweep = {sweep!r}: sweep ids are whole numbers from 1 (None: every sweep)")
    tables = _core._read_sweep(_db_path(db), int(sweep or 0))
    return {name: pd.DataFrame(columns) for name, columns in tables.items()}


def columns():
    """The names softdrop writes, one per quantity, in its CSV, JSON, database views and the frames
    and results here: a pandas DataFrame of name, unit ("1": dimensionless; length, time and mass in
    the model's units; "s": wall-clock seconds) and meaning, as `softdrop columns` prints it. Droplet
    parameters (DropletParams' attributes) are named by their option and are not listed."""
    import pandas as pd

    return pd.DataFrame(_core._columns())


def sweep_droplet(db, porosity_index, medium_index, droplet, sweep=None):
    """One droplet of a `softdrop sweep`, ready to run again, named by its indices in the sweep's
    tables (read_sweep): a Result with medium (the medium's grains, generated again from its stored
    seed and the sweep's options), params (the sweep's DropletParams), run (its RunOptions) and x0
    (the droplet's start), and what the sweep stored of the droplet: outcome, tortuosity (NaN unless
    it passed), steps, with target_porosity, porosity, medium_seed and sweep. simulate(r.medium,
    x0=r.x0, params=r.params, run=r.run) gives the stored outcome, T and steps again to the bit;
    add path=True or trace=True to see how it got there. `sweep` is the sweep's id (None: the only
    one in the file). A sweep of pairs is refused: a pair's first droplet does not run alone."""
    for name, value in (("porosity_index", porosity_index), ("medium_index", medium_index), ("droplet", droplet)):
        if isinstance(value, bool) or not isinstance(value, _numbers.Integral):
            raise TypeError(f"{name}: a whole number, not {value!r}")
    if sweep is not None and (isinstance(sweep, bool) or not isinstance(sweep, _numbers.Integral) or sweep < 1):
        raise ValueError(f"sweep = {sweep!r}: sweep ids are whole numbers from 1 (None: the only one)")
    return Result(_core._sweep_droplet(_db_path(db), int(sweep or 0), int(porosity_index), int(medium_index),
                                       int(droplet)))


def best_arrangement(db, run=1, generation=-1):
    """The arrangement a search kept as of `generation` (-1: the latest; the best for the paper's
    strategy): a Result with medium (a Medium), generation, tortuosity (the objective's value it
    was kept with), touched (a count), touched_grains (their indices) and path (rows of x, y, as
    simulate's; a robust objective's first droplet's), and its values as `softdrop history --best`
    gives them: objective, best_tortuosity (its value in the search: for a robust objective the
    mean of its re_runs re-runs on fresh starts, which a lucky win does not inflate), and
    held_out_tortuosity, held_out_standard_error and held_out_starts (<T> over random starts no
    evaluation used, as stored by the search's end or `softdrop validate`; None if none is
    stored)."""
    if isinstance(run, bool) or not isinstance(run, _numbers.Integral) or run < 1:
        raise ValueError(f"run = {run!r}: run ids are whole numbers from 1")
    return Result(_core._arrangement(_db_path(db), int(run), int(generation)))
