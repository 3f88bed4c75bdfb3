#!/usr/bin/env bash
# Droplets whose springs carry the tension, at the full calibration size (6 porosities x 10
# overlapping media x 20 droplets, area traces at phi = 0.79, the resting test), against the
# paper's <T>(phi); and the balloon on grains twice as large. About 7 minutes on 2 cores.
#
# Every length of a tension-carrying droplet is S times the default droplet's: radius 8 S, box
# 500 S, contact depth 0.5 S, stuck distance 5 S, grains G1 S to G2 S (8 S to 16 S as the defaults'
# grains, or 16 S to 32 S); the stuck window is 0.5 sqrt(S) (with g fixed, times grow as sqrt(S)) and
# the resting test runs at --rest-scale S. The gas holds the springs at 5 % strain at rest, m = 1.
# The contacts follow the model's similarity: k_c = 2e8 / S and c_c = 2e4 / sqrt(S), the defaults'
# contacts seen at S times the size; so does the time step, dt = 1e-5 sqrt(S), which keeps the
# steps a droplet near the defaults'. Internal viscosity nu spares the breathing mode
# (viscosity-dilation = 0) unless a setting says otherwise.
#
# Each group is one `softdrop calibrate` command writing tension/S_G1_G2_TAG.csv and
# tension/S_G1_G2_TAG_points.csv; plot_tension.py joins them into tension.csv, tension_points.csv and
# tension.png. SOFTDROP=path runs another build.
#
#     bash results/calibration/tension.sh
set -euo pipefail
cd "$(dirname "$0")"
BIN=${SOFTDROP:-../../build/softdrop}  # every group starts from balloon.toml (the paper's k_s, k_d and dt)
# The study ran with the stuck test alone (--rest-window 0), which its stuck fractions reflect.
mkdir -p tension

# group S G1 G2 TAG SETTING...: the settings ("label: name=value ...") of one scale and grain range,
# written to tension/S_G1_G2_TAG.csv.
group() {
  local scale=$1 g1=$2 g2=$3 tag=$4
  shift 4
  local radius nrt window depth stuck box kc cc dt
  # nRT for 5 % spring strain at rest (Laplace: k_s strain l0 = P R_rest), as scaled.py's nrt_for.
  read -r radius nrt window depth stuck box kc cc dt <<< "$(awk -v s="$scale" 'BEGIN {
    pi = atan2(0, -1); n = 24; ks = 119755; strain = 0.05; limit = 0.1; r = 8 * s
    l0 = 2 * r * sin(pi / n) / (1 + limit); rest = r * (1 + strain) / (1 + limit)
    printf "%.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g %.17g\n", r, pi * rest * ks * strain * l0,
      0.5 * sqrt(s), 0.5 * s, 5 * s, 500 * s, 2e8 / s, 2e4 / sqrt(s), 1e-5 * sqrt(s) }')"
  local settings=()
  for s in "$@"; do settings+=(--setting "$s"); done
  echo "tension.sh: S = $scale, grains $g1 S to $g2 S, $# settings" >&2
  "$BIN" --config balloon.toml calibrate --format csv --quiet --rest-window 0 "${settings[@]}" \
    --nrt "$nrt" --kc "$kc" --cc "$cc" --dt "$dt" --viscosity 0 --viscosity-dilation 0 \
    --width "$box" --height "$box" --radius "$radius" \
    --r-min "$(awk -v s="$scale" -v g="$g1" 'BEGIN { printf "%.17g", g * s }')" \
    --r-max "$(awk -v s="$scale" -v g="$g2" 'BEGIN { printf "%.17g", g * s }')" \
    --max-depth "$depth" --stuck-distance "$stuck" --stuck-window "$window" \
    --max-steps 100000000 --rest-scale "$scale" \
    --csv "tension/${scale}_${g1}_${g2}_${tag}.csv" --points "tension/${scale}_${g1}_${g2}_${tag}_points.csv" > /dev/null
}

# The time step: the same droplet at the paper's dt, at 14.5 and at 29 times it (S = 840, nu = 800).
group 840 8 16 dt "dt 2e-5: viscosity=800 dt=2e-5" "dt 2.9e-4: viscosity=800 dt=2.9e-4" \
  "dt 5.8e-4: viscosity=800 dt=5.8e-4"
# The scale, and nu, on the defaults' grains (nu dt <= 0.5 bounds nu).
group 2500 8 16 nu "nu 0: viscosity=0" "nu 100: viscosity=100" "nu 300: viscosity=300" "nu 900: viscosity=900"
group 8400 8 16 nu "nu 0: viscosity=0" "nu 30: viscosity=30" "nu 100: viscosity=100" "nu 500: viscosity=500" \
  "nu 100, breathing damped: viscosity=100 viscosity-dilation=1"
# Grains 2, 2.5 and 3 times as large against the droplet: the box is 10, 8 and 7 mean grain diameters
# deep (on the defaults' grains, 21).
group 8400 16 32 nu "nu 20: viscosity=20" "nu 30: viscosity=30" "nu 45: viscosity=45" "nu 100: viscosity=100" \
  "nu 500: viscosity=500"
# Elastic contacts (c_c = 0) and a stiffer shape (nu up to 2 000; nu dt <= 0.5 takes a smaller dt).
group 8400 16 32 elastic "nu 300, c_c 0: viscosity=300 cc=0" "nu 500, c_c 0: viscosity=500 cc=0" \
  "nu 1000, c_c 0: viscosity=1000 cc=0 dt=4.58e-4" "nu 2000, c_c 0: viscosity=2000 cc=0 dt=2.4e-4"
# Around the closest: a little contact damping, and nu between.
group 8400 16 32 around "nu 700, c_c 0: viscosity=700 cc=0 dt=4.58e-4" \
  "nu 700, c_c 50: viscosity=700 cc=50 dt=4.58e-4" "nu 1000, c_c 50: viscosity=1000 cc=50 dt=4.58e-4" \
  "nu 1000, c_c 100: viscosity=1000 cc=100 dt=4.58e-4"
# Grains of radii 16 S to 48 S, a wider spread: elastic contacts, a stiff shape.
group 8400 16 48 elastic "nu 1000, c_c 0: viscosity=1000 cc=0 dt=4.58e-4" \
  "nu 1500, c_c 0: viscosity=1500 cc=0 dt=3.2e-4" "nu 2000, c_c 0: viscosity=2000 cc=0 dt=2.4e-4"
group 8400 20 40 nu "nu 30: viscosity=30"
group 8400 24 48 nu "nu 30: viscosity=30"

# The balloon on grains 16 to 32, with less viscosity.
echo "tension.sh: the balloon on grains 16 to 32" >&2
"$BIN" --config balloon.toml calibrate --format csv --quiet --rest-window 0 --r-min 16 --r-max 32 --scan viscosity=1500,2000,3000 \
  --csv tension/balloon_16_32_nu.csv --points tension/balloon_16_32_nu_points.csv > /dev/null
/usr/bin/python3 plot_tension.py
