"""One name per quantity: every CSV header, JSON key, database view column and Python frame or
result key that softdrop writes is one of `softdrop columns`, and none is an old synonym. Each
writer is run on a small scene and its names are read back from what it wrote."""
import json
import os
import sqlite3
import subprocess

import numpy as np
import pandas as pd
import pytest

import softdrop

import balloon

CLI = os.environ["SOFTDROP_CLI"]

# The names one quantity used to have beside its one name (tortuosity, porosity, time, run, ...).
SYNONYMS = {"t", "phi", "target_phi", "mean_t", "best_t", "candidate_t", "held_out_t", "held_out_se", "parent_t",
            "per_medium_t", "half_dt_mean_t", "in_search_t", "paper_t", "geometric_t", "tau", "se", "phi_se", "t_se",
            "run_id", "sweep_id", "id", "type"}
SCENE = ["--width", "160", "--height", "120", "--medium-seed", "2", "--stuck-window", "0.1", "--stuck-distance", "1"] + balloon.ARGS
SEARCH = SCENE + ["--grains", "16", "--lambda", "3", "--strategy", "es", "--quiet", "--starts", "2", "--validate-starts", "4"]
SWEEP = ["--porosities", "0.8,0.85,0.9,0.95", "--media", "2", "--droplets", "3", "--width", "200", "--height", "200", "--quiet"]


def cli(*args, cwd=None):
    r = subprocess.run([CLI, *args], capture_output=True, text=True, cwd=cwd)
    assert r.returncode == 0, r.stderr
    return r.stdout


def keys(value, out, where):
    """Every key of a JSON document (objects in lists too), with where it was found; a strategy's
    state is a document of its own (the strategy's options), as params is."""
    if isinstance(value, dict):
        for k, v in value.items():
            out.setdefault(k, where)
            if k not in ("state", "params"):
                keys(v, out, where)
    elif isinstance(value, list):
        for v in value:
            keys(v, out, where)
    return out


def header(path):
    with open(path) as f:
        return f.readline().strip().split(",")


@pytest.fixture(scope="module")
def vocabulary():
    table = softdrop.columns()
    names = set(table["name"])
    assert len(names) == len(table), "a name listed twice"
    assert table["name"].is_monotonic_increasing
    assert not names & SYNONYMS, f"synonyms in the table: {names & SYNONYMS}"
    program = pd.read_csv(pd.io.common.StringIO(cli("columns", "--format", "csv")), keep_default_na=False)
    # The program lists the same names, and the droplet parameters besides.
    params = {n for n in dir(softdrop.DropletParams()) if not n.startswith("_") and not callable(getattr(softdrop.DropletParams(), n))}
    assert set(program["name"]) == names | params
    return names | params


@pytest.fixture(scope="module")
def written(tmp_path_factory):
    """Every name the program writes: {name: where}."""
    d = tmp_path_factory.mktemp("vocabulary")
    found = {}

    def csv(path):
        for n in header(path):
            found.setdefault(n, os.path.basename(path))

    def doc(text, where):
        keys(json.loads(text), found, where)

    cli("simulate", *SCENE, "--droplets", "2", "--runs", "runs.csv", "--paths", "paths.csv", "--trace", "trace.csv",
        "--snapshots", "snap.csv", "--snapshot-times", "0.01", "--json", "simulate.json", "--save-medium", "m.json",
        "--max-steps", "20000", "--quiet", cwd=d)
    cli("simulate", *SCENE, "--save-medium", "m.csv", "--max-steps", "2000", cwd=d)
    for f in ("runs.csv", "paths.csv", "trace.csv", "snap.csv", "m.csv"):
        csv(d / f)
    for f in ("simulate.json", "m.json"):
        doc((d / f).read_text(), f)
    doc(cli("simulate", *SCENE, "--format", "json", "--max-steps", "2000"), "simulate --format json")

    db = str(d / "s.db")
    doc(cli("optimize", "--db", db, *SEARCH, "--generations", "3", "--format", "json"), "optimize")
    doc(cli("optimize", "--db", db, *SEARCH, "--generations", "2", "--islands", "2", "--format", "json"), "islands")
    for view in ([], ["--run", "1"], ["--run", "1", "--best"], ["--run", "1", "--candidates"], ["--run", "1", "--params"]):
        doc(cli("history", "--db", db, *view, "--format", "json"), "history " + " ".join(view))
        out = d / "h.csv"
        out.write_text(cli("history", "--db", db, *view, "--format", "csv"))
        csv(out)
    doc(cli("validate", "--db", db, "--run", "1", "--starts", "3", "--runs", str(d / "v.csv"), "--format", "json"),
        "validate")
    csv(d / "v.csv")

    sdb = str(d / "w.db")
    cli("sweep", "--db", sdb, *SWEEP)
    cli("sweep", "--db", sdb, *SWEEP, "--seed", "2")
    cli("sweep", "--db", sdb, *SWEEP, "--seed", "3", "--second-droplet", "distance")
    out = d / "p2.csv"
    out.write_text(cli("sweep-report", "--db", sdb, "--sweep", "3", "--second-droplets", "--format", "csv"))
    csv(out)
    for extra in ([], ["--media"]):
        out = d / "p.csv"
        out.write_text(cli("sweep-report", "--db", sdb, "--sweep", "1", *extra, "--format", "csv"))
        csv(out)
        doc(cli("sweep-report", "--db", sdb, "--sweep", "1", *extra, "--format", "json"), "sweep-report")
    doc(cli("sweep-report", "--db", sdb, "--format", "json"), "sweep-report (the list)")
    (d / "points.csv").write_text(cli("sweep-report", "--db", sdb, "--sweep", "1", "--format", "csv"))
    doc(cli("fit", "--points", str(d / "points.csv"), "--errors", "droplets", "--format", "json"), "fit")
    cli("averagings", "--db", sdb, "--sweep", "1", "--group", "2", "--csv", str(d / "avg.csv"))
    csv(d / "avg.csv")

    doc(cli("tortuosity", "--medium", str(d / "m.json"), "--pixels", "80", "--starts", "2", "--csv",
            str(d / "tau.csv"), "--format", "json", "--quiet"), "tortuosity")
    csv(d / "tau.csv")
    return found, db, sdb


def test_every_name_the_program_writes_is_in_the_vocabulary(vocabulary, written):
    found, _, _ = written
    stray = {n: w for n, w in found.items() if n not in vocabulary}
    assert not stray, f"names outside `softdrop columns`: {stray}"
    assert not set(found) & SYNONYMS
    # The quantities the issue of names was about, each written under its one name.
    for name in ("tortuosity", "mean_tortuosity", "best_tortuosity", "porosity", "target_porosity", "time", "run",
                 "sweep", "touched"):
        assert name in found, name


def test_the_database_views_have_the_python_frames_columns(vocabulary, written):
    _, db, sdb = written
    history, sweeps = softdrop.read_history(db), softdrop.read_sweep(sdb)
    frames = {"runs": history["runs"], "generations": history["generations"], "candidates": history["candidates"],
              "grains": history["grains"], "paths": history["paths"], "validations": history["validations"],
              "sweeps": sweeps["sweeps"], "sweep_media": sweeps["media"], "sweep_droplets": sweeps["droplets"],
              "sweep_second_droplets": sweeps["second_droplets"]}
    for file in (db, sdb):
        with sqlite3.connect(file) as c:
            for table, frame in frames.items():
                view = pd.read_sql(f"SELECT * FROM {table}_view", c)
                assert list(view.columns) == list(frame.columns), table
                assert set(view.columns) <= vocabulary
                if file == (sdb if table.startswith("sweep") else db):
                    assert len(view) == len(frame) > 0, table
    # The views hold the frames' values: the same runs, generations and candidates' moves.
    with sqlite3.connect(db) as c:
        cands = pd.read_sql("SELECT * FROM candidates_view ORDER BY run, generation, candidate", c)
        gens = pd.read_sql("SELECT * FROM generations_view ORDER BY run, generation", c)
    assert cands["kind"].tolist() == history["candidates"]["kind"].tolist()
    assert gens["best_tortuosity"].tolist() == history["generations"]["best_tortuosity"].tolist()
    # es draws each candidate's move: a generation of several moves is 'mixed', not 'all'.
    merged = history["candidates"].groupby(["run", "generation"])["kind"].agg(lambda k: k.iloc[0] if k.nunique() == 1 else "mixed")
    assert merged.tolist() == history["generations"]["kind"].tolist()
    assert "mixed" in set(merged)
    for frame in list(frames.values()) + [sweeps["points"], history["params"]]:
        assert not set(frame.columns) & SYNONYMS


def test_every_name_python_gives_is_in_the_vocabulary(vocabulary, written, tmp_path):
    _, db, sdb = written
    medium = softdrop.Medium.generate(grains=16, width=160, height=120, r_min=8, r_max=16)
    run = softdrop.simulate(medium, path=True, trace=True, run=softdrop.RunOptions(max_steps=20000))
    held = softdrop.held_out(medium, starts=2, run=softdrop.RunOptions(max_steps=20000), threads=1)
    pore = softdrop.tortuosity(medium, pixels=40)
    names = set(run) | set(held) | set(held["at_dt"]) | set(held["runs"].columns) | set(pore)
    names |= set(softdrop.simulate_many(medium, 2, run=softdrop.RunOptions(max_steps=20000)).columns)
    names |= set(softdrop.rigid_descent(medium, [40.0], path=True).columns)
    names |= set(softdrop.best_arrangement(db))
    events = []
    summary = softdrop.optimize(tmp_path / "o.db", callback=lambda e: events.append(e), generations=1, lambda_=2,
                                grains=16, width=160, height=120, quiet=True, validate_starts=0, **balloon.OPTIONS)
    names |= set(summary) | set(events[0])
    sweep_events = []
    summary = softdrop.sweep(tmp_path / "w.db", callback=lambda e: sweep_events.append(e), porosities=[0.9], media=1,
                             droplets=2, width=200, height=200, quiet=True)
    names |= set(summary) | set(sweep_events[0])
    history = softdrop.read_history(db)
    for name, frame in history.items():
        names |= set(frame.columns) if name != "params" else {"run"}  # params: the options' own names
    for frame in softdrop.read_sweep(sdb).values():
        names |= set(frame.columns)
    assert not names - vocabulary, f"names outside softdrop.columns(): {names - vocabulary}"
    assert not names & SYNONYMS
    # A count is a count everywhere, the indices beside it; every path is rows of x, y.
    assert run.touched == len(run.touched_grains) and run.path.shape[1] == 2
    assert softdrop.best_arrangement(db).path.shape[1] == 2
    assert np.array_equal(softdrop.rigid_descent(medium, [40.0], path=True)["path"][0][-1].shape, (2,))


def test_history_writes_typed_values(written):
    _, db, _ = written
    params = {r["option"]: r["value"] for r in json.loads(cli("history", "--db", db, "--run", "1", "--params", "--format", "json"))}
    assert params["grains"] == 16 and params["strategy"] == "es" and params["walls"] is False
    assert isinstance(params["dt"], float)
    generations = json.loads(cli("history", "--db", db, "--run", "1", "--format", "json"))
    assert generations[0]["state"] is None  # generation 0: no state yet, not ""
    assert isinstance(generations[1]["state"], dict) and "step" in generations[1]["state"]
    runs = json.loads(cli("history", "--db", db, "--format", "json"))
    islands = [r for r in runs if r["island"] is not None]
    assert [r["island"] for r in islands] == [0, 1] and {r["archipelago"] for r in islands} == {islands[0]["run"]}
    assert runs[0]["island"] is None and runs[0]["archipelago"] is None


def test_an_older_file_without_candidates_moves_reads_what_it_can_tell(written, tmp_path):
    """Before schema version 8 a candidate's move was not stored and es's generations were all
    'all': a candidate that moved every grain reads as 'all', one that moved one grain (single or
    relocate, which the file cannot tell apart) as unknown, in the frames and the views alike."""
    _, db, _ = written
    old = tmp_path / "old.db"
    with sqlite3.connect(db) as c, sqlite3.connect(old) as o:
        c.backup(o)
    with sqlite3.connect(old) as o:
        o.execute("UPDATE candidates SET kind = NULL")
        o.execute("UPDATE generations SET kind = 'all' WHERE kind = 'mixed'")
    frame = softdrop.read_history(old)["candidates"]
    later = frame[frame.generation > 0]
    whole = later["moved_grain"].isna()
    assert whole.any() and (~whole).any()
    assert (later.loc[whole, "kind"] == "all").all() and later.loc[~whole, "kind"].isna().all()
    with sqlite3.connect(old) as o:
        view = pd.read_sql("SELECT * FROM candidates_view ORDER BY run, generation, candidate", o)
    assert view["kind"].tolist() == [None if pd.isna(k) else k for k in frame["kind"]]
    text = cli("history", "--db", str(old), "--run", "1", "--candidates", "--format", "json")
    assert [r["kind"] for r in json.loads(text)] == view[view.run == 1]["kind"].tolist()


def test_columns_shows_the_names_asked_for_and_refuses_others():
    table = pd.read_csv(pd.io.common.StringIO(cli("columns", "porosity", "radius", "--format", "csv")))
    assert table["name"].tolist() == ["porosity", "radius"]  # a quantity, and a droplet parameter
    assert table.loc[0, "unit"] == 1 or table.loc[0, "unit"] == "1"
    r = subprocess.run([CLI, "columns", "phi"], capture_output=True, text=True)
    assert r.returncode == 1 and r.stderr == "softdrop: error: names: 'phi' is not a name softdrop writes\n"
