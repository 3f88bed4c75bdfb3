"""The balloon, the droplet the defaults were before the calibration, which the tests of the
machinery run on the small scenes laid out for it (as tests/balloon.hpp). Its one spelling is
results/calibration/balloon.toml: the program and softdrop.optimize read the file itself, and the
library's twin is softdrop.DropletParams.balloon()."""

import pathlib
import tomllib

CONFIG = str(pathlib.Path(__file__).resolve().parents[2] / "results" / "calibration" / "balloon.toml")
# Keyword options of softdrop.optimize and sweep, and the same on the command line.
OPTIONS = dict(config=CONFIG)
ARGS = ["--config", CONFIG]
# Its grains, for media the library generates.
with open(CONFIG, "rb") as _file:
    _VALUES = tomllib.load(_file)
GRAINS = dict(r_min=float(_VALUES["r-min"]), r_max=float(_VALUES["r-max"]))
