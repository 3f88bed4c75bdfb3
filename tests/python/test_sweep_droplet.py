"""softdrop.sweep_droplet: one droplet of a stored sweep, run again as the sweep ran it."""

import math

import pytest

import softdrop
import balloon

# The balloon's droplet (not the defaults'), a small box and a rest test of its own: what the sweep
# stored must come back through the medium, the droplet and the exit options alike.
SWEEP = dict(porosities=[0.7, 0.9], media=2, droplets=4, width=200, height=200, rest_window=0.02, quiet=True,
             **balloon.OPTIONS)


def same(a, b):
    return a == b or (math.isnan(a) and math.isnan(b))


def test_every_droplet_of_a_sweep_runs_again_to_the_stored_bits(tmp_path):
    db = tmp_path / "s.db"
    softdrop.sweep(db, **SWEEP)
    stored = softdrop.read_sweep(db)["droplets"]
    assert set(stored.outcome) >= {"passed"}
    for row in stored.itertuples():
        d = softdrop.sweep_droplet(db, row.porosity_index, row.medium_index, row.droplet)
        assert d.params == softdrop.DropletParams.balloon() and d.run.rest_window == 0.02
        assert d.medium.width == 200 and d.target_porosity == SWEEP["porosities"][row.porosity_index]
        assert d.x0 == row.start_x and d.outcome == row.outcome and d.steps == row.steps
        assert same(d.tortuosity, row.tortuosity)
        again = softdrop.simulate(d.medium, x0=d.x0, params=d.params, run=d.run, path=True)
        assert (again.outcome, again.steps) == (row.outcome, row.steps)
        assert same(again.tortuosity if again.outcome == "passed" else math.nan, row.tortuosity)
        assert len(again.path) > 0


def test_the_seed_is_the_stored_one_a_whole_number_beyond_int64(tmp_path):
    db = tmp_path / "s.db"
    softdrop.sweep(db, **dict(SWEEP, porosities=[0.9], media=1, droplets=1))
    media = softdrop.read_sweep(db)["media"]
    d = softdrop.sweep_droplet(db, 0, 0, 0)
    assert d.medium_seed == int(media.medium_seed.iloc[0]) and d.medium_seed >= 0
    assert d.porosity == media.porosity.iloc[0]


@pytest.mark.parametrize("call, error, says", [
    (lambda db: softdrop.sweep_droplet(db, 2, 0, 0), ValueError, r"^porosity_index = 2: must be in \[0, 2\)$"),
    (lambda db: softdrop.sweep_droplet(db, 0, -1, 0), ValueError, r"^medium_index = -1: must be in \[0, 2\)$"),
    (lambda db: softdrop.sweep_droplet(db, 0, 0, 4), ValueError, r"^droplet = 4: must be in \[0, 4\)$"),
    (lambda db: softdrop.sweep_droplet(db, 0, 0, 1.0), TypeError, r"^droplet: a whole number, not 1.0$"),
    (lambda db: softdrop.sweep_droplet(db, 0, 0, 0, sweep=0), ValueError, r"^sweep = 0: sweep ids"),
    (lambda db: softdrop.sweep_droplet(db, 0, 0, 0, sweep=7), softdrop.StoreError, "7"),
])
def test_a_droplet_the_sweep_does_not_have_is_refused_by_name(tmp_path, call, error, says):
    db = tmp_path / "s.db"
    softdrop.sweep(db, **SWEEP)
    before = db.read_bytes()
    with pytest.raises(error, match=says):
        call(db)
    assert db.read_bytes() == before


def test_a_medium_not_yet_stored_two_sweeps_and_pairs_are_refused(tmp_path):
    db = tmp_path / "s.db"
    softdrop.sweep(db, **SWEEP, shard="0/2")  # half of its media
    stored = softdrop.read_sweep(db)["media"]
    missing = next((p, m) for p in range(2) for m in range(2)
                   if not ((stored.porosity_index == p) & (stored.medium_index == m)).any())
    with pytest.raises(ValueError, match=rf"has not stored medium {missing[1]} of porosity_index {missing[0]}"):
        softdrop.sweep_droplet(db, *missing, 0)
    softdrop.sweep(db, **(SWEEP | dict(seed=2)))
    with pytest.raises(ValueError, match="holds 2 sweeps"):
        softdrop.sweep_droplet(db, 0, 0, 0)
    assert softdrop.sweep_droplet(db, 0, 0, 0, sweep=2).sweep == 2
    pairs = tmp_path / "pairs.db"
    softdrop.sweep(pairs, **dict(SWEEP, porosities=[0.9], media=1, droplets=1, second_droplet="distance"))
    with pytest.raises(ValueError, match="a sweep of pairs"):
        softdrop.sweep_droplet(pairs, 0, 0, 0)
