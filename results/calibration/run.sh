#!/usr/bin/env bash
# Regenerates results/calibration/: the droplet's free parameters scanned against the paper's
# <T>(phi) (about 6 minutes on 2 cores). Every stage is one `softdrop calibrate` command; each
# writes a settings CSV (one row per setting; the ranking goes to stdout) and a points CSV (one row
# per setting and porosity). SOFTDROP=path runs another build.
set -euo pipefail
cd "$(dirname "$0")"
# Every stage starts from the balloon (balloon.toml), the droplet this study calibrated; the setting
# labelled "defaults" in its CSVs is the balloon. The study ran with the stuck test alone
# (--rest-window 0), which its stuck fractions and step counts reflect.
S="${SOFTDROP:-../../build/softdrop} --config balloon.toml"
Q="--quiet --format csv --rest-window 0"
SMALL="--media 6 --droplets 15 --trace-media 2 --trace-droplets 5"
# The droplet before calibration, for comparison.
BEFORE="before calibration: masses=40 mass=1 radius=10 nrt=6e8 kc=1e8 cc=1e4 viscosity=1e4"

# 1. Springs carrying the tension: few, light masses (k_d dt / m <= 1 needs m >= 0.0073; the weight
#    N m g must stay below what the springs hold), the gas at 1-5 % spring strain.
$S calibrate $Q --mass 0.015 --kc 9e6 --cc 700 --scan masses=10,12,16 --scan nrt=3e5,9e5 \
  --scan viscosity=0,300 --media 2 --droplets 10 --csv springs.csv --points springs_points.csv > /dev/null

# 2. The broad grid: the gas holds the ring at its stretch limit (a balloon).
$S calibrate $Q $SMALL --kc 2e8 --cc 2e4 --scan radius=5.5,8,10 --scan masses=24,30,40 \
  --scan nrt=6e8,1.5e9 --scan viscosity=1500,3000,5000 --csv grid.csv --points grid_points.csv > /dev/null

# 3. Around the chosen setting, at the full size (6 porosities x 10 media x 20 droplets).
$S calibrate $Q --scan nrt=1.2e9,1.5e9,1.8e9 --scan viscosity=2500,3000,3500 \
  --csv refine.csv --points refine_points.csv > /dev/null

# 4. A droplet that never comes to rest (its gas pushes each mass hard every step, and the ring
#    buzzes against its contacts) beside the same droplet with less gas: its T is longer by the buzz.
$S calibrate $Q $SMALL --setting "masses=30 mass=0.5 radius=5.5 nrt=4e8 viscosity=5000" \
  --setting "masses=30 mass=0.5 radius=5.5 nrt=1.1e9 viscosity=5000" \
  --setting "masses=30 mass=0.5 radius=5.5 nrt=6e8 viscosity=5000" --csv buzz.csv --points buzz_points.csv > /dev/null

# 5. How much internal viscosity the defaults need, and what less of it does.
$S calibrate $Q $SMALL --scan viscosity=0,500,1000,2000,3000 --csv viscosity.csv \
  --points viscosity_points.csv > /dev/null

# 6. Passage at low porosity against the depth of the medium (in grain diameters): the same droplet
#    through boxes 500 wide and 500, 250 and 125 high.
for h in 500 250 125; do
  $S calibrate $Q $SMALL --porosities 0.5,0.6,0.7 --height $h --trace-media 0 --csv depth_$h.csv \
    --points depth_${h}_points.csv > /dev/null
done

# 7. The defaults against the droplet before calibration, at the full size, drawn against the
#    paper's curve.
$S calibrate --format csv --rest-window 0 --setting defaults --setting "$BEFORE" --csv final.csv --points final_points.csv \
  --plot final.png --best 2 > final_ranked.csv
