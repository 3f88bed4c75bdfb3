"""The Python module against the program: the same inputs give the same bits; data frames have
the program's columns; bad input raises ValueError with the library's one-line message."""
import json
import math
import os
import pathlib
import pickle
import subprocess
import sys

import numpy as np
import pandas as pd
import pytest

import softdrop

import balloon

CLI = os.environ["SOFTDROP_CLI"]


def cli(*args):
    done = subprocess.run([CLI, *args], capture_output=True, text=True, check=True)
    return done.stdout


def test_one_droplet_has_the_programs_bits():
    medium = softdrop.Medium.generate()
    run = softdrop.simulate(medium, x0=250, path=True)
    theirs = json.loads(cli("simulate", "--x0", "250", "--format", "json"))
    assert run.outcome == theirs["run"]["outcome"] == "passed"
    assert run.tortuosity == theirs["run"]["tortuosity"]  # exactly
    assert run.steps == theirs["run"]["steps"]
    assert run.touched == len(run.touched_grains) == theirs["run"]["touched"]
    # every path is rows of x, y; its times beside it, a path interval apart
    assert run.path.shape[1] == 2 and run.path.shape[0] > 10 and run.path_time.shape == (run.path.shape[0],)
    assert np.all(np.diff(run.path_time) > 0)
    assert medium.porosity() == theirs["medium"]["porosity"]


def test_the_balloon_is_the_config_files():
    """DropletParams.balloon() on grains of radii 8 to 16 is results/calibration/balloon.toml, to the bit."""
    params = softdrop.DropletParams.balloon()
    assert params.nrt == 1.5e9 and params.viscosity_dilation == 1.0
    medium = softdrop.Medium.generate(**balloon.GRAINS)
    run = softdrop.simulate(medium, x0=250, params=params, run=softdrop.RunOptions(max_steps=2000000))
    theirs = json.loads(cli("--config", balloon.CONFIG, "simulate", "--x0", "250", "--format", "json"))
    assert run.tortuosity == theirs["run"]["tortuosity"] and run.steps == theirs["run"]["steps"]


@pytest.mark.parametrize("factory, config, step", [("explicit_step", "explicit.toml", "explicit"),
                                                    ("exponential_step", "exponential.toml", "exponential")])
def test_the_other_viscosity_steps_are_the_config_files(factory, config, step):
    """DropletParams.explicit_step() and .exponential_step() are their config files, to the bit."""
    params = getattr(softdrop.DropletParams, factory)()
    defaults = softdrop.DropletParams()
    assert params.viscosity_step == step and defaults.viscosity_step == "implicit"
    assert params.viscosity != defaults.viscosity or params.dt != defaults.dt
    run = softdrop.simulate(softdrop.Medium.generate(), x0=250, params=params)
    config = str(pathlib.Path(balloon.CONFIG).with_name(config))
    theirs = json.loads(cli("--config", config, "simulate", "--x0", "250", "--format", "json"))
    assert run.tortuosity == theirs["run"]["tortuosity"] and run.steps == theirs["run"]["steps"]
    assert run.tortuosity != softdrop.simulate(softdrop.Medium.generate(), x0=250).tortuosity


def test_the_passage_droplet_is_the_config_files():
    """DropletParams.passage() on grains of radii 26 to 50 is results/calibration/passage.toml, to the bit."""
    params = softdrop.DropletParams.passage()
    assert params.radius == 5 and params.viscosity == 1e6 and params.viscosity_step == "exponential"
    run = softdrop.simulate(softdrop.Medium.generate(r_min=26, r_max=50), x0=250, params=params)
    config = str(pathlib.Path(balloon.CONFIG).with_name("passage.toml"))
    theirs = json.loads(cli("--config", config, "simulate", "--x0", "250", "--format", "json"))
    assert run.tortuosity == theirs["run"]["tortuosity"] and run.steps == theirs["run"]["steps"]


def test_every_droplet_option_is_an_attribute_and_gives_the_programs_bits():
    params = softdrop.DropletParams()
    help_text = cli("simulate", "--help")
    droplet_group = help_text[help_text.index("Droplet"):]
    options = [w[2:] for w in droplet_group.split() if w.startswith("--")]
    options = options[:options.index("max-steps")] if "max-steps" in options else options
    assert "constraint-order" in options and "viscosity" in options
    for option in options:
        assert hasattr(params, option.replace("-", "_")), option
    medium = softdrop.Medium.generate()
    params = softdrop.DropletParams(constraint_order="red-black", radius=7.5)
    run = softdrop.simulate(medium, x0=250, params=params)
    theirs = json.loads(cli("simulate", "--x0", "250", "--constraint-order", "red-black", "--radius", "7.5",
                            "--format", "json"))
    assert run.tortuosity == theirs["run"]["tortuosity"]  # exactly
    assert run.steps == theirs["run"]["steps"]
    with pytest.raises(ValueError, match="constraint_order = 'zigzag'"):
        params.constraint_order = "zigzag"
    # The other enum, the viscosity's step, the same way; nu dt = 3.5 runs only exponentially or
    # implicitly.
    params = softdrop.DropletParams(viscosity_step="exponential", viscosity=1e6)
    assert params.viscosity_step == "exponential"
    run = softdrop.simulate(medium, x0=250, params=params)
    theirs = json.loads(cli("simulate", "--x0", "250", "--viscosity-step", "exponential", "--viscosity", "1e6",
                            "--format", "json"))
    assert run.tortuosity == theirs["run"]["tortuosity"] and run.steps == theirs["run"]["steps"]
    with pytest.raises(ValueError, match="viscosity_step = 'backward'"):
        params.viscosity_step = "backward"


def test_the_area_trace_is_the_programs(tmp_path):
    medium = softdrop.Medium.generate(width=200, height=200)
    run = softdrop.simulate(medium, x0=100, trace=True, trace_interval=50)
    csv = tmp_path / "trace.csv"
    cli("simulate", "--width", "200", "--height", "200", "--x0", "100", "--trace", str(csv), "--trace-interval", "50",
        "--quiet")
    theirs = pd.read_csv(csv, float_precision="round_trip")
    assert run.trace.shape == (len(theirs), 3)
    assert run.trace[:, 0].tolist() == theirs["time"].tolist() and run.trace[:, 1].tolist() == theirs["area"].tolist()
    assert np.allclose(run.trace[:, 2], theirs["area_ratio"], rtol=1e-15, equal_nan=True)
    inside = theirs["phase"] == "inside"
    assert (theirs.loc[inside, "time"] >= run.enter).all() and run.s0 > 0
    assert run.inside_min_area_ratio <= theirs.loc[inside, "area_ratio"].min()
    assert run.outcome == softdrop.simulate(medium, x0=100).outcome  # the trace is of the same run
    # Asked for both, the path is the run's own, as with path=True alone.
    both = softdrop.simulate(medium, x0=100, path=True, trace=True, trace_interval=50)
    alone = softdrop.simulate(medium, x0=100, path=True)
    assert len(alone.path) > 10 and np.array_equal(both.path, alone.path)
    assert np.array_equal(both.trace, run.trace)
    with pytest.raises(ValueError, match="trace_interval = 0"):
        softdrop.simulate(medium, trace=True, trace_interval=0)


def test_many_droplets_are_the_programs_rows(tmp_path):
    medium = softdrop.Medium.generate(width=200, height=200)
    frame = softdrop.simulate_many(medium, 12, seed=3, threads=2)
    csv = tmp_path / "runs.csv"
    cli("simulate", "--width", "200", "--height", "200", "--droplets", "12", "--seed", "3", "--runs", str(csv), "--quiet")
    theirs = pd.read_csv(csv, float_precision="round_trip")  # the default parser may miss the last bit
    assert list(frame.columns) == list(theirs.columns) + ["reason"]
    for column in ["start_x", "steps", "touched", "min_area_ratio", "max_penetration"]:
        assert frame[column].tolist() == theirs[column].tolist(), column
    assert frame["outcome"].tolist() == theirs["outcome"].tolist()
    passed = frame["outcome"] == "passed"
    assert frame.loc[passed, "tortuosity"].tolist() == theirs.loc[passed, "tortuosity"].tolist()
    # Never shaken: no shaking time, and the route is the path.
    assert frame["shaken_at"].isna().all() and theirs["shaken_at"].isna().all()
    assert frame.loc[passed, "route_tortuosity"].tolist() == frame.loc[passed, "tortuosity"].tolist()
    assert frame.loc[~passed, "tortuosity"].isna().all()
    assert frame.dtypes["steps"] == np.int64 and frame.dtypes["tortuosity"] == np.float64


def test_media_as_arrays_files_and_images(tmp_path):
    medium = softdrop.Medium.generate("non-overlapping", porosity=0.8, width=200, height=200, seed=4)
    grains = medium.grains
    assert grains.shape == (len(medium), 3)
    again = softdrop.Medium.from_arrays(grains[:, 0], grains[:, 1], grains[:, 2], medium.width, medium.height)
    assert np.array_equal(again.grains, grains) and again.porosity() == medium.porosity()
    path = tmp_path / "m.csv"
    medium.save(str(path))
    assert np.array_equal(softdrop.Medium.load(str(path)).grains, grains)
    theirs = tmp_path / "theirs.json"
    cli("simulate", "--kind", "non-overlapping", "--porosity", "0.8", "--width", "200", "--height", "200",
        "--medium-seed", "4", "--save-medium", str(theirs))
    assert np.array_equal(softdrop.Medium.load(str(theirs)).grains, grains)
    image = medium.to_image(400)
    assert image.shape == (400, 400) and image.dtype == bool
    assert abs(image.mean() - medium.porosity()) < 0.01  # pore fraction of the pixels


def test_relaxed_media_are_the_programs_and_keep_their_gaps(tmp_path):
    """A relaxed medium at porosity 0.5 with gaps of 0.4 of the larger radius, which random
    sequential addition cannot place: the program's grains to the bit, every gap kept."""
    medium = softdrop.Medium.generate("relaxed", porosity=0.5, gap=0.4, seed=3)
    theirs = tmp_path / "theirs.json"
    cli("simulate", "--kind", "relaxed", "--porosity", "0.5", "--gap", "0.4", "--medium-seed", "3",
        "--save-medium", str(theirs))
    assert np.array_equal(softdrop.Medium.load(str(theirs)).grains, medium.grains)
    x, y, r = medium.grains.T
    dx = np.abs(x[:, None] - x[None, :])
    dx = np.minimum(dx, medium.width - dx)
    gap = np.hypot(dx, y[:, None] - y[None, :]) - r[:, None] - r[None, :]
    need = 0.4 * np.maximum(r[:, None], r[None, :])
    assert np.all((gap >= need) | np.eye(len(r), dtype=bool))
    assert abs(medium.porosity() - 0.5) < 0.015
    with pytest.raises(ValueError, match="unreachable for non-overlapping grains with gap 0.4"):
        softdrop.Medium.generate("non-overlapping", porosity=0.5, gap=0.4, seed=3)


def test_rigid_descent_stops_in_a_notch_and_passes_a_gap():
    # Grains of radius 50 at x = 200 and 280 meet at (240, 280); one at 400 leaves a gap of 20.
    medium = softdrop.Medium.from_arrays([200, 280, 400], [250, 250, 250], [50, 50, 50], 500, 500)
    runs = softdrop.rigid_descent(medium, [230, 330, 350, 475], radius=4)
    assert list(runs.columns) == ["start_x", "outcome", "tortuosity", "x", "y", "slides"]
    assert list(runs.outcome) == ["stuck", "passed", "passed", "passed"]
    notch = runs.iloc[0]
    assert notch.x == pytest.approx(240) and notch.y == pytest.approx(250 + math.sqrt(54**2 - 40**2))
    assert math.isnan(notch.tortuosity)
    assert runs.x[1] == pytest.approx(334) and runs.x[2] == pytest.approx(346)  # off each side of the gap
    assert runs.tortuosity[3] == 1.0 and runs.slides[3] == 0
    wide = softdrop.rigid_descent(medium, 340, radius=11, path=True)  # a scalar start: one row
    assert len(wide) == 1 and wide.outcome[0] == "stuck"
    assert wide.path[0].shape[1] == 2 and tuple(wide.path[0][-1]) == (wide.x[0], wide.y[0])
    with pytest.raises(ValueError, match="radius = -1: must be finite and >= 0"):
        softdrop.rigid_descent(medium, 10, radius=-1)


@pytest.mark.parametrize("call, says", [
    (lambda: softdrop.Medium.generate(porosity=1.5), "porosity = 1.5: must be in (0, 1)"),
    (lambda: softdrop.Medium.generate(kind="sponge"), "sponge"),
    (lambda: softdrop.Medium.from_arrays([1, 2], [1], [3, 3], 100, 100), "x, y, r: must have the same length"),
    (lambda: softdrop.DropletParams(masess=30), "masess: not a parameter of DropletParams"),
    (lambda: softdrop.simulate(softdrop.Medium.generate(width=100, height=100), params=softdrop.DropletParams(masses=-3)),
     "masses"),
    (lambda: softdrop.simulate(softdrop.Medium.generate(width=100, height=100), x0=-5), "x0 = "),
    (lambda: softdrop.simulate_many(softdrop.Medium.generate(width=100, height=100), 0), "n = 0"),
    (lambda: softdrop.simulate_many(softdrop.Medium.generate(width=100, height=100), 3, threads=-5),
     "threads = -5: must be in [0, "),
    (lambda: softdrop.sweep("never.db", porosities=[]), "porosities: an empty list"),
])
def test_bad_input_raises_value_error_naming_it(call, says):
    with pytest.raises(ValueError) as error:
        call()
    assert says in str(error.value)
    assert "\n" not in str(error.value)


def test_a_missing_grain_file_is_named():
    with pytest.raises(Exception) as error:
        softdrop.Medium.load("/nonexistent/grains.json")
    assert "/nonexistent/grains.json" in str(error.value)


def test_run_options_end_runs_as_the_program_does():
    medium = softdrop.Medium.generate(width=200, height=200)
    run = softdrop.simulate(medium, x0=20, run=softdrop.RunOptions(max_steps=50))
    assert run.outcome == "timeout" and run.steps == 50 and math.isnan(run.tortuosity)


def test_a_search_history_reads_as_the_program_reads_it(tmp_path):
    db = tmp_path / "search.db"
    cli("optimize", "--db", str(db), "--grains", "16", "--width", "160", "--height", "120", "--medium-seed", "2",
        "--stuck-window", "0.1", "--stuck-distance", "1", "--generations", "6", "--lambda", "2", "--quiet",
        "--objective", "single", *balloon.ARGS)
    h = softdrop.read_history(db)
    theirs = json.loads(cli("history", "--db", str(db), "--run", "1", "--format", "json"))
    assert len(h["runs"]) == 1 and h["runs"].loc[0, "generations"] == 6
    assert h["runs"].loc[0, "evaluations"] == len(h["candidates"]) == 1 + 6 * 2
    assert h["runs"].loc[0, "droplets"] == 1 + 6 * 2 and (h["candidates"]["droplets"] == 1).all()
    assert h["generations"]["parent_tortuosity"].isna().all() and h["generations"]["parent_passed"].isna().all()
    assert h["generations"]["best_tortuosity"].tolist() == [g["best_tortuosity"] for g in theirs]
    assert h["generations"].dtypes["accepted_candidate"] == "Int64"
    passed = h["candidates"]["outcome"] == "passed"
    assert h["candidates"].loc[~passed, "tortuosity"].isna().all()
    best = softdrop.best_arrangement(db, run=1)
    assert best.tortuosity == h["runs"].loc[0, "best_tortuosity"]
    # The stored arrangement pushes the same droplet to the same T.
    params = softdrop.DropletParams.balloon()
    again = softdrop.simulate(best.medium, run=softdrop.RunOptions(stuck_window=0.1, stuck_distance=1), params=params)
    assert again.tortuosity == best.tortuosity


def test_a_foreign_database_raises_store_error_naming_it(tmp_path):
    bad = tmp_path / "notes.db"
    bad.write_text("not a database at all " * 40)
    with pytest.raises(softdrop.StoreError) as error:
        softdrop.read_history(bad)
    assert str(bad) in str(error.value)


def test_the_example_runs(tmp_path):
    here = os.path.dirname(os.path.abspath(__file__))
    example = os.path.join(here, "..", "..", "examples", "python", "droplets.py")
    env = dict(os.environ, PATH=os.path.dirname(CLI) + os.pathsep + os.environ.get("PATH", ""))
    done = subprocess.run([sys.executable, example], cwd=tmp_path, env=env, capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert "search: best T" in done.stdout and "generation 30: best T" in done.stdout
    for picture in ("droplet_path.png", "search_curve.png"):  # matplotlib is among the test packages
        assert (tmp_path / picture).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_ctrl_c_stops_a_long_run(tmp_path):
    script = tmp_path / "long.py"
    script.write_text(
        "import softdrop\n"
        "m = softdrop.Medium.from_arrays([81, 119], [300, 300], [16, 16], 200, 400)  # a pore too narrow to pass\n"
        "print('started', flush=True)\n"
        "try:\n"
        "    softdrop.simulate(m, x0=100, run=softdrop.RunOptions(max_steps=10**9, stuck_window=1e6, stuck_distance=0, rest_window=0))\n"
        "except KeyboardInterrupt:\n"
        "    print('interrupted', flush=True)\n")
    child = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, text=True, env=dict(os.environ))
    assert child.stdout.readline().strip() == "started"
    import signal
    import time
    time.sleep(1.0)  # well into the run (a droplet held in the pore, with no stuck test, runs for minutes)
    child.send_signal(signal.SIGINT)
    out, _ = child.communicate(timeout=60)
    assert "interrupted" in out


def test_a_robust_search_reads_with_its_droplets_and_re_runs(tmp_path):
    db = tmp_path / "robust.db"
    cli("optimize", "--db", str(db), "--grains", "16", "--width", "160", "--height", "120", "--medium-seed", "2",
        "--stuck-window", "0.1", "--stuck-distance", "1", "--generations", "3", "--lambda", "2", "--quiet",
        "--validate-starts", "0", "--objective", "mean", "--starts", "4", *balloon.ARGS)
    h = softdrop.read_history(db, arrangements=False)
    assert h["runs"].loc[0, "droplets"] == 4 + 3 * (2 * 4 + 4)
    assert (h["candidates"]["droplets"] == 4).all()
    later = h["generations"]["generation"] > 0
    assert h["generations"].loc[later, "parent_passed"].between(0, 4).all()
    assert h["generations"].loc[~later, "parent_tortuosity"].isna().all()


def _tortuosity_in_a_worker(medium, params):
    return softdrop.simulate(medium, x0=200, params=params).tortuosity


def test_parameters_and_media_are_values_that_cross_to_worker_processes():
    import concurrent.futures
    import copy
    import multiprocessing
    import pickle

    medium = softdrop.Medium.generate("non-overlapping", porosity=0.8, seed=1)
    params = softdrop.DropletParams(radius=7, viscosity_step="explicit", dt=3e-6)
    run = softdrop.RunOptions(max_steps=10**6, path_interval=50)
    for value in (medium, params, run):
        assert pickle.loads(pickle.dumps(value)) == value
        assert copy.deepcopy(value) == value and copy.copy(value) == value
    assert pickle.loads(pickle.dumps(medium)).grains.tobytes() == medium.grains.tobytes()  # to the bit
    # A repr names what differs from the defaults, and reads back.
    assert repr(softdrop.DropletParams()) == "softdrop.DropletParams()"
    assert repr(params) == "softdrop.DropletParams(radius=7.0, dt=3e-06, viscosity_step='explicit')"
    assert eval(repr(params), {"softdrop": softdrop}) == params
    assert repr(run) == "softdrop.RunOptions(max_steps=1000000, path_interval=50)"
    assert params != softdrop.DropletParams() and medium != softdrop.Medium.generate(seed=2)
    # A copy is its own: changing it leaves the original.
    other = copy.deepcopy(params)
    other.radius = 6
    assert params.radius == 7
    # The grains are a copy, so a write to them is refused rather than lost.
    with pytest.raises(ValueError, match="read-only"):
        medium.grains[0, 0] = 1.0
    # A worker process gets the same droplet in the same medium: the same bits.
    here = softdrop.simulate(medium, x0=200, params=params).tortuosity
    with concurrent.futures.ProcessPoolExecutor(2, mp_context=multiprocessing.get_context("spawn")) as pool:
        assert pool.submit(_tortuosity_in_a_worker, medium, params).result() == here


def test_pore_space_tortuosities_of_a_medium_and_of_its_image_are_the_programs(tmp_path):
    medium = softdrop.Medium.generate(porosity=0.7, seed=3, width=200, height=200, r_min=8, r_max=16)
    r = softdrop.tortuosity(medium, pixels=100)
    image = medium.to_image(100)  # True in the pore space, rows from the top
    s = softdrop.tortuosity(image, pixel_size=2.0)
    assert (r.geometric_tortuosity, r.diffusive_tortuosity, r.porosity) == (s.geometric_tortuosity, s.diffusive_tortuosity, s.porosity)
    assert r.porosity == image.mean()
    # The program's coarser resolution is this one.
    path = tmp_path / "m.json"
    medium.save(path)
    out = json.loads(subprocess.run([CLI, "tortuosity", "--medium", str(path), "--pixels", "100", "--starts", "0",
                                     "--quiet", "--format", "json"], capture_output=True, text=True, check=True).stdout)
    assert out["geometric_tortuosity"]["values"][0] == r.geometric_tortuosity and out["diffusive_tortuosity"]["values"][0] == r.diffusive_tortuosity
    # The fields: the top row's distances give the geometric T; the concentration runs from 1 to 0.
    assert r.distance.shape == r.concentration.shape == image.shape
    top = r.distance[0][np.isfinite(r.distance[0])]
    assert np.isclose((top + r.pixel / 2).mean() / medium.height, r.geometric_tortuosity, rtol=1e-12, atol=0)
    assert np.all(np.isnan(r.concentration[~image]))
    assert np.nanmin(r.concentration) > 0 and np.nanmax(r.concentration) < 1
    assert np.nanmean(r.concentration[0]) > 0.9 and np.nanmean(r.concentration[-1]) < 0.1
    # The flow: the program's numbers, and its fields in the pore space only, running down.
    assert out["hydrodynamic_tortuosity"]["values"][0] == r.hydrodynamic_tortuosity == s.hydrodynamic_tortuosity
    assert out["permeability"]["values"][0] == r.permeability == s.permeability
    assert r.velocity_x.shape == r.velocity_y.shape == r.pressure.shape == image.shape
    assert np.array_equal(np.isnan(r.velocity_y), np.isnan(r.concentration))  # the solid and closed pockets
    assert np.all(np.isnan(r.velocity_y[~image]))
    open_ = ~np.isnan(r.velocity_y)
    speed = np.hypot(r.velocity_x, r.velocity_y)[open_]
    assert np.isclose(speed.mean() / -r.velocity_y[open_].mean(), r.hydrodynamic_tortuosity, rtol=1e-12, atol=0)
    assert "hydrodynamic_tortuosity" not in softdrop.tortuosity(image, pixel_size=2.0, flow=False)


def test_the_flow_through_slits_is_plane_poiseuille():
    """Slits w pixels wide in a unit cell periodic in y (buffer_rows=0): the staggered grid's
    permeability is phi (w^2 + 2) h^2 / 12 exactly, the continuum's phi w^2 h^2 / 12 plus h^2 / 6."""
    w, h = 12, 0.25
    image = np.tile(np.arange(4 * w) % (2 * w) < w, (30, 1))  # columns: w open, w solid
    r = softdrop.tortuosity(image, pixel_size=h, buffer_rows=0)
    assert r.permeability == pytest.approx(0.5 * (w * w + 2) * h * h / 12, rel=1e-9)
    assert r.hydrodynamic_tortuosity == pytest.approx(1.0, abs=1e-12)
    with pytest.raises(ValueError, match="buffer_rows = -2: must be >= -1"):
        softdrop.tortuosity(image, buffer_rows=-2)


@pytest.mark.parametrize("image, says", [
    (np.full((20, 20), 0.5), "not binary"),
    (np.zeros((0, 5), dtype=bool), "empty"),
    (np.ones(5, dtype=bool), "a 2D array"),
    (np.vstack([np.ones((9, 20)), np.zeros((1, 20)), np.ones((10, 20))]).astype(bool), "no pore path"),
])
def test_a_bad_image_gets_one_line_naming_it(image, says):
    with pytest.raises(ValueError, match=says):
        softdrop.tortuosity(image)
    with pytest.raises(ValueError, match="pixel_size"):
        softdrop.tortuosity(np.ones((4, 4), dtype=bool), pixel_size=float("nan"))


def test_a_shaken_medium_frees_a_droplet_at_rest(tmp_path):
    # Two overlapping grains make a closed V that holds the droplet; shaken sideways from when it
    # comes to rest, it climbs out (tests/vibration_test.cpp has the same pocket).
    pocket = tmp_path / "v.json"
    pocket.write_text(json.dumps({"format": "softdrop-medium", "version": 1, "width": 200, "height": 120,
                                  "periodic": True, "grains": [{"x": 80, "y": 60, "r": 30},
                                                               {"x": 120, "y": 60, "r": 30}]}))
    still = softdrop.simulate(pocket, x0=100)
    assert still.outcome == "stuck" and math.isnan(still.shaken_at)
    params = softdrop.DropletParams(vibration_amplitude=4.0, vibration_frequency=100.0, vibration_axis="x")
    assert pickle.loads(pickle.dumps(params)) == params and "vibration_amplitude=4.0" in repr(params)
    freed = softdrop.simulate(pocket, x0=100, params=params)
    assert freed.outcome == "passed"
    assert freed.shaken_at == pytest.approx(still.steps * params.dt, rel=1e-12)
    assert 1 < freed.route_tortuosity < freed.tortuosity
    with pytest.raises(ValueError, match="vibration_axis = 'z'"):
        params.vibration_axis = "z"
