#!/usr/bin/env python3
"""Springs that carry the tension, at larger scale: where the droplet's area swells past S0.

With the paper's g, k_s, k_d and dt, a droplet whose springs (not the length constraint) hold its
surface needs its weight small against its springs: the group N^2 m g / (strain R k_s) must be
small. At R = 8 that asks for masses so light that k_d is unstable, and the light rings fold at
their impacts (springs.csv). This study scales every length by S instead (droplet radius 8 S,
grains 8 S to 16 S, box 500 S, contact depth, stuck distance; times by sqrt(S)) and sets the gas
for a given spring strain at rest, to see which regime keeps the ring whole with no or little
internal viscosity and lets its area go above S0. One row per setting and medium kind:
scaled.csv. SOFTDROP=path runs another build. About 20 minutes on 2 cores.

    /usr/bin/python3 results/calibration/scaled.py            # scaled.csv
    /usr/bin/python3 results/calibration/scaled.py contact    # scaled_contact.csv, about 20 minutes:
        # S = 840 with --viscosity-dilation 0: contact damping and viscosity against T
    /usr/bin/python3 results/calibration/scaled.py size       # scaled_size.csv, about 20 minutes:
        # the same droplet's radius against the grains, and its springs' strain at rest
"""
import csv
import math
import os
import subprocess
import sys
import tempfile
import time

import pandas as pd

HERE = os.path.dirname(os.path.abspath(__file__))
SOFTDROP = os.environ.get("SOFTDROP", os.path.join(HERE, "..", "..", "build", "softdrop"))
BALLOON = os.path.join(HERE, "balloon.toml")  # the droplet every run here scales, with the paper's k_s and k_d
N = 24          # masses
KS = 119755.0   # the paper's k_s
STRAIN_LIMIT = 0.1


def nrt_for(radius, strain):
    """nRT that holds the ring at `strain` at rest (Laplace: tension k_s strain l0 = P R_rest)."""
    l0 = 2 * radius * math.sin(math.pi / N) / (1 + STRAIN_LIMIT)  # DropletParams::rest_length
    rest_radius = radius * (1 + strain) / (1 + STRAIN_LIMIT)
    return math.pi * rest_radius * KS * strain * l0


def run(scale, mass, strain, viscosity, dilation, kind, porosity, droplets, seed, tmp, cc_per_mass=2e4,
        radius_factor=8):
    radius = radius_factor * scale
    nrt = nrt_for(radius, strain) if strain is not None else 1.5e9
    args = [SOFTDROP, "--config", BALLOON, "simulate", "--quiet", "--threads", "2", "--seed", str(seed),
            "--droplets", str(droplets), "--kind", kind, "--porosity", str(porosity),
            "--width", str(500 * scale), "--height", str(500 * scale),
            "--r-min", str(8 * scale), "--r-max", str(16 * scale), "--radius", str(radius),
            "--masses", str(N), "--mass", str(mass), "--nrt", repr(nrt),
            "--kc", repr(2e8 * mass), "--cc", repr(cc_per_mass * mass), "--viscosity", str(viscosity),
            "--viscosity-dilation", str(dilation),
            "--max-depth", repr(0.5 * scale), "--stuck-distance", repr(5 * scale),
            "--stuck-window", repr(0.5 * math.sqrt(scale)), "--rest-window", "0", "--max-steps", "20000000",
            "--runs", os.path.join(tmp, "runs.csv"), "--trace", os.path.join(tmp, "trace.csv")]
    start = time.time()
    subprocess.run(args, check=True, stdout=subprocess.DEVNULL)
    seconds = time.time() - start
    runs = pd.read_csv(os.path.join(tmp, "runs.csv"))
    trace = pd.read_csv(os.path.join(tmp, "trace.csv"))
    inside = trace[trace.phase == "inside"].groupby("droplet").area_ratio.agg(["min", "max"])
    passed = runs[runs.outcome == "passed"]
    counts = runs.outcome.value_counts()
    return {
        "scale": scale, "radius": radius, "mass": mass,
        "rest_strain": "" if strain is None else strain, "nrt": nrt,
        "kc": 2e8 * mass, "cc": cc_per_mass * mass, "viscosity": viscosity, "viscosity_dilation": dilation, "kind": kind, "porosity": porosity,
        "droplets": droplets, "passed": int(counts.get("passed", 0)), "stuck": int(counts.get("stuck", 0)),
        "timeout": int(counts.get("timeout", 0)), "diverged": int(counts.get("diverged", 0)),
        "mean_tortuosity": passed.tortuosity.mean() if len(passed) else "",
        "area_min": inside["min"].min(), "area_max": inside["max"].max(),
        "above_1_02": int((inside["max"] > 1.02).sum()), "below_0_95": int((inside["min"] < 0.95).sum()),
        "mean_steps": runs.steps.mean(), "seconds": round(seconds, 2),
    }


def main():
    if sys.argv[1:] == ["contact"]:  # S = 840, m = 1, dilation 0: softer contact damping, other nu
        settings = [(840, 1.0, 0.05, nu, 0.0, cc) for nu, cc in ((3000, 2e3), (3000, 6e3), (1000, 2e3), (10000, 2e4),
                                                                      (20000, 2e4), (25000, 2e4))]  # nu dt <= 0.5
        return scan(settings, os.path.join(HERE, "scaled_contact.csv"))
    if sys.argv[1:] == ["size"]:  # S = 840, m = 1, dilation 0, nu = 10 000: the droplet against the grains (8 S to 16 S)
        settings = [(840, 1.0, strain, 10000, 0.0, 2e4, r) for r, strain in ((5, 0.05), (6.5, 0.05), (11, 0.05),
                                                                           (8, 0.02), (8, 0.08))]
        return scan(settings, os.path.join(HERE, "scaled_size.csv"))
    settings = [(1, 1.0, None, 3000, 1.0)]  # the calibrated defaults (a balloon), for comparison
    for scale in (1, 125, 840, 8400):
        for mass in (0.015, 0.1, 1.0):
            for viscosity in (0, 3000):
                settings.append((scale, mass, 0.05, viscosity, 1.0))
    for viscosity in (30, 100, 300):  # between the two, where the area swells (S = 8400, m = 1)
        settings.append((8400, 1.0, 0.05, viscosity, 1.0))
    for scale in (125, 840, 8400):  # a viscosity that spares the breathing mode (--viscosity-dilation 0)
        for viscosity in (300, 1000, 3000):
            settings.append((scale, 1.0, 0.05, viscosity, 0.0))
    scan(settings, os.path.join(HERE, "scaled.csv"))


def scan(settings, out):
    """Runs every setting (scale, mass, rest strain, nu, dilation[, c_c per unit mass[, radius / S]]) on both
    media kinds, rewriting `out` after each row."""
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for i, (scale, mass, strain, viscosity, dilation, *extra) in enumerate(settings):
            for kind, porosity in (("non-overlapping", 0.79), ("overlapping", 0.8)):
                rows.append(run(scale, mass, strain, viscosity, dilation, kind, porosity, 10, 11, tmp, *extra))
                r = rows[-1]
                print(f"[{i + 1}/{len(settings)}] S={scale} R={r['radius']:g} m={mass} strain={strain} nu={viscosity} dilation={dilation} {kind}: "
                      f"passed {r['passed']} stuck {r['stuck']} timeout {r['timeout']} diverged {r['diverged']}, "
                      f"T {r['mean_tortuosity']}, area {r['area_min']:.3f}-{r['area_max']:.3f}", file=sys.stderr)
                with open(out + ".tmp", "w", newline="") as f:
                    w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
                    w.writeheader()
                    w.writerows(rows)
                os.replace(out + ".tmp", out)


if __name__ == "__main__":
    main()
