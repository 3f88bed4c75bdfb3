"""Arguments the module refuses, by name, before anything is read or written: a database that is
not a file name, ids below 1, a generation a run does not have, and options whose values a file
would overwrite."""
import os
import signal
import sqlite3
import threading
import time

import pytest

import softdrop

import balloon

SEARCH = dict(objective="single", grains=16, width=160, height=120, medium_seed=2, stuck_window=0.1, stuck_distance=1, lambda_=2,
              quiet=True, validate_starts=0, **balloon.OPTIONS)


@pytest.fixture(scope="module")
def history(tmp_path_factory):
    db = tmp_path_factory.mktemp("refusals") / "h.db"
    softdrop.optimize(db, generations=2, **SEARCH)
    return db


@pytest.mark.parametrize("db", [None, 3, b"h.db", ["h.db"]])
def test_a_database_must_be_a_file_name(tmp_path, db):
    os.chdir(tmp_path)
    with pytest.raises(TypeError, match="db: a file name"):
        softdrop.optimize(db, generations=1)
    with pytest.raises(TypeError, match="db: a file name"):
        softdrop.read_history(db)
    assert os.listdir(tmp_path) == []  # no file named None


def test_an_empty_database_name_is_refused(tmp_path):
    os.chdir(tmp_path)
    for call in (lambda: softdrop.optimize("", generations=1), lambda: softdrop.sweep(""),
                 lambda: softdrop.read_sweep("")):
        with pytest.raises(ValueError, match="an empty file name"):
            call()
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("sweep", [0, -1, 1.5, True])
def test_a_sweep_id_is_a_whole_number_from_1(tmp_path, sweep):
    with pytest.raises(ValueError, match="sweep = "):
        softdrop.read_sweep(tmp_path / "s.db", sweep=sweep)


@pytest.mark.parametrize("generation", [999, -5, 3])
def test_a_generation_the_run_does_not_have_is_refused(history, generation):
    with pytest.raises(ValueError, match=f"generation = {generation}: run 1 has stored generations 0 to 2"):
        softdrop.best_arrangement(history, 1, generation=generation)
    assert softdrop.best_arrangement(history, 1, generation=2).generation <= 2


def test_a_run_id_is_a_whole_number_from_1(history):
    with pytest.raises(ValueError, match="run = 0"):
        softdrop.best_arrangement(history, 0)


def test_an_output_over_the_database_is_refused(history):
    before = history.read_bytes()
    with pytest.raises(ValueError, match="json .*: the same file as db"):
        softdrop.optimize(history, resume=1, generations=3, json=str(history))
    assert history.read_bytes() == before


@pytest.mark.parametrize("params, says", [
    ("'{not json'", "run 1: its params are not JSON"),
    ("CAST(x'7bff7d' AS TEXT)", "column params holds text that is not UTF-8"),
])
def test_stored_params_that_cannot_be_read_raise_store_error_naming_the_file(history, tmp_path, params, says):
    db = tmp_path / "params.db"
    db.write_bytes(history.read_bytes())
    with sqlite3.connect(db) as c:
        c.execute(f"UPDATE runs SET params = {params}")
    c.close()
    with pytest.raises(softdrop.StoreError, match=f"'{db}'.*{says}"):
        softdrop.read_history(db)


def test_ctrl_c_stops_simulate_many_after_the_droplets_in_flight():
    medium = softdrop.Medium.generate(width=300, height=300)
    run = softdrop.RunOptions(rest_window=0)  # stuck droplets run their whole stuck test: a long batch
    t0 = time.perf_counter()
    softdrop.simulate_many(medium, 4, seed=5, threads=1, run=run)
    per_droplet = (time.perf_counter() - t0) / 4
    timer = threading.Timer(2 * per_droplet, os.kill, (os.getpid(), signal.SIGINT))
    timer.start()
    t0 = time.perf_counter()
    with pytest.raises(KeyboardInterrupt):
        softdrop.simulate_many(medium, 40, seed=5, threads=1, run=run)
    # Stopped after the droplet in flight, not after all 40.
    assert time.perf_counter() - t0 < 10 * per_droplet
    timer.join()


def test_rigid_descent_refuses_a_disc_wider_than_a_periodic_box():
    medium = softdrop.Medium.generate(width=300, height=300)
    with pytest.raises(ValueError, match="radius = 1e\\+308: the disc is wider than the box"):
        softdrop.rigid_descent(medium, [100], radius=1e308)


def test_a_medium_object_for_a_file_option_says_to_save_it(tmp_path):
    medium = softdrop.Medium.generate(width=300, height=300)
    with pytest.raises(TypeError, match="medium: a grain file name, not a Medium"):
        softdrop.optimize(tmp_path / "h.db", medium=medium, generations=1)
    assert not (tmp_path / "h.db").exists()


def test_a_sweep_callback_that_raised_is_not_called_again(tmp_path):
    calls = []

    def callback(event):
        calls.append(event["medium_index"])
        raise RuntimeError("stop here")

    with pytest.raises(RuntimeError, match="stop here"):
        softdrop.sweep(tmp_path / "s.db", callback=callback, porosities=[0.8], media=6, droplets=2, width=200,
                       height=200, threads=2, quiet=True)
    assert len(calls) == 1


def test_held_out_is_simulate_many_from_the_same_starts():
    medium = softdrop.Medium.generate(porosity=0.85, width=300, height=300)
    v = softdrop.held_out(medium, starts=12, seed=4)
    many = softdrop.simulate_many(medium, 12, seed=4)
    passed = many[many["outcome"] == "passed"]
    assert v.at_dt["passed"] == len(passed)
    assert v.at_dt["mean_tortuosity"] == pytest.approx(passed["tortuosity"].mean(), rel=1e-12)
    assert v.at_dt["median"] == pytest.approx(passed["tortuosity"].quantile(0.5), rel=1e-12)
    assert v.at_half_dt["dt"] == v.at_dt["dt"] / 2
    assert list(v.runs.columns) == ["start", "start_x", "dt", "outcome", "tortuosity", "steps"]
    assert len(v.runs) == 24
    with pytest.raises(ValueError, match="starts = 0"):
        softdrop.held_out(medium, starts=0)


def test_read_history_has_the_held_out_values(tmp_path):
    db = tmp_path / "h.db"
    end = softdrop.optimize(db, generations=2, **{**SEARCH, "validate_starts": 8})
    v = softdrop.read_history(db)["validations"]
    assert len(v) == 1 and v["starts"][0] == 8 and v["generation"][0] == end["best_generation"]
    assert v["mean_tortuosity"][0] == end["held_out"]["mean_tortuosity"]
    assert str(v["paired"].dtype) == "Int64"


def test_python_types_and_exceptions(tmp_path):
    import pathlib

    medium = softdrop.Medium.generate(porosity=0.85, width=300, height=300)
    path = pathlib.Path(tmp_path) / "m.json"
    medium.save(path)
    assert softdrop.Medium.load(path).grains.tolist() == medium.grains.tolist()
    assert softdrop.simulate(path, x0=150).outcome == softdrop.simulate(medium, x0=150).outcome
    with pytest.raises(FileNotFoundError, match="no such file"):
        softdrop.Medium.load(tmp_path / "nonexistent.json")
    with pytest.raises(TypeError, match="medium: a Medium or a grain file name, not NoneType"):
        softdrop.simulate(None)
    with pytest.raises(TypeError, match="n: a whole number, not 2.5"):
        softdrop.simulate_many(medium, 2.5)
    with pytest.raises(ValueError, match="seed = -1: must be >= 0"):
        softdrop.simulate_many(medium, 2, seed=-1)
    with pytest.raises(ValueError, match="porosity = 0.3: unreachable"):
        softdrop.Medium.generate("non-overlapping", porosity=0.3)
    with pytest.raises(softdrop.StoreError, match="folder '.*' does not exist"):
        softdrop.optimize(tmp_path / "nonexistent" / "x.db", generations=1)


@pytest.mark.parametrize("call, error, says", [
    (lambda: softdrop.Medium.generate(seed=-1), ValueError, r"^seed = -1: must be >= 0$"),
    (lambda: softdrop.Medium.generate(seed=2**64), ValueError, r"^seed = 18446744073709551616: must be < 2\*\*64$"),
    (lambda: softdrop.Medium.generate(porosity="0.8"), TypeError, r"^porosity: a number, not '0.8'$"),
    (lambda: softdrop.Medium.generate(porosity=True), TypeError, r"^porosity: a number, not True$"),
    (lambda: softdrop.Medium.generate(grains=2.0), TypeError, r"^grains: a whole number, not 2.0$"),
    (lambda: softdrop.Medium.generate(periodic="yes"), TypeError, r"^periodic: True or False, not 'yes'$"),
    (lambda: softdrop.Medium.generate("nonoverlapping"), ValueError,
     r"^kind = 'nonoverlapping': must be overlapping, non-overlapping or relaxed$"),
    (lambda: softdrop.Medium.generate(r_min=30, r_max=10), ValueError, r"^r_max = 10: must be >= r_min$"),
    (lambda: softdrop.Medium.generate().to_image(2.5), TypeError, r"^pixels: a whole number, not 2.5$"),
    (lambda: softdrop.Medium.from_arrays([1], [2], ["a"], 100, 100), TypeError, r"^r: a sequence of numbers"),
    (lambda: softdrop.Medium.from_image([[1, 0]], pixel_size="a"), TypeError, r"^pixel_size: a number, not 'a'$"),
    (lambda: softdrop.Medium.load(3), TypeError, r"^path: a file name \(str or os.PathLike\), not 3$"),
    (lambda: softdrop.Medium.generate().save(b"m.json"), TypeError, r"^path: a file name"),
    (lambda: softdrop.DropletParams(radius="big"), TypeError, r"^radius: a number, not 'big'$"),
    (lambda: softdrop.DropletParams(masses=24.5), TypeError, r"^masses: a whole number, not 24.5$"),
    (lambda: softdrop.DropletParams(vibration_axis=1), TypeError, r"^vibration_axis: a str, not 1$"),
    (lambda: softdrop.RunOptions(max_steps=1e6), TypeError, r"^max_steps: a whole number, not 1000000.0$"),
    (lambda: softdrop.simulate(softdrop.Medium.generate(), params=softdrop.DropletParams(vibration_amplitude=-1)),
     ValueError, r"^vibration_amplitude = -1: must be >= 0$"),
    (lambda: softdrop.simulate(softdrop.Medium.generate(), run=softdrop.RunOptions(max_steps=-1)), ValueError,
     r"^max_steps = -1: must be > 0$"),
    (lambda: softdrop.simulate(softdrop.Medium.generate(), x0=-100), ValueError, r"^x0 = -100.0: must be in"),
    (lambda: softdrop.optimize("h.db", generations=2.5), TypeError, r"^generations: a whole number, not 2.5$"),
    (lambda: softdrop.optimize("h.db", lambda_=2.5), TypeError, r"^lambda_: a whole number, not 2.5$"),
    (lambda: softdrop.optimize("h.db", porosity=0.5), TypeError,
     r"^optimize\(\) got an unexpected keyword argument 'porosity'$"),
    (lambda: softdrop.optimize("h.db", generatons=3), TypeError,
     r"^optimize\(\) got an unexpected keyword argument 'generatons' \(did you mean generations\?\)$"),
    (lambda: softdrop.optimize("h.db", r_max=-1), ValueError, r"^r_max = -1: must be >= r_min$"),
    (lambda: softdrop.sweep("nonexistent/s.db"), softdrop.StoreError, r"^db 'nonexistent/s.db': folder"),
    (lambda: softdrop.read_history("nonexistent.db"), softdrop.StoreError, r"^db 'nonexistent.db': no such file$"),
])
def test_bad_arguments_are_said_in_pythons_words(tmp_path, call, error, says):
    # One line naming the Python argument, in Python's spelling (r_max, db: not --db or r-max), with
    # numbers as Python writes them: not pybind11's list of overloads, and nothing written.
    os.chdir(tmp_path)
    with pytest.raises(error, match=says):
        call()
    assert os.listdir(tmp_path) == []


def test_numpy_numbers_are_taken():
    import numpy as np

    medium = softdrop.Medium.generate(porosity=np.float32(0.8), seed=np.uint8(3), grains=np.int64(0))
    assert medium == softdrop.Medium.generate(porosity=float(np.float32(0.8)), seed=3)
    assert medium.to_image(np.int16(40)).shape == (40, 40)
    assert softdrop.RunOptions(max_steps=np.int64(1000)).max_steps == 1000
    assert softdrop.Medium.from_arrays(np.array([50.0]), (50,), [10], 100, 100, periodic=np.True_).periodic
