"""optimize's and sweep's keywords are the program's options, read as typed values, not as a command
line: every option of `softdrop optimize` and `softdrop sweep` is a keyword, each value is read as
its option's type, config files give values under the keywords, and a preset or a config file
counts as given on resume, as on the command line."""
import json
import os
import re
import subprocess

import pytest

import softdrop

import balloon

CLI = os.environ["SOFTDROP_CLI"]
SEARCH = dict(objective="single", grains=16, width=160, height=120, medium_seed=2, stuck_window=0.1, stuck_distance=1,
              lambda_=2, quiet=True, validate_starts=0)
# Options the program's sweep takes only to refuse them (it generates its media).
SWEEP_IGNORES = {"medium", "pixel-size", "porosity", "medium-seed"}


def options_of(command):
    text = subprocess.run([CLI, command, "--help"], capture_output=True, text=True, check=True).stdout
    return sorted(set(re.findall(r"^\s+(?:-\w,)?--([a-z][a-z0-9-]*)", text, re.MULTILINE)) - {"help", "db"})


@pytest.mark.parametrize("command", ["optimize", "sweep"])
def test_every_option_of_the_program_is_a_keyword(tmp_path, command):
    run = getattr(softdrop, command)
    names = [n for n in options_of(command) if not (command == "sweep" and n in SWEEP_IGNORES)]
    assert len(names) > 40
    for name in names:
        keyword = "lambda_" if name == "lambda" else name.replace("-", "_")
        with pytest.raises(TypeError) as error:  # a value of no option's type: refused by name
            run(tmp_path / "never.db", **{keyword: object()})
        assert str(error.value).startswith(keyword + ": "), str(error.value)
    assert not (tmp_path / "never.db").exists()


@pytest.mark.parametrize("call, error, says", [
    (lambda db: softdrop.optimize(db, seed=-1), ValueError, r"^seed = -1: must be >= 0$"),
    (lambda db: softdrop.optimize(db, walls=2), TypeError, r"^walls: True or False, not 2$"),
    (lambda db: softdrop.optimize(db, strategy=3), TypeError, r"^strategy: a str, not 3$"),
    (lambda db: softdrop.optimize(db, resume=0), ValueError, r"^resume = 0: run ids are whole numbers from 1$"),
    (lambda db: softdrop.optimize(db, sigma=3), ValueError, r"^sigma: an option of strategy cmaes, not used by strategy es$"),
    (lambda db: softdrop.optimize(db, medium="m.json", grains=4), ValueError,
     r"^grains: has no effect with medium \(the grain file fixes the medium\); leave it out$"),
    (lambda db: softdrop.sweep(db, media=2.0), TypeError, r"^media: a whole number, not 2.0$"),
    (lambda db: softdrop.sweep(db, porosity=0.5), TypeError, r"^sweep\(\) got an unexpected keyword argument 'porosity'"),
    (lambda db: softdrop.sweep(db, second_after=3), ValueError, r"^second_after: has no effect without second_droplet$"),
    (lambda db: softdrop.sweep(db, shard="2/2"), ValueError, r"^shard = '2/2': expected i/n with 0 <= i < n$"),
    (lambda db: softdrop.sweep(db, preset="slow"), ValueError, r"^preset = 'slow': must be quick or paper$"),
    # Read by the reader of stored runs, but the caller's own value: the refusal names it alone.
    (lambda db: softdrop.optimize(db, objective="o"), ValueError,
     r"^objective = 'o': must be single, mean, quantile or lower-bound$"),
    (lambda db: softdrop.sweep(db, constraint_order="zigzag"), ValueError,
     r"^constraint_order = 'zigzag': must be sequential or red-black$"),
])
def test_a_value_is_read_as_its_options_type(tmp_path, call, error, says):
    with pytest.raises(error, match=says):
        call(tmp_path / "never.db")
    assert os.listdir(tmp_path) == []


def test_a_config_files_values_are_keywords_that_a_keyword_overrides(tmp_path):
    config = tmp_path / "c.toml"  # the balloon's droplet, and a search's keys: plain, and in tables
    config.write_text(open(balloon.CONFIG).read() + "\nlambda = 3\nseed = 9\n[optimize]\nseed = 11\n[simulate]\nx0 = 3\n")
    db = tmp_path / "c.db"
    options = {k: v for k, v in SEARCH.items() if k != "lambda_"}
    softdrop.optimize(db, config=config, generations=1, **dict(options, seed=5))
    params = softdrop.read_history(db, arrangements=False)["params"]
    assert params.loc[0, "lambda"] == 3  # the file's
    assert params.loc[0, "seed"] == 5  # the keyword's, over the [optimize] table's 11 and the plain 9
    assert params.loc[0, "nrt"] == 1.5e9  # the balloon's
    # The config's values count as given: a resume with another file that contradicts them is refused.
    other = tmp_path / "o.toml"
    other.write_text("lambda = 4\n")
    with pytest.raises(ValueError, match="lambda"):
        softdrop.optimize(db, resume=1, config=other, quiet=True)


@pytest.mark.parametrize("text, says", [
    ("lamda = 3\n", r"c.toml': lamda: optimize has no option lamda \(did you mean lambda\?\)"),
    ("lambda = 2.5\n", r"c.toml': lambda: a whole number, not 2.5"),
    ("media = 4\n", r"c.toml': media: optimize has no option media"),  # a sweep's key, refused as the program does
    ("lambda = [\n", r"c.toml' line 1"),
])
def test_a_config_file_is_refused_naming_it_and_the_key(tmp_path, text, says):
    config = tmp_path / "c.toml"
    config.write_text(text)
    with pytest.raises((ValueError, TypeError), match=says):
        softdrop.optimize(tmp_path / "never.db", config=config, **SEARCH)
    assert not (tmp_path / "never.db").exists()


def test_none_leaves_an_option_at_its_default(tmp_path):
    db = tmp_path / "n.db"
    summary = softdrop.optimize(db, generations=1, resume=None, strategy=None, **SEARCH, **balloon.OPTIONS)
    assert summary.run == 1 and summary.strategy == "es"
    grains = tmp_path / "m.json"
    softdrop.best_arrangement(db).medium.save(grains)
    options = {k: v for k, v in SEARCH.items() if k not in ("grains", "width", "height", "medium_seed")}
    summary = softdrop.optimize(db, medium=grains, grains=None, width=None, generations=1, **options, **balloon.OPTIONS)
    assert summary.run == 2
    with pytest.raises(ValueError, match="r_max"):  # no config: the default droplet's radii in this box
        softdrop.optimize(tmp_path / "never.db", config=None, r_max=-1, **SEARCH)


def test_the_paper_preset_is_the_programs(tmp_path):
    ours, theirs = tmp_path / "ours.db", tmp_path / "theirs.db"
    options = {k: v for k, v in SEARCH.items() if k not in ("objective", "lambda_")}
    summary = softdrop.optimize(ours, preset="paper", generations=3, **options, **balloon.OPTIONS)
    args = ["--grains", "16", "--width", "160", "--height", "120", "--medium-seed", "2", "--stuck-window", "0.1",
            "--stuck-distance", "1", "--quiet", "--validate-starts", "0"]
    theirs_summary = json.loads(subprocess.run([CLI, *balloon.ARGS, "optimize", "--db", str(theirs), "--preset", "paper",
                                                "--generations", "3", "--format", "json", *args],
                                               capture_output=True, text=True, check=True).stdout)
    assert summary.strategy == "paper" and summary.objective == "single"
    assert summary.best_tortuosity == theirs_summary["best_tortuosity"]
    a = softdrop.read_history(ours, arrangements=False)["params"]
    b = softdrop.read_history(theirs, arrangements=False)["params"]
    assert a.drop(columns="run").to_dict("records") == b.drop(columns="run").to_dict("records")
    # The preset's keys count as given: resuming with another strategy is refused.
    with pytest.raises(ValueError, match="strategy"):
        softdrop.optimize(ours, resume=1, strategy="es", quiet=True)
