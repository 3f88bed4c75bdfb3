"""optimize and sweep from Python against the program: the same options write the same records;
the callback stops a search that then resumes exactly; readers give the program's tables."""
import io
import json
import os
import signal
import subprocess
import sys
import threading
import time

import numpy as np
import pandas as pd
import pytest

import softdrop

import balloon

CLI = os.environ["SOFTDROP_CLI"]

# A small search scene (seconds) and a small sweep.
SEARCH = dict(objective="single", grains=16, width=160, height=120, medium_seed=2, stuck_window=0.1, stuck_distance=1, lambda_=2,
              quiet=True, validate_starts=0, **balloon.OPTIONS)
SEARCH_ARGS = ["--grains", "16", "--width", "160", "--height", "120", "--medium-seed", "2", "--stuck-window", "0.1",
               "--stuck-distance", "1", "--lambda", "2", "--quiet", "--validate-starts", "0", "--objective", "single"] + balloon.ARGS
SWEEP = dict(porosities=[0.8, 0.9], media=2, droplets=4, width=200, height=200, quiet=True)
SWEEP_ARGS = ["--porosities", "0.8,0.9", "--media", "2", "--droplets", "4", "--width", "200", "--height", "200",
              "--quiet"]
# Columns that hold wall times and dates, which differ between two runs of the same search.
CLOCKS = {"created", "updated", "finished", "seconds"}


def cli(*args):
    return subprocess.run([CLI, *args], capture_output=True, text=True, check=True).stdout


def without_clocks(frame):
    return frame.drop(columns=[c for c in frame.columns if c in CLOCKS])


def assert_same_history(a, b):
    for name in ("generations", "candidates", "grains", "paths"):
        pd.testing.assert_frame_equal(without_clocks(a[name]), without_clocks(b[name]), check_exact=True, obj=name)
    for column in ("generations", "evaluations", "best_tortuosity", "best_generation", "status"):
        assert a["runs"][column].tolist() == b["runs"][column].tolist(), column


def test_optimize_writes_the_programs_history(tmp_path):
    ours, theirs = tmp_path / "ours.db", tmp_path / "theirs.db"
    summary = softdrop.optimize(ours, generations=8, strategy="es", relocate_every=3, **SEARCH)
    cli("optimize", "--db", str(theirs), "--generations", "8", "--strategy", "es", "--relocate-every", "3", *SEARCH_ARGS)
    assert summary.termination == "generations" and summary.last_generation == 8
    a, b = softdrop.read_history(ours), softdrop.read_history(theirs)
    assert_same_history(a, b)
    assert summary.best_tortuosity == b["runs"].loc[0, "best_tortuosity"]
    pd.testing.assert_frame_equal(a["params"], b["params"])
    assert a["params"].loc[0, "strategy"] == "es" and a["params"].loc[0, "relocate-every"] == 3


def test_a_search_stopped_by_the_callback_resumes_as_if_never_stopped(tmp_path):
    events = []

    def stop_at_4(event):
        events.append(event)
        return event["generation"] < 4

    stopped, whole = tmp_path / "stopped.db", tmp_path / "whole.db"
    first = softdrop.optimize(stopped, callback=stop_at_4, generations=10, **SEARCH)
    assert first.termination == "callback" and first.last_generation == 4
    assert [e["generation"] for e in events] == [1, 2, 3, 4]
    assert events[-1]["best_tortuosity"] == first.best_tortuosity and events[-1]["target_generations"] == 10
    assert softdrop.read_history(stopped)["runs"].loc[0, "status"] == "interrupted"
    second = softdrop.optimize(stopped, resume=1, quiet=True)  # goes on to the run's own target
    assert second.termination == "generations" and second.last_generation == 10
    softdrop.optimize(whole, generations=10, **SEARCH)
    assert_same_history(softdrop.read_history(stopped), softdrop.read_history(whole))


def test_cmaes_stopped_by_the_callback_resumes_by_replay_as_if_never_stopped(tmp_path):
    options = dict(SEARCH, lambda_=5, strategy="cmaes")
    stopped, whole = tmp_path / "stopped.db", tmp_path / "whole.db"
    first = softdrop.optimize(stopped, callback=lambda e: e["generation"] < 3, generations=6, **options)
    assert first.termination == "callback" and first.last_generation == 3
    assert softdrop.optimize(stopped, resume=1, quiet=True).last_generation == 6
    softdrop.optimize(whole, generations=6, **options)
    assert_same_history(softdrop.read_history(stopped), softdrop.read_history(whole))
    states = [json.loads(s) for s in softdrop.read_history(whole)["generations"]["state"] if isinstance(s, str) and s]
    assert [s["generation"] for s in states] == [1, 2, 3, 4, 5, 6] and all(len(s["values"]) == 5 for s in states)
    assert "start" in states[0] and "start" not in states[1]


def test_an_exception_in_the_callback_stops_the_search_and_is_raised(tmp_path):
    db = tmp_path / "s.db"

    def fails(event):
        if event["generation"] == 2:
            raise KeyError("from the callback")

    with pytest.raises(KeyError, match="from the callback"):
        softdrop.optimize(db, callback=fails, generations=6, **SEARCH)
    runs = softdrop.read_history(db)["runs"]
    assert runs.loc[0, "generations"] == 2 and runs.loc[0, "status"] == "interrupted"
    assert softdrop.optimize(db, resume=1, quiet=True).last_generation == 6


def test_islands_from_python_are_runs_with_their_island(tmp_path):
    db = tmp_path / "islands.db"
    events = []
    summary = softdrop.optimize(db, callback=events.append, islands=3, migrate_every=3, generations=7, **SEARCH)
    assert [i["island"] for i in summary.islands] == [0, 1, 2] and summary.last_generation == 7
    runs = softdrop.read_history(db, arrangements=False)["runs"]
    assert runs["island"].tolist() == [0, 1, 2] and runs["archipelago"].tolist() == [1, 1, 1]
    assert runs.dtypes["island"] == "Int64"
    assert sorted({(e["island"], e["generation"]) for e in events}) == [(i, g) for i in range(3) for g in range(1, 8)]
    assert {e["kind"] for e in events if e["generation"] in (3, 6)} == {"migrate"}
    softdrop.optimize(tmp_path / "plain.db", generations=1, **SEARCH)
    assert softdrop.read_history(tmp_path / "plain.db")["runs"]["island"].isna().all()


def test_restarts_from_python_start_from_media_of_their_own(tmp_path):
    db = tmp_path / "restarts.db"
    summary = softdrop.optimize(db, islands=2, migrate_every=0, island_starts="own", generations=3, **SEARCH)
    assert summary.last_generation == 3 and summary.migrate_every == 0
    history = softdrop.read_history(db)
    assert set(history["generations"]["kind"]) <= {"initial", "all", "single", "relocate", "mixed"}  # no migration
    assert set(history["candidates"]["kind"]) <= {"initial", "all", "single", "relocate"}
    grains = history["grains"]
    start = grains[grains.generation == 0]
    assert not start[start.run == 1][["x", "y"]].reset_index(drop=True).equals(
        start[start.run == 2][["x", "y"]].reset_index(drop=True))


def test_sweep_writes_the_programs_store(tmp_path):
    ours, theirs = tmp_path / "ours.db", tmp_path / "theirs.db"
    seen = []
    summary = softdrop.sweep(ours, callback=seen.append, threads=2, **SWEEP)
    cli("sweep", "--db", str(theirs), "--threads", "1", *SWEEP_ARGS)
    assert summary.status == "complete" and summary.done == summary.media == 4
    assert summary.droplets_this_session == 16
    assert sorted((e["porosity_index"], e["medium_index"]) for e in seen) == [(0, 0), (0, 1), (1, 0), (1, 1)]
    assert [e["media_done"] for e in seen] == [1, 2, 3, 4]
    a, b = softdrop.read_sweep(ours), softdrop.read_sweep(theirs)
    for name in ("media", "droplets", "points"):
        pd.testing.assert_frame_equal(without_clocks(a[name]), without_clocks(b[name]), check_exact=True, obj=name)
    # The points are sweep-report's.
    rows = json.loads(cli("sweep-report", "--db", str(theirs), "--format", "json"))
    assert a["points"]["mean_tortuosity"].tolist() == [r["mean_tortuosity"] for r in rows]
    assert a["points"]["porosity"].tolist() == [r["porosity"] for r in rows]
    assert a["points"]["media_passed"].tolist() == [r["media_passed"] for r in rows]
    np.testing.assert_array_equal(  # NaN where fewer than two media had a droplet pass
        a["points"]["media_standard_error"].to_numpy(),
        np.array([np.nan if r["media_standard_error"] is None else r["media_standard_error"] for r in rows]))
    for column in ("per_medium_tortuosity", "per_medium_standard_error"):  # the other averaging, also sweep-report's
        np.testing.assert_array_equal(a["points"][column].to_numpy(),
                                      np.array([np.nan if r[column] is None else r[column] for r in rows]))


def test_a_sweep_stopped_by_the_callback_goes_on_where_it_stopped(tmp_path):
    db = tmp_path / "s.db"
    options = dict(SWEEP, media=8, droplets=8)  # 16 media: more than are in flight at once
    first = softdrop.sweep(db, callback=lambda e: False, threads=1, **options)
    assert first.status == "interrupted" and 1 <= first.done < 16
    second = softdrop.sweep(db, threads=1, **options)
    assert second.status == "complete" and second.media_this_session == 16 - first.done
    whole = tmp_path / "whole.db"
    softdrop.sweep(whole, **options)
    a, b = softdrop.read_sweep(db), softdrop.read_sweep(whole)
    for name in ("media", "droplets"):
        pd.testing.assert_frame_equal(without_clocks(a[name]), without_clocks(b[name]), check_exact=True)


def test_tables_have_the_databases_columns_and_types(tmp_path):
    db = tmp_path / "s.db"
    softdrop.optimize(db, generations=4, **SEARCH)
    h = softdrop.read_history(db)
    assert list(h["grains"].columns) == ["run", "generation", "grain", "x", "y", "r", "touched"]
    assert list(h["paths"].columns) == ["run", "generation", "point", "x", "y"]
    assert h["grains"].dtypes["touched"] == bool and h["grains"].dtypes["x"] == np.float64
    kept = h["generations"].dropna(subset=["accepted_candidate"])["generation"].tolist()  # with generation 0
    assert kept[0] == 0 and len(kept) > 1
    assert sorted(h["grains"]["generation"].unique().tolist()) == kept
    assert (h["grains"].groupby("generation").size() == 16).all()
    best = softdrop.best_arrangement(db, run=1)
    last = h["grains"][h["grains"].generation == best.generation]
    assert np.array_equal(last[["x", "y", "r"]].to_numpy(), best.medium.grains)
    assert sorted(last.loc[last.touched, "grain"].tolist()) == list(best.touched_grains)
    assert best.touched == len(best.touched_grains) and best.path.shape[1] == 2
    assert h["params"].loc[0, "run"] == 1 and h["params"].loc[0, "grains"] == 16
    assert softdrop.read_history(db, arrangements=False)["grains"].empty
    softdrop.sweep(tmp_path / "w.db", **SWEEP)
    w = softdrop.read_sweep(tmp_path / "w.db")
    assert list(w["droplets"].columns) == ["sweep", "porosity_index", "medium_index", "droplet", "start_x", "outcome",
                                           "tortuosity", "steps", "shaken_at", "route_tortuosity"]
    assert w["droplets"].dtypes["steps"] == np.int64 and w["droplets"].dtypes["tortuosity"] == np.float64
    passed = w["droplets"]["outcome"] == "passed"
    # T >= 1 up to the rounding of a path summed over thousands of steps (a straight fall gives 1 +- 1e-15)
    assert w["droplets"].loc[~passed, "tortuosity"].isna().all()
    assert (w["droplets"].loc[passed, "tortuosity"] >= 1 - 1e-12).all()
    # An unshaken sweep: never shaken, and the route is the path itself.
    assert w["droplets"]["shaken_at"].isna().all()
    assert (w["droplets"].loc[passed, "route_tortuosity"] == w["droplets"].loc[passed, "tortuosity"]).all()


@pytest.mark.parametrize("call, says", [
    (lambda db: softdrop.optimize(db, lambda_=-3), "lambda = -3: must be in [1, 4096]"),
    (lambda db: softdrop.optimize(db, strategy="genetic"), "genetic"),
    (lambda db: softdrop.sweep(db, porosities=[0.5, 1.5]), "1.5"),
    (lambda db: softdrop.optimize(db, callback=3), "callback: must be callable"),
])
def test_bad_options_raise_value_error_with_the_programs_line(tmp_path, call, says):
    db = tmp_path / "s.db"
    with pytest.raises(ValueError) as error:
        call(db)
    assert says in str(error.value) and "\n" not in str(error.value)
    assert not db.exists()  # nothing written


@pytest.mark.parametrize("call", [
    lambda db: softdrop.optimize(db, generations=2, **SEARCH),
    lambda db: softdrop.sweep(db, **SWEEP),
    lambda db: softdrop.read_sweep(db),
])
def test_a_foreign_database_raises_store_error_and_is_left_alone(tmp_path, call):
    db = tmp_path / "notes.db"
    db.write_bytes(b"SQLite format 3\0" + b"\0" * 84 + b"x" * 300)
    before = db.read_bytes()
    with pytest.raises(softdrop.StoreError) as error:
        call(db)
    assert str(db) in str(error.value)
    assert db.read_bytes() == before


def test_simulate_many_lets_other_python_threads_run():
    medium = softdrop.Medium.generate(width=300, height=300)
    ticks = []
    done = threading.Event()

    def count():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.005)

    counter = threading.Thread(target=count)
    counter.start()
    t0 = time.perf_counter()
    # (the stuck test alone, so that the stuck droplets keep the run long enough to watch)
    softdrop.simulate_many(medium, 16, seed=5, threads=1, run=softdrop.RunOptions(rest_window=0))
    t1 = time.perf_counter()
    done.set()
    counter.join()
    during = [t for t in ticks if t0 < t < t1]
    # With the GIL held the counter could not run at all until simulate_many returned.
    assert t1 - t0 > 0.1 and len(during) >= 5


def test_ctrl_c_stops_a_search_which_then_resumes(tmp_path):
    db = tmp_path / "s.db"
    script = tmp_path / "search.py"
    script.write_text(
        "import sys, softdrop\n"
        "def tell(e):\n"
        "    if e['generation'] == 1: print('started', flush=True)\n"
        "try:\n"
        f"    softdrop.optimize(sys.argv[1], callback=tell, generations=10**6, **{SEARCH!r})\n"
        "except KeyboardInterrupt:\n"
        "    print('interrupted', flush=True)\n")
    child = subprocess.Popen([sys.executable, str(script), str(db)], stdout=subprocess.PIPE, text=True)
    assert child.stdout.readline().strip() == "started"
    time.sleep(0.3)
    child.send_signal(signal.SIGINT)
    out, _ = child.communicate(timeout=60)
    assert "interrupted" in out and child.returncode == 0
    runs = softdrop.read_history(db, arrangements=False)["runs"]
    assert runs.loc[0, "status"] == "interrupted"
    stopped_at = runs.loc[0, "generations"]
    assert softdrop.optimize(db, resume=1, generations=stopped_at + 2, quiet=True).last_generation == stopped_at + 2


def test_progress_is_a_bar_in_python_not_the_programs_line(tmp_path, capfd):
    tqdm = pytest.importorskip("tqdm")  # noqa: F841 (Debian python3-tqdm; scripts/setup.sh installs it)
    seen = []
    summary = softdrop.optimize(tmp_path / "p.db", progress=True, callback=seen.append, generations=3,
                                **dict(SEARCH, quiet=False))
    out, err = capfd.readouterr()
    assert summary.last_generation == 3 and [e["generation"] for e in seen] == [1, 2, 3]  # the callback still runs
    assert "3/3" in err and "generation" in err and "best T" in err
    assert "optimize: run 1" not in err  # the program's own progress line is silenced
    softdrop.sweep(tmp_path / "s.db", progress=True, **dict(SWEEP, quiet=False))
    out, err = capfd.readouterr()
    assert "4/4" in err and "medium" in err and "sweep: " not in err


def test_without_tqdm_progress_goes_to_logging(tmp_path, monkeypatch, caplog):
    import builtins

    real_import = builtins.__import__

    def no_tqdm(name, *args, **kwargs):
        if name.startswith("tqdm"):
            raise ImportError(name)
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_tqdm)
    with caplog.at_level("INFO", logger="softdrop"):
        softdrop.optimize(tmp_path / "p.db", progress=True, generations=3, **SEARCH)
    lines = [r.getMessage() for r in caplog.records if r.name == "softdrop"]
    assert lines and lines[-1].startswith("generation 3/3")


def test_best_arrangement_quotes_what_history_best_does(tmp_path):
    # A robust search: its best's value in the search is the mean of its re-runs, and the held-out
    # value stored at the end sits beside it, as in `softdrop history --best`.
    db = tmp_path / "robust.db"
    summary = softdrop.optimize(db, generations=5, **{**SEARCH, "objective": "mean", "starts": 4,
                                                        "validate_starts": 12})
    best = softdrop.best_arrangement(db)
    row = json.loads(cli("history", "--db", str(db), "--run", "1", "--best", "--format", "json"))[-1]
    assert best.generation == row["generation"] == summary["best_generation"]
    assert best.objective == "mean"
    assert best.best_tortuosity == row["best_tortuosity"] == summary["best_tortuosity"]
    assert best.re_runs == row["re_runs"]
    assert best.held_out_tortuosity == row["held_out_tortuosity"] == summary["held_out"]["mean_tortuosity"]
    assert best.held_out_standard_error == row["held_out_standard_error"]
    assert best.held_out_starts == 12
    # The single objective's in-search value is its droplet's T; no held-out value was asked for.
    single = tmp_path / "single.db"
    softdrop.optimize(single, generations=3, **SEARCH)
    one = softdrop.best_arrangement(single)
    assert one.objective == "single" and one.best_tortuosity == one.tortuosity and one.re_runs == 0
    assert one.held_out_tortuosity is None and one.held_out_starts is None
    # read_history's `best` is history --best's table for every run, cell for cell.
    for path, robust in ((db, True), (single, False)):
        ours = softdrop.read_history(path, arrangements=False)["best"]
        theirs = pd.read_csv(io.StringIO(cli("history", "--db", str(path), "--run", "1", "--best", "--format", "csv")))
        theirs.insert(0, "run", 1)
        assert list(ours.columns) == list(theirs.columns)
        assert ours["re_runs"].isna().all() != robust
        pd.testing.assert_frame_equal(ours, theirs, check_dtype=False)
