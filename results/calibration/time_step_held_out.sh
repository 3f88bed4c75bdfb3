#!/usr/bin/env bash
# Is <T>(phi) converged in the time step? Three droplets, each at its time step and at half of it,
# on media no calibration saw: 10 porosities (0.45 to 0.9) x 100 overlapping media x 40 droplets,
# the same media and starts for every run (seed 55501 of the calibration stream of media seeds,
# which no calibration used: they use seeds 1 and 2). The droplets:
#   defaults     the implicit viscosity step, nu = 1.37e5 (the explicit droplet's), dt = 6e-6
#                (and 3e-6)
#   exponential  exponential.toml: the exponential step, nu = 2.8e5, dt = 6e-6 (and 3e-6)
#   explicit-nu  the exponential step with the explicit droplet's continuous nu, 1.8656e5, at
#                dt = 3.5e-6 (and 1.75e-6)
# Writes time_step_held_out_points.csv (one row per run and porosity, sweep-report's columns) and
# time_step_held_out.csv (one row per droplet and porosity: <T> at dt and dt/2, their difference
# with its error, and the per-medium paired difference). About 100 minutes on 2 cores.
# SOFTDROP=path runs another build.
#     bash results/calibration/time_step_held_out.sh
set -euo pipefail
cd "$(dirname "$0")"
BIN=${SOFTDROP:-../../build/softdrop}
mkdir -p time_step_held_out
P=0.45,0.5,0.55,0.6,0.65,0.7,0.75,0.8,0.85,0.9
run() {  # name, dt, droplet options...
  local name=$1 dt=$2
  shift 2
  "$BIN" sweep --db "time_step_held_out/$name.db" --media-stream calibration --seed 55501 --porosities $P \
    --media 100 --droplets 40 --dt "$dt" "$@" --quiet --format csv > /dev/null
  report "$name"
}
report() {  # name
  "$BIN" sweep-report --db "time_step_held_out/$1.db" --format csv > "time_step_held_out/$1.csv"
  "$BIN" sweep-report --db "time_step_held_out/$1.db" --media --format csv > "time_step_held_out/$1-media.csv"
}
run defaults-6e-6 6e-6
run defaults-3e-6 3e-6
run exponential-6e-6 6e-6 --viscosity-step exponential --viscosity 2.8e5
run exponential-3e-6 3e-6 --viscosity-step exponential --viscosity 2.8e5
run explicit-nu-3.5e-6 3.5e-6 --viscosity-step exponential --viscosity 1.8656e5
run explicit-nu-1.75e-6 1.75e-6 --viscosity-step exponential --viscosity 1.8656e5
# Where fewest droplets pass, 300 more media for the defaults (seed 55502): porosities 0.45 and 0.5.
for dt in 6e-6 3e-6; do
  "$BIN" sweep --db "time_step_held_out/defaults-more-$dt.db" --media-stream calibration --seed 55502 \
    --porosities 0.45,0.5 --media 300 --droplets 40 --dt "$dt" --quiet --format csv > /dev/null
  report "defaults-more-$dt"
done
# And at dt / 4 where the defaults move most, porosity 0.45.
"$BIN" sweep --db time_step_held_out/defaults-more-1.5e-6.db --media-stream calibration --seed 55502 \
  --porosities 0.45 --media 300 --droplets 40 --dt 1.5e-6 --quiet --format csv > /dev/null
report defaults-more-1.5e-6
/usr/bin/python3 time_step_held_out.py
