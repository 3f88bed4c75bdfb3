"""Two droplets one after the other from Python: the program's pairs, the same bits, and refusals
that name the argument."""
import math
import os
import subprocess

import pandas as pd
import pytest

import softdrop

CLI = os.environ["SOFTDROP_CLI"]


def test_simulate_pairs_is_the_programs_pairs(tmp_path):
    medium = softdrop.Medium.generate("non-overlapping", porosity=0.79, seed=3, width=200, height=200)
    path = tmp_path / "m.json"
    medium.save(path)
    runs = tmp_path / "runs.csv"
    subprocess.run([CLI, "simulate", "--medium", str(path), "--droplets", "3", "--seed", "5", "--quiet",
                    "--second-droplet", "distance", "--second-after", "20", "--runs", str(runs)],
                   check=True, capture_output=True)
    program = pd.read_csv(runs, float_precision="round_trip")  # the default parser can miss by an ulp
    frame = softdrop.simulate_pairs(medium, 3, seed=5, after=20.0)
    assert list(frame.columns[:-1]) == list(program.columns)
    assert len(frame) == 6 and list(frame["order"]) == [1, 2, 1, 2, 1, 2]
    for column in ["start_x", "tortuosity", "steps", "touched", "contact_steps", "shared_touched", "released_at"]:
        pd.testing.assert_series_equal(frame[column], program[column], check_dtype=False, check_exact=True)


def test_simulate_pair_gives_each_droplet_its_run_path_and_area():
    medium = softdrop.Medium.generate("non-overlapping", porosity=0.79, seed=3, width=200, height=200)
    pair = softdrop.simulate_pair(medium, x0=100.0, after=20.0, path=True, trace=True, trace_interval=50)
    assert pair.released and pair.released_at > 0
    for droplet in (pair.first, pair.second):
        assert droplet.outcome in ("passed", "stuck")
        assert droplet.path.shape[1] == 2 and len(droplet.path) == len(droplet.path_time)
        assert droplet.trace.shape[1] == 2 and droplet.trace[0, 0] == 0
        assert math.isnan(droplet.held_at) or droplet.held_at > 0
    # Both start as the same ring at rest: the same area, to the bit.
    assert pair.first.trace[0, 1] == pair.second.trace[0, 1] > 0
    # The first droplet's run is simulate's until the rings meet; apart, it is simulate's to the bit.
    apart = softdrop.simulate_pair(medium, x0=40.0, after=20.0, offset_x=100.0)
    assert apart.contact_steps == 0
    for droplet, x0 in ((apart.first, 40.0), (apart.second, 140.0)):
        alone = softdrop.simulate(medium, x0=x0)
        assert droplet.outcome == alone.outcome and droplet.steps == alone.steps
        assert droplet.tortuosity == alone.tortuosity or math.isnan(alone.tortuosity)


def test_a_bad_second_droplet_raises_value_error_naming_it():
    medium = softdrop.Medium.generate("non-overlapping", porosity=0.79, seed=3, width=200, height=200)
    with pytest.raises(ValueError, match="release = 'later'"):
        softdrop.simulate_pair(medium, release="later")
    with pytest.raises(ValueError, match="after = 5: the second droplet would start overlapping"):
        softdrop.simulate_pair(medium, after=5.0)
    with pytest.raises(ValueError, match="after = nan"):
        softdrop.simulate_pairs(medium, 2, after=float("nan"))
    with pytest.raises(TypeError, match="n: a whole number"):
        softdrop.simulate_pairs(medium, 2.5)


def test_a_shaken_medium_shakes_both_droplets_from_when_it_began():
    medium = softdrop.Medium.generate("non-overlapping", porosity=0.79, seed=3, width=200, height=200)
    params = softdrop.DropletParams(vibration_amplitude=2.0, vibration_frequency=100.0, vibration_start="start")
    pair = softdrop.simulate_pair(medium, x0=100.0, after=20.0, params=params)
    assert pair.released
    # Both feel the medium shaking from their own starts: it shook before the second was released.
    assert pair.first.shaken_at == 0.0 and pair.second.shaken_at == 0.0


def test_a_sweep_of_pairs_stores_the_seconds_beside_their_firsts(tmp_path):
    db = tmp_path / "pairs.db"
    summary = softdrop.sweep(db, porosities=[0.79], kind="non-overlapping", width=200, height=200, media=2,
                             droplets=4, second_droplet="distance", second_after=20, quiet=True)
    assert summary["done"] == 2
    frames = softdrop.read_sweep(db)
    firsts, seconds = frames["droplets"], frames["second_droplets"]
    assert len(firsts) == 8 and 0 < len(seconds) <= 8
    pairs = seconds.merge(firsts, on=["sweep", "porosity_index", "medium_index", "droplet"], suffixes=("", "_first"))
    assert len(pairs) == len(seconds)
    assert (pairs["start_x"] == pairs["start_x_first"]).all()  # no offset: the pair's one start
    assert (pairs["released_at"] > 0).all() and (pairs["contact_steps"] >= 0).all()
    # Where the rings never met and neither was held, the second ran the first's run again, to the bit.
    alone = pairs[(pairs["contact_steps"] == 0) & pairs["held_at"].isna() & pairs["first_held_at"].isna()]
    assert (alone["steps"] == alone["steps_first"]).all()
    assert alone["tortuosity"].equals(alone["tortuosity_first"])
    # The same call continues the same sweep; a pair that would start overlapping is refused by its keyword.
    assert softdrop.sweep(db, porosities=[0.79], kind="non-overlapping", width=200, height=200, media=2,
                          droplets=4, second_droplet="distance", second_after=20, quiet=True)["sweep"] == 1
    with pytest.raises(ValueError, match="second_after = 5: the second droplet would start overlapping"):
        softdrop.sweep(tmp_path / "no.db", second_droplet="distance", second_after=5, quiet=True)
    assert not (tmp_path / "no.db").exists()
