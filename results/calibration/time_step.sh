#!/usr/bin/env bash
# The explicit droplet (explicit.toml) with the exponential viscosity step at six time steps, over
# radius.sh's ensemble (the calibration's six porosities x 200 overlapping media x 20 droplets, no
# area traces). nu = 1.8656e5 makes the exponential step take exp(-nu dt) = 1 - 1.37e5 x 3.5e-6 of
# the deformation a step at explicit.toml's dt, what its explicit step takes; at other time steps
# it is the same continuous viscosity. Shows how <T>(phi) and the run time depend on dt. Then, at
# dt = 6e-6, three larger viscosities through the same droplets: the one that gives the explicit
# droplet's <T>(phi), 2.8e5, is exponential.toml's. Last, the defaults (the implicit step with the
# explicit droplet's nu at dt = 6e-6) through the same droplets. (Every option that differs
# between the defaults and explicit.toml is set here, so either base gives these rows.) Writes
# time_step.csv (one row per dt), time_step_points.csv (one row per dt and porosity),
# time_step_viscosity.csv and time_step_viscosity_points.csv (the same per viscosity at
# dt = 6e-6), time_step_defaults.csv and time_step_defaults_points.csv, and time_step.png. About 13
# minutes on 2 cores. SOFTDROP=path runs another build.
#     bash results/calibration/time_step.sh
set -euo pipefail
cd "$(dirname "$0")"
BIN=${SOFTDROP:-../../build/softdrop}
settings=()
for dt in 1.75e-6 2.5e-6 3.5e-6 5e-6 6e-6 7e-6; do
  settings+=(--setting "dt $dt: dt=$dt")
done
"$BIN" calibrate --format csv --media 200 --droplets 20 --trace-media 0 --viscosity-step exponential \
  --viscosity 1.8656e5 "${settings[@]}" --csv time_step.csv --points time_step_points.csv > /dev/null
"$BIN" calibrate --format csv --media 200 --droplets 20 --trace-media 0 --viscosity-step exponential \
  --dt 6e-6 --setting "nu 2.0e5: viscosity=2.0e5" --setting "nu 2.3e5: viscosity=2.3e5" \
  --setting "nu 2.8e5: viscosity=2.8e5" --csv time_step_viscosity.csv --points time_step_viscosity_points.csv \
  > /dev/null
# The defaults (the implicit step, nu = 1.37e5, dt = 6e-6) through the same droplets.
"$BIN" calibrate --format csv --media 200 --droplets 20 --trace-media 0 --viscosity-step implicit \
  --viscosity 1.37e5 --dt 6e-6 --setting "defaults:" --csv time_step_defaults.csv \
  --points time_step_defaults_points.csv > /dev/null
/usr/bin/python3 - <<'PY'
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import pandas as pd

rows, points = pd.read_csv("time_step.csv"), pd.read_csv("time_step_points.csv")
points = points.merge(rows[["setting", "dt"]], on="setting")
radius = pd.read_csv("radius.csv")
defaults = pd.read_csv("radius_points.csv")
defaults = defaults[defaults.setting == radius.setting[radius.radius == 8].iloc[0]]
fig, (left, right) = plt.subplots(1, 2, figsize=(10, 4))
for dt, group in points.groupby("dt"):
    left.errorbar(group.porosity, group.mean_tortuosity - group.paper_tortuosity, yerr=group.media_standard_error, marker="o", ms=3,
                  capsize=2, label=f"exponential, ν = 1.8656e5, δt = {dt:.3g}")
left.plot(defaults.porosity, defaults.mean_tortuosity - defaults.paper_tortuosity, "k--", lw=1, label="explicit.toml (explicit, 3.5e-06)")
nu_rows, nu_points = pd.read_csv("time_step_viscosity.csv"), pd.read_csv("time_step_viscosity_points.csv")
fast = nu_points[nu_points.setting == nu_rows.setting[nu_rows.viscosity == 2.8e5].iloc[0]]
left.plot(fast.porosity, fast.mean_tortuosity - fast.paper_tortuosity, "k-", lw=2, label="the defaults (exponential, 6e-06, ν = 2.8e5)")
left.axhspan(-0.03, 0.03, color="0.9", label="within 0.03")
left.axhline(0, color="k", lw=0.8)
left.set_xlabel("porosity φ")
left.set_ylabel("⟨T⟩ − paper's f(φ)  (bars: SE over media)")
left.legend(fontsize=7)
right.plot(rows.dt, rows.rms_distance, "o-", label="rms distance from f(φ)")
right.set_xlabel("time step δt")
right.set_ylabel("rms distance from f(φ)")
twin = right.twinx()
twin.plot(rows.dt, rows.seconds, "s--", color="C1", label="seconds for 24 000 droplets")
twin.set_ylabel("seconds for 24 000 droplets (2 cores)")
handles = right.get_legend_handles_labels()[0] + twin.get_legend_handles_labels()[0]
right.legend(handles=handles, loc="upper center", fontsize=7)
fig.suptitle("the explicit droplet's continuous viscosity, exponential step: 200 overlapping media × 20 droplets a porosity",
             fontsize=9)
fig.tight_layout()
fig.savefig("time_step.png", dpi=110)
PY
