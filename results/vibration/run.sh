#!/usr/bin/env bash
# Does shaking the medium free trapped droplets, and what does it do to T? The default droplet on
# overlapping media at porosities 0.5, 0.6 and 0.7, shaken along x from the moment each droplet
# first comes to rest. Every setting runs the same droplets on the same media (the sweep's
# held-out stream), so each droplet is compared with itself unshaken.
#   1. grid.csv: amplitudes 0.5 to 8 and frequencies 50 to 400, on the media of seed 9001
#      (20 a porosity, 20 droplets each);
#   2. confirm.csv: two settings chosen on step 1 at porosity 0.7, the gentlest that halves the
#      stuck fraction (least peak velocity 2 pi f A) along x, y and xy, and the one with the fewest
#      stuck, on fresh media (seed 9002, 40 a porosity, 20 droplets each), beside no shaking;
#   3. route.csv: T and the route's T (the path once a shaking period) under both settings, from
#      `simulate` on 20 more media a porosity (medium seeds 9301 to 9320);
#   4. figure.py draws stuck.png and tortuosity.png from grid.csv.
# About 30 minutes on 2 cores.
#     bash results/vibration/run.sh
set -euo pipefail
cd "$(dirname "$0")"
BIN=${SOFTDROP:-../../build/softdrop}
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
sweep() {  # db seed media amplitude frequency axis
  "$BIN" sweep --porosities 0.5,0.6,0.7 --media "$3" --droplets 20 --seed "$2" \
    --vibration-amplitude "$4" --vibration-frequency "$5" --vibration-axis "$6" --db "$1" --quiet > /dev/null
}
sweep "$tmp/grid_0_0_x.db" 9001 20 0 0 x
for f in 50 100 200 400; do
  for a in 0.5 1 2 4 8; do
    sweep "$tmp/grid_${a}_${f}_x.db" 9001 20 "$a" "$f" x
  done
done
/usr/bin/python3 summarize.py grid "$tmp" > grid.csv
read -r gentle_a gentle_f < <(/usr/bin/python3 summarize.py gentlest grid.csv 0.7)
read -r most_a most_f < <(/usr/bin/python3 summarize.py fewest grid.csv 0.7)
sweep "$tmp/confirm_0_0_x.db" 9002 40 0 0 x
for axis in x y xy; do
  sweep "$tmp/confirm_${gentle_a}_${gentle_f}_${axis}.db" 9002 40 "$gentle_a" "$gentle_f" "$axis"
done
sweep "$tmp/confirm_${most_a}_${most_f}_x.db" 9002 40 "$most_a" "$most_f" x
/usr/bin/python3 summarize.py confirm "$tmp" > confirm.csv
for phi in 0.5 0.6 0.7; do
  for m in $(seq 9301 9320); do
    for setting in "0 0" "$gentle_a $gentle_f" "$most_a $most_f"; do
      read -r a f <<< "$setting"
      "$BIN" simulate --porosity "$phi" --medium-seed "$m" --droplets 20 --seed "$m" --quiet \
        --vibration-amplitude "$a" --vibration-frequency "$f" --runs "$tmp/route_${phi}_${m}_${a}_${f}.csv" > /dev/null
    done
  done
done
/usr/bin/python3 summarize.py route "$tmp" > route.csv
/usr/bin/python3 figure.py
cat grid.csv confirm.csv route.csv
